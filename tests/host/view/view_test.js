// The browser tests of `voxcd view` (tests/host/view/CMakeLists.txt): Debian's chromium, headless with software WebGL,
// driven through the DevTools protocol by puppeteer-core, loads the page the tool serves (or writes with --html) and
// checks what it draws against the tool's own output. Usage:
//   node view_test.js CASE VOXCD WORK SHOTS    CASE: recording, live, object, sparse, pair or html
// Prints "N passed, M failed" and exits non-zero on any failure.
'use strict';

const { spawn, execFileSync } = require('child_process');
const fs = require('fs');
const path = require('path');
const puppeteer = require('puppeteer-core');
const lib = require('./view_lib.js');

const [, , CASE, VOXCD, WORK, SHOTS] = process.argv;
let passed = 0, failed = 0;

function check(ok, what) {
  if (ok) passed++;
  else failed++;
  console.log((ok ? 'ok:   ' : 'FAIL: ') + what);
}

function voxcd(...args) {
  return execFileSync(VOXCD, args, { encoding: 'utf8', maxBuffer: 1 << 28 });
}

// Starts `voxcd view ARGS --port 0` and resolves with {proc, url} once it prints its URL.
function serve(args) {
  return new Promise((resolve, reject) => {
    const proc = spawn(VOXCD, ['view', ...args, '--port', '0', '--timeout', '300'], { stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    const fail = (why) => reject(new Error('voxcd view ' + args.join(' ') + ': ' + why + '\n' + out));
    proc.stdout.on('data', (d) => {
      out += d;
      const m = out.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (m) resolve({ proc, url: m[0] });
    });
    proc.stderr.on('data', (d) => { out += d; });
    proc.on('exit', (code) => fail('exited ' + code + ' before printing its URL'));
    setTimeout(() => fail('printed no URL in 120 s'), 120000);
  });
}

// [status, body] of a GET, outside the page (so that a refusal is not a console error of the page's).
function get(url) {
  return new Promise((resolve, reject) => {
    require('http').get(url, (res) => {
      let body = '';
      res.on('data', (d) => { body += d; });
      res.on('end', () => resolve([res.statusCode, body]));
    }).on('error', reject);
  });
}

// Opens `url` with the console and page errors collected; waits until the page says it is ready.
async function open(browser, url) {
  const page = await browser.newPage();
  await page.setViewport({ width: 720, height: 520 });
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('requestfailed', (r) => errors.push('request failed: ' + r.url()));
  page.on('request', (r) => {
    const u = r.url();
    if (!u.startsWith('http://127.0.0.1') && !u.startsWith('file://') && !u.startsWith('data:'))
      errors.push('fetched from outside: ' + u);
  });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => window.voxcdView && (window.voxcdView.ready || window.voxcdView.errors.length),
    { timeout: 120000 });
  return { page, errors };
}

// Renders a few animation frames, then saves a screenshot and checks that it is not blank.
async function shot(page, name) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: path.join(SHOTS, name) });
  const s = lib.pngStats(Buffer.from(await (await page.$('#viewport')).screenshot()));
  check(s.changed > 0.03 && s.colours > 20, name + ': the view is not blank (' +
    (100 * s.changed).toFixed(1) + '% of pixels differ from the background, ' + s.colours + ' colours)');
}

async function recordingCase(browser) {
  const run = path.join(WORK, 'run.vxr');
  voxcd('simulate', '--objects', '64', '--density', '0.1', '--frames', '20', '--seed', '3', '--record', run,
    '--no-progress');
  const rec = lib.readRecording(fs.readFileSync(run));
  check(rec.frames.length === 20, 'the recording has 20 frames (' + rec.frames.length + ')');
  const { proc, url } = await serve([run]);
  try {
    const { page, errors } = await open(browser, url);
    const v = (f) => page.evaluate(f);
    check(await v(() => window.voxcdView.kind === 'recording'), 'the page shows a recording');
    check(await v(() => window.voxcdView.view.drawnBodies()) === rec.bodies,
      'bodies drawn = bodies recorded (' + rec.bodies + ')');
    let withContacts = 0;
    for (let i = 0; i < rec.frames.length; ++i) {
      const drawn = await page.evaluate((i) => { window.voxcdView.view.setFrame(i); return window.voxcdView.view.drawnContacts(); }, i);
      if (drawn !== rec.frames[i].contacts) check(false, 'frame ' + i + ': contacts drawn ' + drawn + ' = recorded ' + rec.frames[i].contacts);
      withContacts += rec.frames[i].contacts > 0;
    }
    check(withContacts > 0, 'contacts drawn = contacts recorded in every frame (' + withContacts + ' frames have contacts)');
    await sliderMoves(page, rec);
    await picking(page);
    await playing(page);
    await page.select('#controls select:nth-of-type(2)', 'spheres');
    check(await v(() => window.voxcdView.view.detail === 'spheres' && window.voxcdView.view.drawnBodies()) === rec.bodies,
      'bodies drawn as spheres = bodies recorded');
    await shot(page, 'view_scene_spheres.png');
    await page.select('#controls select:nth-of-type(2)', 'meshes');
    await shot(page, 'view_scene.png');
    check(errors.length === 0 && (await v(() => window.voxcdView.errors.length)) === 0,
      'no console error (' + errors.concat(await v(() => window.voxcdView.errors)).join('; ') + ')');
  } finally {
    proc.kill();
  }
}

