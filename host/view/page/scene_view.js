// A recorded run: every body drawn instanced with its type's mesh, coloured by state; contacts as points with
// normals; a frame slider, play/pause and speed; a picked body's pairs, contacts and history; plots of the run.
'use strict';

const VOXCD_COLOURS = { free: [0.45, 0.58, 0.72], pair: [0.93, 0.78, 0.30], touching: [0.95, 0.30, 0.25],
  picked: [0.35, 0.95, 0.45] };

// A Lambert material whose colour is multiplied by a per-instance attribute `icolor` (three.js r111 has none).
function voxcdInstanceMaterial() {
  const m = new THREE.MeshLambertMaterial({ color: 0xffffff });
  m.onBeforeCompile = (s) => {
    s.vertexShader = s.vertexShader
      .replace('#include <common>', '#include <common>\nattribute vec3 icolor;\nvarying vec3 vIColor;')
      .replace('#include <begin_vertex>', '#include <begin_vertex>\nvIColor = icolor;');
    s.fragmentShader = s.fragmentShader
      .replace('#include <common>', '#include <common>\nvarying vec3 vIColor;')
      .replace('vec4 diffuseColor = vec4( diffuse, opacity );', 'vec4 diffuseColor = vec4( diffuse * vIColor, opacity );');
  };
  return m;
}

// Bodies as lit spheres of their bounding radius, one point each: what software rendering can draw at 30 frames per
// second for tens of thousands of bodies (docs/view.md, "Large runs"), where a mesh per body cannot.
function voxcdSphereMaterial() {
  return new THREE.ShaderMaterial({
    uniforms: { scale: { value: 1 } },
    vertexShader: `attribute vec3 bcolor; attribute float radius; uniform float scale; varying vec3 vColor;
      void main() {
        vec4 mv = modelViewMatrix * vec4(position, 1.0);
        gl_Position = projectionMatrix * mv;
        gl_PointSize = max(2.0, 2.0 * scale * radius / -mv.z);
        vColor = bcolor;
      }`,
    fragmentShader: `varying vec3 vColor;
      void main() {
        vec2 p = gl_PointCoord * 2.0 - 1.0;
        float r2 = dot(p, p);
        if (r2 > 1.0) discard;
        vec3 n = vec3(p.x, -p.y, sqrt(1.0 - r2));
        gl_FragColor = vec4(vColor * (0.45 + 0.55 * max(0.0, dot(n, normalize(vec3(0.4, 0.6, 0.7))))), 1.0);
      }`,
  });
}

// Above this many bodies the page draws them as spheres by default (the "bodies as" menu changes it), and above
// VOXCD_HALF_ABOVE at half resolution (the "resolution" menu): software rendering is bound by the pixels it fills.
const VOXCD_SPHERES_ABOVE = 8192, VOXCD_HALF_ABOVE = 32768;

class VoxcdSceneView {
  constructor(stage, rec, data) {
    this.stage = stage;
    this.rec = rec;
    this.data = data;
    this.frame = 0;
    this.playing = false;
    this.speed = 1;
    this.picked = -1;
    this.state = new Uint8Array(rec.bodyTypes.length);  // 0 free, 1 in a broadphase pair, 2 touching
    this.makeBodies();
    this.makeSpheres();
    this.makeContacts();
    this.makeWorld();
    this.makeControls();
    this.makePlots();
    this.makePicking();
    stage.onFrame.push((t) => this.tick(t));
    this.setFrame(0);
    voxcdStatus(rec.bodyTypes.length + ' bodies of ' + rec.types.length + ' type(s), ' + rec.frames.length +
      ' frames' + (rec.truncated ? ' (' + rec.note + ')' : ''));
  }

  makeBodies() {
    const rec = this.rec, n = rec.bodyTypes.length;
    this.slot = new Uint32Array(n);  // each body's instance in its type's mesh
    const counts = rec.types.map(() => 0);
    for (let i = 0; i < n; ++i) this.slot[i] = counts[rec.bodyTypes[i]]++;
    this.meshes = rec.types.map((t, k) => {
      const g = VoxcdUtil.geometry(t.vertices, t.triangles);
      g.setAttribute('icolor', new THREE.InstancedBufferAttribute(new Float32Array(3 * counts[k]), 3));
      const m = new THREE.InstancedMesh(g, voxcdInstanceMaterial(), counts[k]);
      m.frustumCulled = false;  // the geometry's sphere is at the origin, the instances anywhere
      this.stage.scene.add(m);
      return m;
    });
  }

