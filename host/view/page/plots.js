// Line plots of per-frame values under the view, with the current frame marked; a click picks a frame.
'use strict';

class VoxcdPlot {
  // series: [{name, color, values}] of equal length; onPick(frame) when the plot is clicked.
  constructor(parent, title, unit, series, onPick) {
    this.canvas = document.createElement('canvas');
    parent.appendChild(this.canvas);
    this.title = title;
    this.unit = unit;
    this.series = series;
    this.cursor = 0;
    this.canvas.addEventListener('click', (e) => {
      const n = this.length();
      if (n < 1) return;
      const r = this.canvas.getBoundingClientRect();
      onPick(Math.max(0, Math.min(n - 1, Math.round((e.clientX - r.left - 4) / (r.width - 8) * (n - 1)))));
    });
  }

  length() { return this.series.length ? this.series[0].values.length : 0; }

  setSeries(series) { this.series = series; this.draw(this.cursor); }

  draw(cursor) {
    this.cursor = cursor;
    const c = this.canvas, w = c.clientWidth, h = c.clientHeight;
    if (c.width !== w || c.height !== h) { c.width = w; c.height = h; }
    const g = c.getContext('2d');
    g.fillStyle = '#1d2026';
    g.fillRect(0, 0, w, h);
    const n = this.length();
    let top = 0;
    for (const s of this.series) for (const v of s.values) top = Math.max(top, v);
    top = top > 0 ? top * 1.1 : 1;
    const x = (i) => 4 + (n > 1 ? i / (n - 1) : 0.5) * (w - 8);
    const y = (v) => h - 4 - v / top * (h - 34);
    for (const s of this.series) {
      g.strokeStyle = s.color;
      g.beginPath();
      for (let i = 0; i < n; ++i) i ? g.lineTo(x(i), y(s.values[i])) : g.moveTo(x(i), y(s.values[i]));
      g.stroke();
    }
    g.strokeStyle = '#fff';
    g.beginPath();
    g.moveTo(x(cursor), 28);
    g.lineTo(x(cursor), h);
    g.stroke();
    this.legend(g, cursor, top);
  }

  legend(g, cursor, top) {
    g.font = '11px sans-serif';
    g.fillStyle = '#aab';
    g.fillText(this.title + ' (' + this.unit + ', top ' + top.toPrecision(3) + ')', 4, 11);
    let at = 4;
    for (const s of this.series) {
      const v = s.values[cursor];
      const text = s.name + ' ' + (v === undefined ? '' : +v.toPrecision(4));
      g.fillStyle = s.color;
      g.fillText(text, at, 24);
      at += g.measureText(text).width + 10;
    }
  }
}
