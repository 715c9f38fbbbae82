// One object: its mesh (or its voxmap's surface), surface and interior voxels, slices of the voxmap or of the
// distance field along each axis, the point shell with its normals, the sparse structure (the voxmap's bricks, the
// distance field's bricks coloured by level) with what each part takes in device memory, and the repair report with
// its places marked.
'use strict';

// Distance bricks by level 0..3: the finer, the hotter.
const VOXCD_LEVEL_COLOURS = [0x66bb6a, 0xffd54f, 0xff7043, 0xd500f9];

class VoxcdObjectView {
  constructor(stage, d) {
    this.stage = stage;
    this.d = d;
    // 2-bit states, 16 per 32-bit word (docs/objects.md); null when not sent (docs/view.md, "An object").
    this.words = d.voxmap ? VoxcdUtil.u32(d.voxmap) : null;
    this.q = d.distance && d.distance.q ? new Int16Array(VoxcdUtil.bytes(d.distance.q)) : null;
    const lo = new THREE.Vector3(...d.origin);
    const hi = lo.clone().add(new THREE.Vector3(...d.dims).multiplyScalar(d.voxel));
    this.makeMesh();
    this.makeVoxels();
    this.makeShell();
    this.makeBricks();
    this.makePlaces();
    this.makeControls();
    this.showSide();
    stage.frame(lo, hi);
    voxcdStatus('voxmap ' + d.dims.join('x') + ' at voxel ' + +d.voxel.toPrecision(4) + ', ' + d.shell.count +
      ' shell points' + (d.surface.note ? ' (' + d.surface.note + ')' : ''));
  }

  state(x, y, z) {
    const i = x + this.d.dims[0] * (y + this.d.dims[1] * z);
    return (this.words[i >>> 4] >>> (2 * (i & 15))) & 3;
  }

  makeMesh() {
    const s = this.d.surface;
    this.geometry = VoxcdUtil.geometry(VoxcdUtil.floats(s.vertices), VoxcdUtil.u32(s.triangles));
    this.mesh = new THREE.Mesh(this.geometry, new THREE.MeshLambertMaterial({ color: 0xb8c4d8, transparent: true,
      opacity: 0.55, side: THREE.DoubleSide, depthWrite: false }));
    this.stage.scene.add(this.mesh);
  }

  // Instanced cubes at the centres of the voxels in `wanted` state.
  voxelCubes(wanted, color) {
    const d = this.d, v = d.voxel, m = new THREE.Matrix4(), at = [];
    for (let z = 0; this.words && z < d.dims[2]; ++z)
      for (let y = 0; y < d.dims[1]; ++y)
        for (let x = 0; x < d.dims[0]; ++x)
          if (this.state(x, y, z) === wanted) at.push(x, y, z);
    const n = at.length / 3;
    const cubes = new THREE.InstancedMesh(new THREE.BoxBufferGeometry(0.92 * v, 0.92 * v, 0.92 * v),
      new THREE.MeshLambertMaterial({ color }), Math.max(1, n));
    for (let i = 0; i < n; ++i) {
      m.makeTranslation(d.origin[0] + (at[3 * i] + 0.5) * v, d.origin[1] + (at[3 * i + 1] + 0.5) * v,
        d.origin[2] + (at[3 * i + 2] + 0.5) * v);
      cubes.setMatrixAt(i, m);
    }
    cubes.count = n;
    cubes.frustumCulled = false;
    this.stage.scene.add(cubes);
    return cubes;
  }

  makeVoxels() {
    this.surfaceVoxels = this.voxelCubes(1, 0xe8984a);
    this.interiorVoxels = this.voxelCubes(2, 0x4a78e8);
    this.slices = this.words || this.q ? [0, 1, 2].map((a) => this.makeSlice(a)) : [];
  }

  // Translucent boxes of the coarse cells at `cells` ((cx, cy, cz) triples), `edge` voxels a side, one draw call.
  boxes(cells, edge, color) {
    const d = this.d, s = edge * d.voxel, n = cells.length / 3, m = new THREE.Matrix4();
    const mesh = new THREE.InstancedMesh(new THREE.BoxBufferGeometry(0.94 * s, 0.94 * s, 0.94 * s),
      new THREE.MeshLambertMaterial({ color, transparent: true, opacity: 0.22, depthWrite: false }), Math.max(1, n));
    for (let i = 0; i < n; ++i) {
      m.makeTranslation(d.origin[0] + (cells[3 * i] + 0.5) * s, d.origin[1] + (cells[3 * i + 1] + 0.5) * s,
        d.origin[2] + (cells[3 * i + 2] + 0.5) * s);
      mesh.setMatrixAt(i, m);
    }
    mesh.count = n;
    mesh.frustumCulled = false;
    this.stage.scene.add(mesh);
    return mesh;
  }

