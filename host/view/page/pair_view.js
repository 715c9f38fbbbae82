// Two objects, A fixed and B at an editable pose in A's frame, with their contacts; the tool that serves the page
// recomputes the contacts at every new pose (/api/pair). An inlined page (--html) shows the pose it was written at.
'use strict';

class VoxcdPairView {
  constructor(stage, d, live) {
    this.stage = stage;
    this.d = d;
    this.live = live;
    this.a = this.object(d.a, 0x8fb0d8);
    this.b = this.object(d.b, 0xd8b08f);
    this.contacts = new THREE.Group();
    stage.scene.add(this.contacts);
    this.makeControls();
    this.show(d.result);
    const r = Math.max(d.a.radius, d.b.radius);
    const c = new THREE.Vector3(...d.a.centre);
    stage.frame(c.clone().subScalar(r), c.clone().addScalar(r));
  }

  object(t, color) {
    const g = new THREE.Group();
    const mesh = new THREE.Mesh(VoxcdUtil.geometry(VoxcdUtil.floats(t.surface.vertices), VoxcdUtil.u32(t.surface.triangles)),
      new THREE.MeshLambertMaterial({ color, transparent: true, opacity: 0.6, depthWrite: false, side: THREE.DoubleSide }));
    const shell = VoxcdUtil.points(VoxcdUtil.floats(t.shell.points), color, 2);
    shell.visible = false;
    g.add(mesh, shell);
    g.userData = { mesh, shell };
    this.stage.scene.add(g);
    return g;
  }

  makeControls() {
    const c = document.getElementById('controls'), el = VoxcdUtil.el;
    el('span', { textContent: 'B in A: ' }, c);
    const names = ['tx', 'ty', 'tz', 'rx', 'ry', 'rz'];
    this.inputs = names.map((n, i) => {
      const l = el('label', { textContent: n + ' ' }, c);
      const step = i < 3 ? +(this.d.a.voxel / 2).toPrecision(2) : 5;
      const input = el('input', { type: 'number', step, value: +this.d.result.pose[i].toPrecision(6), disabled: !this.live }, l);
      input.addEventListener('change', () => this.setPose(this.inputs.map((x) => +x.value)));
      return input;
    });
    VoxcdUtil.toggle(c, 'shells', false, (on) => { this.a.userData.shell.visible = on; this.b.userData.shell.visible = on; });
    if (!this.live) el('span', { textContent: ' (written with --html: the pose is fixed; voxcd view A B recomputes)' }, c);
  }

  // Asks the tool for the contacts at `pose` and shows them.
  async setPose(pose) {
    const r = await fetch('api/pair?pose=' + pose.join(','));
    const text = await r.text();
    if (!r.ok) { voxcdStatus(text, true); return; }
    this.show(JSON.parse(text));
  }

  show(res) {
    const p = res.pose;
    this.pose = p;
    this.b.position.set(p[0], p[1], p[2]);
    this.b.rotation.set(p[3] * Math.PI / 180, p[4] * Math.PI / 180, p[5] * Math.PI / 180, 'ZYX');
    this.inputs.forEach((x, i) => { x.value = +p[i].toPrecision(6); });
    this.contacts.clear ? this.contacts.clear() : this.contacts.children.slice().forEach((o) => this.contacts.remove(o));
    const n = res.contacts.length, pos = new Float32Array(3 * n), nrm = new Float32Array(3 * n);
    res.contacts.forEach((k, i) => { pos.set(k.position, 3 * i); nrm.set(k.normal, 3 * i); });
    this.contactCount = n;
    if (n) {
      this.contacts.add(VoxcdUtil.points(pos, 0xffffff, 5));
      this.contacts.add(VoxcdUtil.normals(pos, nrm, 1.5 * this.d.a.voxel, 0xffe070));
    }
    this.result = res;
    voxcdStatus(n + ' contacts, ' + res.hits + ' hits, ' + res.lookups + ' lookups' +
      (res.device_cycles !== null ? ', ' + res.device_cycles + ' device cycles' : '') + ' on ' + this.d.backend);
    this.showSide(res);
  }

  showSide(res) {
    let h = '<b>A</b> ' + this.d.a.name + ' (' + this.d.a.shell.count + ' shell points)<br><b>B</b> ' + this.d.b.name +
      ' (' + this.d.b.shell.count + ' shell points)<br><br><b>contacts</b><table>';
    res.contacts.slice(0, 40).forEach((k) => {
      h += '<tr><td>' + k.shell + ' ' + k.point + '</td><td>depth ' + k.depth.toFixed(3) + '</td><td>(' +
        k.normal.map((v) => v.toFixed(2)).join(', ') + ')</td></tr>';
    });
    if (res.contacts.length > 40) h += '<tr><td colspan=3>... ' + (res.contacts.length - 40) + ' more</td></tr>';
    document.getElementById('side').innerHTML = h + '</table>';
  }

  drawnContacts() { return this.contactCount; }
}