  makeSpheres() {
    const n = this.rec.bodyTypes.length, g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
    g.setAttribute('bcolor', new THREE.BufferAttribute(new Float32Array(3 * n), 3));
    const r = new Float32Array(n);
    for (let i = 0; i < n; ++i) r[i] = this.rec.types[this.rec.bodyTypes[i]].radius;
    g.setAttribute('radius', new THREE.BufferAttribute(r, 1));
    this.spheres = new THREE.Points(g, voxcdSphereMaterial());
    this.spheres.frustumCulled = false;
    this.stage.scene.add(this.spheres);
    this.stage.onFrame.push(() => {
      const c = this.stage.camera;
      this.spheres.material.uniforms.scale.value =
        this.stage.renderer.domElement.height / (2 * Math.tan(c.fov * Math.PI / 360));
    });
    this.setDetail(n > VOXCD_SPHERES_ABOVE ? 'spheres' : 'meshes');
  }

  // 'meshes': every body with its type's mesh (instanced); 'spheres': every body as its bounding sphere.
  setDetail(d) {
    this.detail = d;
    for (const m of this.meshes) m.visible = d === 'meshes';
    this.spheres.visible = d === 'spheres';
    if (this.slider) this.setFrame(this.frame);
  }

  // Renders at `s` times the page's pixels (1 or 0.5).
  setScale(s) {
    this.scale = s;
    this.stage.renderer.setPixelRatio(s);
    this.stage.resize();
  }

  makeContacts() {
    const most = Math.max(1, ...this.rec.frames.map((f) => f.contacts.count));
    const r = this.rec.types.reduce((s, t) => s + t.radius, 0) / this.rec.types.length;
    this.normalLength = 0.35 * r;
    this.contactPoints = VoxcdUtil.points(new Float32Array(3 * most), 0xffffff, 4);
    this.contactNormals = VoxcdUtil.normals(new Float32Array(3 * most), new Float32Array(3 * most), 0, 0xffe070);
    for (const o of [this.contactPoints, this.contactNormals]) {
      o.frustumCulled = false;
      this.stage.scene.add(o);
    }
  }

  makeWorld() {
    const side = this.rec.run.side || 100;
    const box = new THREE.LineSegments(new THREE.EdgesGeometry(new THREE.BoxBufferGeometry(side, side, side)),
      new THREE.LineBasicMaterial({ color: 0x666c78 }));
    box.position.set(side / 2, side / 2, side / 2);
    this.stage.scene.add(box);
    this.stage.frame(new THREE.Vector3(0, 0, 0), new THREE.Vector3(side, side, side));
    this.path = new THREE.Line(new THREE.BufferGeometry(), new THREE.LineBasicMaterial({ color: 0x7dff8a }));
    this.path.frustumCulled = false;
    this.stage.scene.add(this.path);
  }

  makeControls() {
    const c = document.getElementById('controls'), el = VoxcdUtil.el;
    this.playButton = el('button', { textContent: 'play' }, c);
    this.playButton.addEventListener('click', () => this.play(!this.playing));
    this.slider = el('input', { type: 'range', min: 0, max: Math.max(0, this.rec.frames.length - 1), value: 0 }, c);
    this.slider.style.width = '45%';
    this.slider.addEventListener('input', () => this.setFrame(+this.slider.value));
    this.label = el('span', {}, c);
    el('span', { textContent: ' speed ' }, c);
    const speed = el('select', {}, c);
    for (const s of [0.25, 0.5, 1, 2, 4, 8]) el('option', { value: s, textContent: s + 'x', selected: s === 1 }, speed);
    speed.addEventListener('change', () => { this.speed = +speed.value; });
    el('span', { textContent: ' bodies as ' }, c);
    const detail = el('select', {}, c);
    for (const d of ['meshes', 'spheres']) el('option', { value: d, textContent: d, selected: d === this.detail }, detail);
    detail.addEventListener('change', () => this.setDetail(detail.value));
    el('span', { textContent: ' resolution ' }, c);
    const scale = el('select', {}, c);
    const half = this.rec.bodyTypes.length > VOXCD_HALF_ABOVE;
    for (const [v, t] of [[1, 'full'], [0.5, 'half']]) el('option', { value: v, textContent: t, selected: (v < 1) === half }, scale);
    scale.addEventListener('change', () => this.setScale(+scale.value));
    this.setScale(half ? 0.5 : 1);
    el('span', { textContent: '  ' }, c);
    VoxcdUtil.toggle(c, 'contacts', true, (on) => { this.contactPoints.visible = on; });
    VoxcdUtil.toggle(c, 'normals', true, (on) => { this.contactNormals.visible = on; });
    if (this.data.url) VoxcdUtil.toggle(c, 'follow the file', false, (on) => this.follow(on));
  }