  // The voxmap's bricks (cells not all in one state), and the distance field's bricks, one mesh per level.
  makeBricks() {
    const b = this.d.bricks, f = b.distance;
    this.voxmapBricks = this.boxes(VoxcdUtil.u32(b.voxmap.cells), b.voxmap.edge, 0x4dd0e1);
    this.distanceBricks = [];
    if (!f) return;
    const cells = VoxcdUtil.u32(f.cells), levels = new Uint8Array(VoxcdUtil.bytes(f.levels));
    for (let l = 0; l < 4; ++l) {
      const at = [];
      levels.forEach((level, i) => { if (level === l) at.push(cells[3 * i], cells[3 * i + 1], cells[3 * i + 2]); });
      this.distanceBricks.push(this.boxes(at, f.edge, VOXCD_LEVEL_COLOURS[l]));
    }
  }

  makeShell() {
    const s = this.d.shell, pts = VoxcdUtil.floats(s.points);
    this.shell = VoxcdUtil.points(pts, 0x7dff8a, 3);
    this.shellNormals = VoxcdUtil.normals(pts, VoxcdUtil.floats(s.normals), 0.8 * this.d.voxel, 0x3f9f4a);
    this.stage.scene.add(this.shell, this.shellNormals);
  }

  // A plane across axis a at slice k, textured with the states or the distance field there.
  makeSlice(a) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(12), 3));
    g.setAttribute('uv', new THREE.BufferAttribute(new Float32Array([0, 0, 1, 0, 1, 1, 0, 1]), 2));
    g.setIndex([0, 1, 2, 0, 2, 3]);
    const mesh = new THREE.Mesh(g, new THREE.MeshBasicMaterial({ side: THREE.DoubleSide, transparent: true }));
    mesh.frustumCulled = false;
    mesh.visible = false;
    this.stage.scene.add(mesh);
    return { axis: a, mesh, k: Math.floor(this.d.dims[a] / 2), mode: this.words ? 'states' : 'distance' };
  }

  placeSlice(s) {
    const d = this.d, a = s.axis, u = (a + 1) % 3, w = (a + 2) % 3, p = s.mesh.geometry.attributes.position;
    const corner = (cu, cw) => {
      const c = [0, 0, 0];
      c[a] = d.origin[a] + (s.k + 0.5) * d.voxel;
      c[u] = d.origin[u] + cu * d.dims[u] * d.voxel;
      c[w] = d.origin[w] + cw * d.dims[w] * d.voxel;
      return c;
    };
    [[0, 0], [1, 0], [1, 1], [0, 1]].forEach(([cu, cw], i) => p.array.set(corner(cu, cw), 3 * i));
    p.needsUpdate = true;
    if (s.mesh.material.map) s.mesh.material.map.dispose();
    s.mesh.material.map = s.mode === 'distance' && this.q ? this.distanceTexture(s, u, w) : this.stateTexture(s, u, w);
    s.mesh.material.needsUpdate = true;
  }

  stateTexture(s, u, w) {
    const d = this.d, nu = d.dims[u], nw = d.dims[w], px = new Uint8Array(4 * nu * nw);
    const colours = [[40, 44, 52, 60], [232, 152, 74, 235], [74, 120, 232, 235], [255, 0, 255, 255]];
    for (let j = 0; j < nw; ++j)
      for (let i = 0; i < nu; ++i) {
        const c = [0, 0, 0];
        c[s.axis] = s.k; c[u] = i; c[w] = j;
        px.set(colours[this.state(c[0], c[1], c[2])], 4 * (i + nu * j));
      }
    const t = new THREE.DataTexture(px, nu, nw, THREE.RGBAFormat);
    t.needsUpdate = true;
    return t;
  }

  // The field at the nodes of the two node planes around the slice's centre, averaged: blue inside, red outside.
  distanceTexture(s, u, w) {
    const f = this.d.distance, n = f.nodes, nu = n[u], nw = n[w], px = new Uint8Array(4 * nu * nw);
    const qmax = (1 << (f.bits - 1)) - 1;
    for (let j = 0; j < nw; ++j)
      for (let i = 0; i < nu; ++i) {
        let sum = 0;
        for (const k of [s.k, s.k + 1]) {
          const c = [0, 0, 0];
          c[s.axis] = k; c[u] = i; c[w] = j;
          sum += this.q[c[0] + n[0] * (c[1] + n[1] * c[2])];
        }
        const v = Math.max(-1, Math.min(1, sum / 2 / qmax));
        const c = v < 0 ? [255 * (1 + v), 255 * (1 + v), 255] : [255, 255 * (1 - v), 255 * (1 - v)];
        px.set([c[0], c[1], c[2], Math.abs(v) >= 1 ? 90 : 235], 4 * (i + nu * j));
      }
    const t = new THREE.DataTexture(px, nu, nw, THREE.RGBAFormat);
    t.magFilter = THREE.LinearFilter;
    t.needsUpdate = true;
    return t;
  }

  makePlaces() {
    const p = this.d.places;
    this.places = new THREE.Group();
    this.stage.scene.add(this.places);
    if (!p) return;
    const r = this.d.voxel;
    const add = (o) => { o.frustumCulled = false; this.places.add(o); };
    add(VoxcdUtil.points(VoxcdUtil.floats(p.dropped), 0xff4040, 9));
    add(VoxcdUtil.points(VoxcdUtil.floats(p.moved), 0xffe040, 7));
    add(VoxcdUtil.points(VoxcdUtil.floats(p.reoriented), 0xff9030, 7));
    for (const [key, color] of [['open_edges', 0xff40ff], ['nonmanifold_edges', 0x40ffff]]) {
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.BufferAttribute(VoxcdUtil.floats(p[key]), 3));
      add(new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color })));
    }
    const sheets = VoxcdUtil.u32(p.sheet_triangles);
    if (sheets.length) {
      const tri = this.geometry.index.array, idx = [];
      for (const t of sheets) idx.push(tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]);
      const g = new THREE.BufferGeometry();
      g.setAttribute('position', this.geometry.attributes.position);
      g.setIndex(idx);
      add(new THREE.Mesh(g, new THREE.MeshBasicMaterial({ color: 0x50e070, side: THREE.DoubleSide })));
    }
    this.places.userData.r = r;
  }

  makeControls() {
    const c = document.getElementById('controls'), T = VoxcdUtil.toggle;
    T(c, 'mesh', true, (on) => { this.mesh.visible = on; });
    T(c, 'surface voxels', false, (on) => { this.surfaceVoxels.visible = on; });
    T(c, 'interior voxels', false, (on) => { this.interiorVoxels.visible = on; });
    T(c, 'shell', true, (on) => { this.shell.visible = on; });
    T(c, 'normals', false, (on) => { this.shellNormals.visible = on; });
    T(c, 'repairs', true, (on) => { this.places.visible = on; });
    T(c, 'voxmap bricks', this.d.storage.voxmap === 'sparse', (on) => { this.voxmapBricks.visible = on; });
    if (this.distanceBricks.length)
      T(c, 'distance bricks', true, (on) => this.distanceBricks.forEach((m) => { m.visible = on; }));
    if (!this.slices.length) return;
    const mode = VoxcdUtil.el('select', {}, c);
    if (this.words) VoxcdUtil.el('option', { value: 'states', textContent: 'slices: voxel states' }, mode);
    if (this.q) VoxcdUtil.el('option', { value: 'distance', textContent: 'slices: distance field' }, mode);
    mode.addEventListener('change', () => this.slices.forEach((s) => { s.mode = mode.value; this.placeSlice(s); }));
    for (const s of this.slices) this.sliceControl(c, s);
  }

  sliceControl(c, s) {
    const el = VoxcdUtil.el, l = el('label', {}, c);
    const box = el('input', { type: 'checkbox' }, l);
    l.appendChild(document.createTextNode(' ' + 'xyz'[s.axis] + ' '));
    const r = el('input', { type: 'range', min: 0, max: this.d.dims[s.axis] - 1, value: s.k }, l);
    r.style.width = '90px';
    box.addEventListener('change', () => { s.mesh.visible = box.checked; if (box.checked) this.placeSlice(s); });
    r.addEventListener('input', () => { s.k = +r.value; this.placeSlice(s); });
    s.box = box;
  }

  showSide() {
    const d = this.d, p = d.places;
    let h = '<b>' + d.name + '</b><table>';
    const row = (k, v) => { h += '<tr><td class="key">' + k + '</td><td>' + v + '</td></tr>'; };
    row('source', d.source);
    row('voxmap', d.dims.join(' x ') + ' at ' + +d.voxel.toPrecision(5));
    row('voxels', d.counts.surface + ' surface, ' + d.counts.interior + ' interior');
    row('shell', d.shell.count + ' points' + (d.shell.on_surface ? ' on the surface' : ''));
    if (d.distance) row('distance', d.distance.bits + ' bits over +-' + +d.distance.band.toPrecision(3) + ' voxels');
    row('drawn', d.surface.from_mesh ? 'the mesh (' + d.surface.triangle_count + ' triangles)' :
      d.surface.triangle_count ? 'the voxmap surface' : 'no surface');
    h += '</table>' + this.storageHtml() + this.bricksHtml();
    if (d.notes.length) h += '<p class="key">' + d.notes.join('<br>') + '</p>';
    h += '<b>repair report</b>';
    if (!d.report) h += '<p>none (an object file of version 1)</p>';
    else {
      h += '<table>';
      for (const [k, v] of Object.entries(d.report)) row(k.replace(/_/g, ' '), v);
      h += '</table>';
    }
    if (p) h += '<p>marked: <span style="color:#f44">dropped triangles</span>, <span style="color:#fe4">moved ' +
      'vertices</span>, <span style="color:#f93">reoriented triangles</span>, <span style="color:#f4f">open edges' +
      '</span>, <span style="color:#4ff">non-manifold edges</span>, <span style="color:#5e7">sheets</span></p>';
    document.getElementById('side').innerHTML = h;
  }

  // What each part takes in device memory, stored and in both forms (voxcd info's figures).
  storageHtml() {
    const st = this.d.storage, kb = (b) => b === null ? '-' : b < 1024 ? b + ' B' : b < 1048576 ?
      (b / 1024).toFixed(1) + ' KiB' : (b / 1048576).toFixed(1) + ' MiB';
    let h = '<b>device memory</b><table><tr><td></td><td class="key">stored</td><td class="key">dense</td>' +
      '<td class="key">sparse</td></tr>';
    for (const part of ['voxmap', 'shell', 'distance']) {
      const m = st.memory[part];
      if (m) h += '<tr><td class="key">' + part + '</td><td>' + st[part] + '</td><td>' + kb(m.dense) + '</td><td>' +
        kb(m.sparse) + '</td></tr>';
    }
    return h + '</table>';
  }

  // The bricks drawn of each structure, with the distance levels' colours as the legend.
  bricksHtml() {
    const b = this.d.bricks, f = b.distance, sw = (c) => '<span style="color:#' + c.toString(16).padStart(6, '0') +
      '">&#9632;</span> ';
    let h = '<b>bricks</b><table><tr><td class="key">' + sw(0x4dd0e1) + 'voxmap</td><td>' + b.voxmap.sent + ' of ' +
      b.voxmap.count + ' (' + b.voxmap.edge + '^3 voxels' + (b.voxmap.stored ? ')' : ', were it sparse)') +
      '</td></tr>';
    if (f) for (let l = 0; l < 4; ++l)
      h += '<tr><td class="key">' + sw(VOXCD_LEVEL_COLOURS[l]) + 'distance level ' + l + '</td><td>' + f.sent[l] +
        ' of ' + f.count[l] + (l ? ' (' + (1 << l) + 'x finer)' : '') + '</td></tr>';
    return h + '</table>';
  }

  drawnVoxmapBricks() { return this.voxmapBricks.visible ? this.voxmapBricks.count : 0; }
  drawnDistanceBricks() { return this.distanceBricks.map((m) => (m.visible ? m.count : 0)); }
  drawnShellPoints() { return this.shell.visible ? this.shell.geometry.attributes.position.count : 0; }
  drawnSurfaceVoxels() { return this.surfaceVoxels.count; }
  drawnInteriorVoxels() { return this.interiorVoxels.count; }
  showSlices(on) { for (const s of this.slices) { s.box.checked = on; s.mesh.visible = on; if (on) this.placeSlice(s); } }
}