// The frame slider, moved as a user moves it (keyboard on the focused slider), changes the drawn poses to the frame's.
async function sliderMoves(page, rec) {
  const body = 5;
  await page.evaluate(() => window.voxcdView.view.setFrame(0));
  const before = await page.evaluate((b) => window.voxcdView.view.bodyMatrix(b), body);
  await page.focus('#controls input[type=range]');
  await page.keyboard.press('End');
  const frame = await page.evaluate(() => window.voxcdView.view.frame);
  const after = await page.evaluate((b) => window.voxcdView.view.bodyMatrix(b), body);
  const last = rec.frames[rec.frames.length - 1].positions[body];
  check(frame === rec.frames.length - 1, 'the slider moved to the last frame (' + frame + ')');
  check(after.slice(12, 15).some((x, k) => x !== before[12 + k]), 'the slider changed the drawn pose of body ' + body);
  check(after.slice(12, 15).every((x, k) => Math.fround(x) === last[k]),
    'the drawn pose is the recorded one (' + after.slice(12, 15) + ' vs ' + last + ')');
}

// Play advances the frames (at 30 recorded frames a second times the speed); pause stops them.
async function playing(page) {
  await page.evaluate(() => window.voxcdView.view.setFrame(0));
  await page.select('#controls select', '4');
  await page.click('#controls button');
  await page.waitForFunction(() => window.voxcdView.view.frame >= 5, { timeout: 20000 });
  await page.click('#controls button');
  const stopped = await page.evaluate(() => window.voxcdView.view.frame);
  await new Promise((r) => setTimeout(r, 300));
  check(!(await page.evaluate(() => window.voxcdView.view.playing)) &&
    (await page.evaluate(() => window.voxcdView.view.frame)) === stopped,
    'play at 4x advanced the frames to ' + stopped + ', pause stopped them');
}

// A click on a body picks it: the side panel shows its pairs, contacts and history, and the view its path.
async function picking(page) {
  const xy = await page.evaluate(() => {
    const v = window.voxcdView.view, p = v.rec.frames[v.frame].poses, c = v.stage.camera;
    const r = v.stage.renderer.domElement.getBoundingClientRect();
    const s = new THREE.Vector3(p[0], p[1], p[2]).project(c);
    return [r.left + (s.x + 1) / 2 * r.width, r.top + (1 - s.y) / 2 * r.height];
  });
  await page.mouse.click(xy[0], xy[1]);
  const picked = await page.evaluate(() => window.voxcdView.view.picked);
  const side = await page.evaluate(() => document.getElementById('side').textContent);
  const path = await page.evaluate(() => window.voxcdView.view.path.geometry.attributes.position.count);
  check(picked >= 0 && side.includes('body ' + picked) && side.includes('touching in frames') && path === 20,
    'a click picks body ' + picked + ': its pairs, contacts and history are shown, its path has ' + path + ' points');
}

