// Shared by the browser tests and bench/view_fps.js: chromium as Debian installs it, a reader of recordings written
// from docs/view.md (independent of the page's), and what a screenshot holds.
'use strict';

const zlib = require('zlib');

// Debian's chromium, headless, with software WebGL (SwiftShader), nothing fetched, a fresh profile.
function launch(puppeteer, profile) {
  return puppeteer.launch({
    executablePath: process.env.VOXCD_CHROMIUM || '/usr/bin/chromium',
    headless: true,
    userDataDir: profile,
    args: ['--no-sandbox', '--disable-gpu', '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
      '--disable-background-networking', '--disable-component-update', '--disable-sync', '--no-first-run',
      '--disable-quic', '--disable-dev-shm-usage'],
  });
}

// The bodies and, per frame, the contact count and body positions of a recording (docs/view.md's layout).
function readRecording(b) {
  if (b.toString('latin1', 0, 8) !== 'VOXCDREC' || b.readUInt32LE(8) !== 1) throw new Error('not a version 1 recording');
  const out = { bodies: 0, frames: [], frameEnds: [] };
  for (let at = 16; at + 8 <= b.length;) {
    const kind = b.readUInt32LE(at), len = b.readUInt32LE(at + 4), p = at + 8;
    if (p + len + 4 > b.length) break;
    if (kind === 3) out.bodies = b.readUInt32LE(p);
    if (kind === 4) {
      const n = b.readUInt32LE(p + 168), positions = [];
      for (let i = 0; i < n; ++i) {
        const q = p + 172 + 28 * i;
        positions.push([b.readFloatLE(q), b.readFloatLE(q + 4), b.readFloatLE(q + 8)]);
      }
      const pairs = b.readUInt32LE(p + 172 + 28 * n);
      const contacts = b.readUInt32LE(p + 176 + 28 * n + 9 * pairs);
      out.frames.push({ contacts, positions, statsContacts: Number(b.readBigUInt64LE(p + 64)) });
      out.frameEnds.push(p + len + 4);
    }
    at = p + len + 4;
  }
  return out;
}

// A PNG's pixels (8-bit RGB or RGBA, not interlaced): the fraction that differ from the page's background
// (#1d2026) and the number of distinct colours (5 bits a channel).
function pngStats(png) {
  let at = 8, w = 0, h = 0, type = 0;
  const idat = [];
  while (at < png.length) {
    const len = png.readUInt32BE(at), name = png.toString('latin1', at + 4, at + 8), data = png.subarray(at + 8, at + 8 + len);
    if (name === 'IHDR') { w = data.readUInt32BE(0); h = data.readUInt32BE(4); type = data[9]; }
    if (name === 'IDAT') idat.push(data);
    at += 12 + len;
  }
  const bpp = type === 6 ? 4 : 3, raw = zlib.inflateSync(Buffer.concat(idat)), stride = w * bpp;
  const px = Buffer.alloc(h * stride);
  for (let y = 0; y < h; ++y) {
    const f = raw[y * (stride + 1)], row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; ++x) {
      const a = x >= bpp ? px[y * stride + x - bpp] : 0, b = y ? px[(y - 1) * stride + x] : 0;
      const c = x >= bpp && y ? px[(y - 1) * stride + x - bpp] : 0;
      const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c);
      const pred = [0, a, b, (a + b) >> 1, pa <= pb && pa <= pc ? a : pb <= pc ? b : c][f];
      px[y * stride + x] = (row[x] + pred) & 255;
    }
  }
  let changed = 0;
  const colours = new Set();
  for (let i = 0; i < w * h; ++i) {
    const r = px[i * bpp], g = px[i * bpp + 1], bl = px[i * bpp + 2];
    if (Math.abs(r - 0x1d) + Math.abs(g - 0x20) + Math.abs(bl - 0x26) > 24) changed++;
    colours.add((r >> 3) << 10 | (g >> 3) << 5 | (bl >> 3));
  }
  return { width: w, height: h, changed: changed / (w * h), colours: colours.size };
}

module.exports = { launch, readRecording, pngStats };