  makePlots() {
    const p = document.getElementById('plots'), f = this.rec.frames;
    const series = (name, color, get) => ({ name, color, values: f.map(get) });
    const pick = (i) => this.setFrame(i);
    this.plots = [
      new VoxcdPlot(p, 'stage times', 'us', [
        series('integrate', '#8ab4f8', (x) => 1e6 * x.stats.t_integrate),
        series('bounds', '#c58af9', (x) => 1e6 * x.stats.t_bounds),
        series('broadphase', '#fdd663', (x) => 1e6 * x.stats.t_broadphase),
        series('pair tests', '#f28b82', (x) => 1e6 * x.stats.t_narrow),
        series('response', '#81c995', (x) => 1e6 * x.stats.t_response)], pick),
      new VoxcdPlot(p, 'lookups', 'shell points', [series('lookups', '#fdd663', (x) => x.stats.lookups),
        series('hits', '#f28b82', (x) => x.stats.hits)], pick),
      new VoxcdPlot(p, 'device cycles', 'cycles', [series('cycles', '#8ab4f8', (x) => x.stats.device_cycles)], pick),
    ];
  }

  play(on) {
    this.playing = on;
    this.playButton.textContent = on ? 'pause' : 'play';
    this.last = undefined;
  }

  tick(t) {
    if (!this.playing || this.rec.frames.length < 2) return;
    if (this.last === undefined) { this.last = t; this.acc = 0; }
    this.acc += (t - this.last) * 30 * this.speed / 1000;  // recorded frames at 30 per second times the speed
    this.last = t;
    if (this.acc < 1) return;
    const step = Math.floor(this.acc);
    this.acc -= step;
    this.setFrame((this.frame + step) % this.rec.frames.length);
  }

  setFrame(i) {
    const f = this.rec.frames[i];
    if (!f) return;
    this.frame = i;
    this.slider.value = i;
    this.label.textContent = ' frame ' + f.stats.frame + ' (' + (i + 1) + ' of ' + this.rec.frames.length + ')';
    this.updateState(f);
    this.updateBodies(f);
    this.updateContacts(f);
    for (const p of this.plots) p.draw(i);
    this.showSide();
  }

  updateState(f) {
    const s = this.state;
    s.fill(0);
    for (let k = 0; k < f.flags.length; ++k) {
      const v = (f.flags[k] & 2) ? 2 : 1;
      const a = f.pairs[2 * k], b = f.pairs[2 * k + 1];
      if (s[a] < v) s[a] = v;
      if (s[b] < v) s[b] = v;
    }
  }

  updateBodies(f) {
    if (this.detail === 'spheres') this.updateSpheres(f);
    else this.updateMeshes(f);
  }

  colour(i) {
    return i === this.picked ? VOXCD_COLOURS.picked : VOXCD_COLOURS[['free', 'pair', 'touching'][this.state[i]]];
  }

  updateMeshes(f) {
    const p = f.poses, types = this.rec.bodyTypes;
    for (let i = 0; i < types.length; ++i) {
      const mesh = this.meshes[types[i]], at = this.slot[i];
      const e = mesh.instanceMatrix.array, o = 16 * at, q = 7 * i;
      const x = p[q + 4], y = p[q + 5], z = p[q + 6], w = p[q + 3];
      e[o] = 1 - 2 * (y * y + z * z); e[o + 1] = 2 * (x * y + w * z); e[o + 2] = 2 * (x * z - w * y); e[o + 3] = 0;
      e[o + 4] = 2 * (x * y - w * z); e[o + 5] = 1 - 2 * (x * x + z * z); e[o + 6] = 2 * (y * z + w * x); e[o + 7] = 0;
      e[o + 8] = 2 * (x * z + w * y); e[o + 9] = 2 * (y * z - w * x); e[o + 10] = 1 - 2 * (x * x + y * y); e[o + 11] = 0;
      e[o + 12] = p[q]; e[o + 13] = p[q + 1]; e[o + 14] = p[q + 2]; e[o + 15] = 1;
      mesh.geometry.attributes.icolor.array.set(this.colour(i), 3 * at);
    }
    for (const m of this.meshes) {
      m.instanceMatrix.needsUpdate = true;
      m.geometry.attributes.icolor.needsUpdate = true;
    }
  }