// A recording still being written: the page shows its whole frames, and its new ones once it follows the file.
async function liveCase(browser) {
  const run = path.join(WORK, 'whole.vxr'), live = path.join(WORK, 'live.vxr');
  voxcd('simulate', '--objects', '64', '--density', '0.1', '--frames', '20', '--seed', '3', '--record', run, '--no-progress');
  const bytes = fs.readFileSync(run), rec = lib.readRecording(bytes);
  const cut = rec.frameEnds[9] + 100;  // frames 0-9 whole, frame 10 begun
  fs.writeFileSync(live, bytes.subarray(0, cut));
  const { proc, url } = await serve([live]);
  try {
    const { page, errors } = await open(browser, url);
    const frames = () => page.evaluate(() => window.voxcdView.view.rec.frames.length);
    check(await frames() === 10, 'a recording cut inside frame 10 shows its 10 whole frames (' + await frames() + ')');
    await page.focus('#controls input[type=range]');
    await page.keyboard.press('End');  // at the last frame, the page keeps to the last frame as the file grows
    fs.appendFileSync(live, bytes.subarray(cut));
    const follow = await page.$$('#controls input[type=checkbox]');
    await follow[follow.length - 1].click();
    await page.waitForFunction(() => window.voxcdView.view.rec.frames.length === 20, { timeout: 20000 });
    check(await page.evaluate(() => window.voxcdView.view.frame) === 19, 'following the file, the page shows its new frames');
    check(errors.length === 0, 'no console error (' + errors.join('; ') + ')');
  } finally {
    proc.kill();
  }
}

async function objectCase(browser) {
  const mesh = '/usr/share/assimp/models/OBJ/spider.obj';
  const obj = path.join(WORK, 'spider.vox');
  voxcd('voxelize', mesh, '--resolution', '48', '-o', obj, '--distance-bits', '8');
  const info = JSON.parse(voxcd('info', obj, '--json'));
  const { proc, url } = await serve([obj]);
  try {
    const { page, errors } = await open(browser, url);
    const v = (f) => page.evaluate(f);
    check(await v(() => window.voxcdView.kind === 'object'), 'the page shows an object');
    const drawn = await v(() => [window.voxcdView.view.drawnShellPoints(), window.voxcdView.view.drawnSurfaceVoxels(),
      window.voxcdView.view.drawnInteriorVoxels()]);
    check(drawn[0] === info.shell_points, 'shell points drawn = the file\'s (' + drawn[0] + ' vs ' + info.shell_points + ')');
    check(drawn[1] === info.surface && drawn[2] === info.interior,
      'surface and interior voxels drawn = the file\'s (' + drawn.slice(1) + ' vs ' + info.surface + ', ' + info.interior + ')');
    const report = await v(() => window.voxcdView.view.d.report);
    check(report && report.input_triangles > 0, 'the repair report is shown (' + JSON.stringify(report).slice(0, 80) + ')');
    await v(() => { window.voxcdView.view.showSlices(true); });
    await shot(page, 'view_object.png');
    check(errors.length === 0, 'no console error (' + errors.join('; ') + ')');
  } finally {
    proc.kill();
  }
}

// A cube stored with a sparse distance field (its edges refined to level 1), then a rod longer than a dense voxmap
// (its voxmap and shell sparse, no states sent): the bricks drawn equal voxcd info's, per level.
async function sparseCase(browser) {
  const cube = path.join(WORK, 'cube.vox');
  voxcd('voxelize', 'cube', '--resolution', '24', '--storage', 'sparse', '--distance-bits', '8', '-o', cube);
  const info = JSON.parse(voxcd('info', cube, '--json'));
  let { proc, url } = await serve([cube]);
  try {
    const { page, errors } = await open(browser, url);
    const v = (f) => page.evaluate(f);
    const levels = await v(() => window.voxcdView.view.drawnDistanceBricks());
    check(JSON.stringify(levels) === JSON.stringify(info.distance.bricks_per_level) && levels[1] > 0,
      'distance bricks drawn per level = the file\'s (' + levels + ' vs ' + info.distance.bricks_per_level + ')');
    check(await v(() => window.voxcdView.view.drawnVoxmapBricks()) === 0, 'a dense voxmap\'s bricks start hidden');
    const side = await v(() => document.getElementById('side').textContent);
    check(side.includes('device memory') && side.includes('distance level 1'), 'the side panel shows the storage and '
      + 'the levels\' legend');
    await shot(page, 'view_object_sparse.png');
    check(errors.length === 0, 'no console error (' + errors.join('; ') + ')');
  } finally {
    proc.kill();
  }
  const obj = path.join(WORK, 'rod.obj'), rod = path.join(WORK, 'rod.vox');
  fs.writeFileSync(obj, 'v 0 0 0\nv 100 0 0\nv 0 1 0\nv 100 1 0\nv 0 0 1\nv 100 0 1\nv 0 1 1\nv 100 1 1\n' +
    'f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\nf 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n');
  const rodInfo = JSON.parse(voxcd('voxelize', obj, '--resolution', '1030', '--storage', 'sparse', '-o', rod,
    '--json'));
  ({ proc, url } = await serve([rod]));
  try {
    const { page, errors } = await open(browser, url);
    const v = (f) => page.evaluate(f);
    const drawn = await v(() => [window.voxcdView.view.drawnVoxmapBricks(),
      window.voxcdView.view.drawnSurfaceVoxels()]);
    check(rodInfo.dims[0] > 1024 && drawn[0] === rodInfo.storage.sparse.cells.brick && drawn[1] === 0,
      'a voxmap too large for its dense form: its bricks drawn, no voxels (' + drawn + ')');
    check(errors.length === 0, 'no console error (' + errors.join('; ') + ')');
  } finally {
    proc.kill();
  }
}

