// Reads a voxcd recording (docs/view.md: "The recording format") from an ArrayBuffer, up to its last whole frame.
// The tool checks every record's CRC before it serves a file; this reader checks sizes and order.
'use strict';

const VoxcdRecording = (() => {
  const MAGIC = 'VOXCDREC', VERSION = 1;
  const RUN = 1, TYPE = 2, BODIES = 3, FRAME = 4;
  const COUNTERS = ['frame', 'pairs', 'tested', 'touching', 'responses', 'wall_hits', 'lookups', 'hits', 'contacts',
    'device_cycles', 'ccd_iterations', 'ccd_queries', 'ccd_limited', 'ccd_toi', 'ccd_dropped', 'ccd_lookups'];
  const TIMES = ['t_integrate', 't_bounds', 't_broadphase', 't_narrow', 't_response'];

  // A cursor over one record's payload [at, end).
  class Cursor {
    constructor(buf, at, end) { this.buf = buf; this.dv = new DataView(buf); this.at = at; this.end = end; }
    need(n, what) { if (this.end - this.at < n) throw new Error('the record ends inside ' + what); }
    u8() { this.need(1, 'a byte'); return this.dv.getUint8(this.at++); }
    u32() { this.need(4, 'a u32'); const v = this.dv.getUint32(this.at, true); this.at += 4; return v; }
    u64() { this.need(8, 'a u64'); const v = Number(this.dv.getBigUint64(this.at, true)); this.at += 8; return v; }
    f32() { this.need(4, 'a f32'); const v = this.dv.getFloat32(this.at, true); this.at += 4; return v; }
    f64() { this.need(8, 'a f64'); const v = this.dv.getFloat64(this.at, true); this.at += 8; return v; }
    f64s(n) { const a = []; for (let i = 0; i < n; ++i) a.push(this.f64()); return a; }
    // n items of `each` bytes copied into an aligned array of type T.
    copy(T, n, each) {
      this.need(n * each, n + ' items');
      const a = new T(this.buf.slice(this.at, this.at + n * each));
      this.at += n * each;
      return a;
    }
  }

  function readType(c, index) {
    if (c.u32() !== index) throw new Error('types out of order');
    const nameLen = c.u32();
    c.need(nameLen, 'the name');
    const name = new TextDecoder().decode(new Uint8Array(c.buf, c.at, nameLen));
    c.at += nameLen;
    const t = { name, voxel: c.f64(), origin: c.f64s(3), dims: [c.u32(), c.u32(), c.u32()] };
    t.lo = c.f64s(3); t.hi = c.f64s(3); t.centre = c.f64s(3); t.radius = c.f64();
    t.fromMesh = c.u32() === 0;
    t.vertices = c.copy(Float32Array, c.u32(), 12);
    t.triangles = c.copy(Uint32Array, c.u32(), 12);
    const shell = c.u32();
    t.shellPoints = c.copy(Float32Array, shell, 12);
    t.shellNormals = c.copy(Float32Array, shell, 12);
    return t;
  }

  function readContacts(c) {
    const n = c.u32();
    c.need(n * 37, n + ' contacts');
    const k = { count: n, pair: new Uint32Array(n), aInB: new Uint8Array(n), point: new Uint32Array(n),
      position: new Float32Array(3 * n), normal: new Float32Array(3 * n), depth: new Float32Array(n) };
    for (let i = 0; i < n; ++i) {
      k.pair[i] = c.u32(); k.aInB[i] = c.u8(); k.point[i] = c.u32();
      for (let a = 0; a < 3; ++a) k.position[3 * i + a] = c.f32();
      for (let a = 0; a < 3; ++a) k.normal[3 * i + a] = c.f32();
      k.depth[i] = c.f32();
    }
    return k;
  }

  function readFrame(c, bodies) {
    const stats = {};
    for (const k of COUNTERS) stats[k] = c.u64();
    for (const k of TIMES) stats[k] = c.f64();
    const n = c.u32();
    if (n !== bodies) throw new Error(n + ' bodies in a frame of a recording of ' + bodies);
    const poses = c.copy(Float32Array, n, 28);  // per body x, y, z, qw, qx, qy, qz
    const np = c.u32();
    const pairs = c.copy(Uint32Array, np, 8);
    const flags = c.copy(Uint8Array, np, 1);
    return { stats, poses, pairs, flags, contacts: readContacts(c) };
  }

  function header(buf) {
    if (buf.byteLength < 16) throw new Error('not a recording: ' + buf.byteLength + ' bytes');
    const magic = new TextDecoder().decode(new Uint8Array(buf, 0, 8));
    if (magic !== MAGIC) throw new Error('not a voxcd recording (it does not start with VOXCDREC)');
    const version = new DataView(buf).getUint32(8, true);
    if (version !== VERSION)
      throw new Error('a recording of format version ' + version + '; this page reads version ' + VERSION);
    return version;
  }

  // The recording in `buf`: {version, run, types, bodyTypes, frames, truncated, note}.
  function parse(buf) {
    const r = { version: header(buf), run: {}, types: [], bodyTypes: null, frames: [], truncated: false, note: '' };
    const dv = new DataView(buf);
    let at = 16;
    while (at < buf.byteLength) {
      const left = buf.byteLength - at;
      const len = left >= 8 ? dv.getUint32(at + 4, true) : 0;
      if (left < 8 || left - 8 < len + 4) {
        r.truncated = true;
        r.note = 'the file ends inside a record at byte ' + at + ': ' + r.frames.length + ' whole frames';
        break;
      }
      const kind = dv.getUint32(at, true);
      const c = new Cursor(buf, at + 8, at + 8 + len);
      if (kind === RUN) r.run = JSON.parse(new TextDecoder().decode(new Uint8Array(buf, at + 8, len)) || '{}');
      else if (kind === TYPE) r.types.push(readType(c, r.types.length));
      else if (kind === BODIES) r.bodyTypes = c.copy(Uint32Array, c.u32(), 4);
      else if (kind === FRAME) r.frames.push(readFrame(c, r.bodyTypes.length));
      else throw new Error('a record of unknown kind ' + kind + ' at byte ' + at);
      at += 8 + len + 4;
    }
    if (!r.bodyTypes) throw new Error('the recording has no bodies yet');
    return r;
  }

  return { parse, COUNTERS, TIMES };
})();