  // Each body's sphere at its bounding sphere's centre: rotation * the type's centre + position.
  updateSpheres(f) {
    const p = f.poses, types = this.rec.bodyTypes, g = this.spheres.geometry;
    const pos = g.attributes.position.array, col = g.attributes.bcolor.array;
    for (let i = 0; i < types.length; ++i) {
      const c = this.rec.types[types[i]].centre, q = 7 * i;
      const w = p[q + 3], x = p[q + 4], y = p[q + 5], z = p[q + 6];
      // v + 2w(u x v) + 2u x (u x v), u = (x, y, z): the quaternion's rotation of c.
      const tx = 2 * (y * c[2] - z * c[1]), ty = 2 * (z * c[0] - x * c[2]), tz = 2 * (x * c[1] - y * c[0]);
      pos[3 * i] = p[q] + c[0] + w * tx + y * tz - z * ty;
      pos[3 * i + 1] = p[q + 1] + c[1] + w * ty + z * tx - x * tz;
      pos[3 * i + 2] = p[q + 2] + c[2] + w * tz + x * ty - y * tx;
      col.set(this.colour(i), 3 * i);
    }
    g.attributes.position.needsUpdate = true;
    g.attributes.bcolor.needsUpdate = true;
  }

  updateContacts(f) {
    if (3 * f.contacts.count > this.contactPoints.geometry.attributes.position.array.length) {
      for (const o of [this.contactPoints, this.contactNormals]) this.stage.scene.remove(o);
      this.makeContacts();  // a frame read since (follow) has more contacts than the buffers hold
    }
    const k = f.contacts, pts = this.contactPoints.geometry, nrm = this.contactNormals.geometry;
    pts.attributes.position.array.set(k.position);
    pts.setDrawRange(0, k.count);
    pts.attributes.position.needsUpdate = true;
    const a = nrm.attributes.position.array, L = this.normalLength;
    for (let i = 0; i < k.count; ++i)
      for (let j = 0; j < 3; ++j) {
        a[6 * i + j] = k.position[3 * i + j];
        a[6 * i + 3 + j] = k.position[3 * i + j] + L * k.normal[3 * i + j];
      }
    nrm.setDrawRange(0, 2 * k.count);
    nrm.attributes.position.needsUpdate = true;
  }

  // Bodies drawn (instances of every type's mesh) and contact points drawn, for tests.
  drawnBodies() {
    const spheres = this.spheres.visible ? this.spheres.geometry.attributes.position.count : 0;
    return this.meshes.reduce((s, m) => s + (m.visible ? m.count : 0), spheres);
  }
  drawnContacts() { return this.contactPoints.visible ? this.contactPoints.geometry.drawRange.count : 0; }
  bodyMatrix(i) {
    const m = this.meshes[this.rec.bodyTypes[i]];
    return Array.from(m.instanceMatrix.array.slice(16 * this.slot[i], 16 * this.slot[i] + 16));
  }

  makePicking() {
    const el = this.stage.renderer.domElement;
    el.addEventListener('pointerdown', (e) => { this.down = [e.clientX, e.clientY]; });
    el.addEventListener('pointerup', (e) => {
      if (!this.down || Math.hypot(e.clientX - this.down[0], e.clientY - this.down[1]) > 4) return;
      this.pick(this.bodyUnder(this.stage.ray(e)));
    });
  }

  // The nearest body whose bounding sphere the ray meets, or -1.
  bodyUnder(ray) {
    const f = this.rec.frames[this.frame], p = f.poses, c = new THREE.Vector3(), q = new THREE.Quaternion();
    let best = -1, bestT = Infinity;
    for (let i = 0; i < this.rec.bodyTypes.length; ++i) {
      const t = this.rec.types[this.rec.bodyTypes[i]];
      q.set(p[7 * i + 4], p[7 * i + 5], p[7 * i + 6], p[7 * i + 3]);
      c.set(t.centre[0], t.centre[1], t.centre[2]).applyQuaternion(q).add(new THREE.Vector3(p[7 * i], p[7 * i + 1], p[7 * i + 2]));
      const d = ray.distanceSqToPoint(c);
      if (d > t.radius * t.radius) continue;
      const along = c.clone().sub(ray.origin).dot(ray.direction);
      if (along > 0 && along < bestT) { bestT = along; best = i; }
    }
    return best;
  }