async function pairCase(browser) {
  const pose = (p) => JSON.parse(voxcd('pair', 'polytope36', 'stellated', '--pose', p, '--json')).results[0].contacts.length;
  const { proc, url } = await serve(['polytope36', 'stellated', '--pose', '0.6,0.2,0,0,0,30']);
  try {
    const { page, errors } = await open(browser, url);
    const first = await page.evaluate(() => window.voxcdView.view.drawnContacts());
    const want = pose('0.6,0.2,0,0,0,30');
    check(want > 0 && first === want, 'contacts drawn = voxcd pair\'s at the first pose (' + first + ' vs ' + want + ')');
    // Edit the pose as a user does: type a new tx and leave the field.
    await page.click('#controls input[type=number]', { clickCount: 3 });
    await page.keyboard.type('0.9');
    await page.keyboard.press('Tab');
    await page.waitForFunction(() => window.voxcdView.view.pose[0] === 0.9, { timeout: 60000 });
    const second = await page.evaluate(() => window.voxcdView.view.drawnContacts());
    const want2 = pose('0.9,0.2,0,0,0,30');
    check(second === want2 && want2 !== want, 'contacts recomputed by the tool at the edited pose (' + second + ' vs ' + want2 + ')');
    const bad = await get(url + 'api/pair?pose=1,x,3');
    check(bad[0] === 400 && bad[1] === "pose: 'x' in '1,x,3' is not a number",
      'a pose that is not numbers is refused with a message (' + bad + ')');
    await shot(page, 'view_pair.png');
    check(errors.length === 0, 'no console error (' + errors.join('; ') + ')');
  } finally {
    proc.kill();
  }
}

async function htmlCase(browser) {
  const run = path.join(WORK, 'small.vxr'), html = path.join(WORK, 'run.html');
  voxcd('simulate', '--objects', '32', '--frames', '5', '--record', run, '--no-progress');
  voxcd('view', run, '--html', html);
  const text = fs.readFileSync(html, 'utf8');
  check(!/<script[^>]*\ssrc=/.test(text), 'the HTML file loads no script from elsewhere');
  const rec = lib.readRecording(fs.readFileSync(run));
  const page = await browser.newPage();
  await page.setOfflineMode(true);
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto('file://' + html);
  await page.waitForFunction(() => window.voxcdView && window.voxcdView.ready, { timeout: 120000 });
  check(await page.evaluate(() => window.voxcdView.view.drawnBodies()) === rec.bodies, 'offline: bodies drawn = recorded');
  check(errors.length === 0, 'offline: no console error (' + errors.join('; ') + ')');
}

(async () => {
  fs.mkdirSync(WORK, { recursive: true });
  fs.mkdirSync(SHOTS, { recursive: true });
  const browser = await lib.launch(puppeteer, fs.mkdtempSync(path.join(WORK, 'profile-')));
  try {
    const cases = { recording: recordingCase, live: liveCase, object: objectCase, sparse: sparseCase, pair: pairCase,
      html: htmlCase };
    if (!cases[CASE]) throw new Error('no case ' + CASE);
    await cases[CASE](browser);
  } catch (e) {
    check(false, String(e && e.stack || e));
  } finally {
    await browser.close();
  }
  console.log(passed + ' passed, ' + failed + ' failed');
  process.exit(failed ? 1 : 0);
})();
