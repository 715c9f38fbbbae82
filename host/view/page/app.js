// The page: loads its data (inlined by --html, or from the tool that serves it), makes the three.js stage and
// shows a recording, an object or a pair. window.voxcdView tells tests and benchmarks what is drawn.
'use strict';

window.voxcdView = { ready: false, kind: null, errors: [], renderedFrames: 0, frameTimes: [] };
window.addEventListener('error', (e) => window.voxcdView.errors.push(String(e.message)));
window.addEventListener('unhandledrejection', (e) => window.voxcdView.errors.push(String(e.reason)));

function voxcdStatus(text, error) {
  const s = document.getElementById('status');
  s.textContent = text;
  s.className = error ? 'error' : '';
}

// The renderer, camera, controls and lights, rendering on every animation frame; `onFrame` callbacks run first.
class VoxcdStage {
  constructor(viewport) {
    this.viewport = viewport;
    this.renderer = new THREE.WebGLRenderer({ antialias: false, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.renderer.setClearColor(0x1d2026);
    viewport.appendChild(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1e5);
    this.controls = new THREE.OrbitControls(this.camera, this.renderer.domElement);
    this.scene.add(new THREE.AmbientLight(0xffffff, 0.45));
    const sun = new THREE.DirectionalLight(0xffffff, 0.75);
    sun.position.set(0.5, 0.8, 1.0);
    this.camera.add(sun);
    this.scene.add(this.camera);
    this.onFrame = [];
    new ResizeObserver(() => this.resize()).observe(viewport);
    this.resize();
    const loop = (t) => {
      for (const f of this.onFrame) f(t);
      this.renderer.render(this.scene, this.camera);
      const v = window.voxcdView;
      v.renderedFrames++;
      v.frameTimes.push(t);
      if (v.frameTimes.length > 600) v.frameTimes.shift();
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  resize() {
    const w = Math.max(1, this.viewport.clientWidth), h = Math.max(1, this.viewport.clientHeight);
    this.renderer.setSize(w, h);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
  }

  // Looks at the box [lo, hi] from a corner, far enough to see all of it.
  frame(lo, hi) {
    const c = new THREE.Vector3().addVectors(lo, hi).multiplyScalar(0.5);
    const r = new THREE.Vector3().subVectors(hi, lo).length() / 2 || 1;
    this.controls.target.copy(c);
    this.camera.position.copy(c).add(new THREE.Vector3(0.9, 0.7, 1.3).normalize().multiplyScalar(2.6 * r));
    this.camera.near = r / 100;
    this.camera.far = r * 100;
    this.camera.updateProjectionMatrix();
    this.controls.update();
  }

  // The ray under a mouse event, in world coordinates.
  ray(event) {
    const r = this.renderer.domElement.getBoundingClientRect();
    const m = new THREE.Vector2((event.clientX - r.left) / r.width * 2 - 1, -(event.clientY - r.top) / r.height * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(m, this.camera);
    return ray.ray;
  }
}

// Helpers shared by the views.
const VoxcdUtil = {
  bytes(b64) {
    const s = atob(b64);
    const a = new Uint8Array(s.length);
    for (let i = 0; i < s.length; ++i) a[i] = s.charCodeAt(i);
    return a.buffer;
  },
  floats(b64) { return new Float32Array(VoxcdUtil.bytes(b64)); },
  u32(b64) { return new Uint32Array(VoxcdUtil.bytes(b64)); },
  // A lit mesh of vertices (Float32Array, 3 per vertex) and triangles (Uint32Array, 3 per triangle).
  geometry(vertices, triangles) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(vertices, 3));
    g.setIndex(new THREE.BufferAttribute(triangles, 1));
    g.computeVertexNormals();
    g.computeBoundingSphere();
    return g;
  },
  points(positions, color, size) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    return new THREE.Points(g, new THREE.PointsMaterial({ color, size, sizeAttenuation: false }));
  },
  // Line segments from each point along its unit normal, `length` long.
  normals(points, normals, length, color) {
    const n = points.length / 3, a = new Float32Array(6 * n);
    for (let i = 0; i < n; ++i)
      for (let k = 0; k < 3; ++k) {
        a[6 * i + k] = points[3 * i + k];
        a[6 * i + 3 + k] = points[3 * i + k] + length * normals[3 * i + k];
      }
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(a, 3));
    return new THREE.LineSegments(g, new THREE.LineBasicMaterial({ color }));
  },
  el(tag, attrs, parent) {
    const e = document.createElement(tag);
    Object.assign(e, attrs || {});
    if (parent) parent.appendChild(e);
    return e;
  },
  // A labelled checkbox that calls f(checked) now and on every change.
  toggle(parent, text, checked, f) {
    const l = VoxcdUtil.el('label', {}, parent);
    const c = VoxcdUtil.el('input', { type: 'checkbox', checked }, l);
    l.appendChild(document.createTextNode(' ' + text));
    c.addEventListener('change', () => f(c.checked));
    f(checked);
    return c;
  },
};

async function voxcdLoad() {
  if (window.VOXCD_DATA) return window.VOXCD_DATA;
  const r = await fetch('data/info');
  if (!r.ok) throw new Error('data/info: ' + r.status + ' ' + (await r.text()));
  return r.json();
}

async function voxcdMain() {
  const data = await voxcdLoad();
  const stage = new VoxcdStage(document.getElementById('viewport'));
  window.voxcdView.kind = data.kind;
  document.getElementById('title').textContent = 'voxcd view: ' + (data.name || data.kind);
  if (data.kind === 'recording') {
    const buf = data.bytes ? VoxcdUtil.bytes(data.bytes) : await (await fetch(data.url)).arrayBuffer();
    window.voxcdView.view = new VoxcdSceneView(stage, VoxcdRecording.parse(buf), data);
  } else if (data.kind === 'object') {
    window.voxcdView.view = new VoxcdObjectView(stage, data);
  } else if (data.kind === 'pair') {
    window.voxcdView.view = new VoxcdPairView(stage, data, !window.VOXCD_DATA);
  } else {
    throw new Error('unknown data kind ' + data.kind);
  }
  window.voxcdView.ready = true;
}

voxcdMain().catch((e) => {
  window.voxcdView.errors.push(String(e && e.message || e));
  voxcdStatus('error: ' + (e && e.message || e), true);
});