  pick(i) {
    this.picked = i;
    const pts = [];
    if (i >= 0) for (const f of this.rec.frames) pts.push(new THREE.Vector3(f.poses[7 * i], f.poses[7 * i + 1], f.poses[7 * i + 2]));
    this.path.geometry.dispose();
    this.path.geometry = new THREE.BufferGeometry().setFromPoints(pts);
    this.setFrame(this.frame);
  }

  showSide() {
    const side = document.getElementById('side'), f = this.rec.frames[this.frame];
    let h = '<b>frame ' + f.stats.frame + '</b><table>';
    for (const k of ['pairs', 'tested', 'touching', 'contacts', 'lookups', 'hits', 'device_cycles', 'responses', 'wall_hits'])
      h += '<tr><td class="key">' + k.replace('_', ' ') + '</td><td>' + f.stats[k] + '</td></tr>';
    h += '</table>' + this.bodyText(f) + '<p class="key">Click a body to see its pairs, contacts and history.</p>';
    h += '<b>run</b><table>';
    for (const [k, v] of Object.entries(this.rec.run)) h += '<tr><td class="key">' + k + '</td><td>' + v + '</td></tr>';
    side.innerHTML = h + '</table>';
  }

  bodyText(f) {
    const i = this.picked;
    if (i < 0) return '';
    const t = this.rec.types[this.rec.bodyTypes[i]], p = f.poses;
    let h = '<p><b class="hot">body ' + i + '</b> (' + t.name + ') at (' +
      [0, 1, 2].map((k) => p[7 * i + k].toFixed(2)).join(', ') + ')<br>';
    const mine = [];
    for (let k = 0; k < f.flags.length; ++k)
      if (f.pairs[2 * k] === i || f.pairs[2 * k + 1] === i) mine.push(k);
    h += 'pairs: ' + (mine.map((k) => (f.pairs[2 * k] === i ? f.pairs[2 * k + 1] : f.pairs[2 * k]) +
      ['', ' tested', '', ' touching'][f.flags[k]]).join(', ') || 'none') + '<br>';
    const c = f.contacts;
    let n = 0;
    for (let k = 0; k < c.count; ++k) if (mine.includes(c.pair[k])) {
      if (n++ < 8) h += 'contact depth ' + c.depth[k].toFixed(3) + ' normal (' +
        [0, 1, 2].map((a) => c.normal[3 * k + a].toFixed(2)).join(', ') + ')<br>';
    }
    h += n + (n === 1 ? ' contact' : ' contacts') + ' this frame<br>touching in frames: ' + this.history(i) + '</p>';
    return h;
  }

  // The frames in which body i touched another, as ranges.
  history(i) {
    const ranges = [];
    this.rec.frames.forEach((f, n) => {
      let touching = false;
      for (let k = 0; k < f.flags.length && !touching; ++k)
        touching = (f.flags[k] & 2) && (f.pairs[2 * k] === i || f.pairs[2 * k + 1] === i);
      if (!touching) return;
      const last = ranges[ranges.length - 1];
      if (last && last[1] === n - 1) last[1] = n; else ranges.push([n, n]);
    });
    return ranges.map((r) => r[0] === r[1] ? r[0] : r[0] + '-' + r[1]).join(', ') || 'none';
  }

  // Re-reads the file every second while on: a recording still being written shows its new frames.
  follow(on) {
    clearInterval(this.timer);
    if (!on) return;
    this.timer = setInterval(async () => {
      const rec = VoxcdRecording.parse(await (await fetch(this.data.url)).arrayBuffer());
      if (rec.frames.length <= this.rec.frames.length) return;
      const atEnd = this.frame === this.rec.frames.length - 1;
      this.rec = rec;
      this.slider.max = rec.frames.length - 1;
      this.resetPlots();
      this.setFrame(atEnd ? rec.frames.length - 1 : this.frame);
    }, 1000);
  }

  resetPlots() {
    document.getElementById('plots').innerHTML = '';
    this.makePlots();
  }
}
