// Frame rate of `voxcd view` for a large recording in Debian's headless chromium (bench/view_fps.sh runs it):
// the page's own work per frame (setFrame: every body's matrix and colour, the contacts), and the rendered frames
// per second with a new recorded frame every rendered frame, and with none. Usage:
//   node view_fps.js VOXCD WORK OBJECTS FRAMES WIDTHxHEIGHT SECONDS DETAIL SCALE   (meshes or spheres; 1 or 0.5)
'use strict';

const { spawn, execFileSync } = require('child_process');
const fs = require('fs');
const path = require('path');
const puppeteer = require('puppeteer-core');
const lib = require(path.join(__dirname, '..', 'tests', 'view', 'view_lib.js'));

const [, , VOXCD, WORK, OBJECTS, FRAMES, SIZE, SECONDS, DETAIL, SCALE] = process.argv;
const median = (v) => { const s = [...v].sort((a, b) => a - b); return s.length ? s[Math.floor(s.length / 2)] : NaN; };

function serve(file) {
  return new Promise((resolve, reject) => {
    const p = spawn(VOXCD, ['view', file, '--port', '0', '--timeout', '900'], { stdio: ['ignore', 'pipe', 'inherit'] });
    let out = '';
    p.stdout.on('data', (d) => { out += d; const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//); if (m) resolve({ p, url: m[0] }); });
    p.on('exit', (c) => reject(new Error('voxcd view exited ' + c)));
  });
}

// Rendered frames per second over `seconds`, from the page's animation frame times (median interval).
async function fps(page, seconds, advance) {
  await page.evaluate((advance) => {
    const v = window.voxcdView;
    v.view.advance = advance;
    if (!v.view.hooked) {
      v.view.hooked = true;
      v.view.stage.onFrame.push(() => { if (v.view.advance) v.view.setFrame((v.view.frame + 1) % v.view.rec.frames.length); });
    }
    v.frameTimes.length = 0;
  }, advance);
  await new Promise((r) => setTimeout(r, seconds * 1000));
  const t = await page.evaluate(() => window.voxcdView.frameTimes.slice());
  const d = t.slice(1).map((x, i) => x - t[i]);
  return { fps: 1000 / median(d), frames: t.length };
}

(async () => {
  fs.mkdirSync(WORK, { recursive: true });
  const run = path.join(WORK, 'fps_' + OBJECTS + '.vxr');
  if (!fs.existsSync(run)) execFileSync(VOXCD, ['simulate', '--objects', OBJECTS, '--frames', FRAMES, '--record', run, '--no-progress'],
    { stdio: 'ignore' });
  const { p, url } = await serve(run);
  const browser = await lib.launch(puppeteer, fs.mkdtempSync(path.join(WORK, 'profile-')));
  try {
    const page = await browser.newPage();
    const [w, h] = SIZE.split('x').map(Number);
    await page.setViewport({ width: w, height: h });
    await page.goto(url);
    await page.waitForFunction(() => window.voxcdView.ready, { timeout: 600000 });
    await page.evaluate((d, s) => { window.voxcdView.view.setDetail(d); window.voxcdView.view.setScale(s); }, DETAIL, +SCALE);
    const bodies = await page.evaluate(() => window.voxcdView.view.drawnBodies());
    const work = await page.evaluate(() => {
      const v = window.voxcdView.view, t = [];
      for (let k = 0; k < 3 * v.rec.frames.length; ++k) {
        const t0 = performance.now();
        v.setFrame(k % v.rec.frames.length);
        t.push(performance.now() - t0);
      }
      return t;
    });
    const still = await fps(page, +SECONDS, false);
    const moving = await fps(page, +SECONDS, true);
    const viewport = await page.evaluate(() => [window.innerWidth, window.innerHeight]);
    const canvas = await page.evaluate(() => { const c = document.querySelector('#viewport canvas'); return [c.width, c.height]; });
    console.log('| ' + bodies + ' | ' + DETAIL + ' | ' + (+SCALE === 1 ? 'full' : 'half') + ' | ' + median(work).toFixed(1) + ' ms | ' + moving.fps.toFixed(1) + ' (' + moving.frames +
      ' frames) | ' + still.fps.toFixed(1) + ' | ' + canvas.join('x') + ' canvas in a ' + viewport.join('x') + ' page | ' +
      (await browser.version()) + ', SwiftShader (software WebGL) |');
  } finally {
    await browser.close();
    p.kill();
  }
})().catch((e) => { console.error(e); process.exit(1); });
