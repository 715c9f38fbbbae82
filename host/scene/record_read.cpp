// Reading a recording (docs/view.md): every record checked (CRC, sizes, indices), up to the last whole frame.
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include "voxcd/host/scene/record.h"

namespace voxcd {

namespace {

constexpr char kMagic[8] = {'V', 'O', 'X', 'C', 'D', 'R', 'E', 'C'};
constexpr uint32_t kRun = 1, kType = 2, kBodies = 3, kFrame = 4;

const char* kind_name(uint32_t k) {
  switch (k) {
    case kRun: return "run";
    case kType: return "type";
    case kBodies: return "bodies";
    case kFrame: return "frame";
    default: return "unknown";
  }
}

// Reads little-endian values from one record's payload; an error names the file, the byte and what was read.
struct Cursor {
  const std::string& bytes;
  size_t at, end;
  const std::string& name;
  const char* record;

  [[noreturn]] void fail(const std::string& what) const {
    throw RecordError(name + ": byte " + std::to_string(at) + ": " + record + " record: " + what);
  }
  template <class T>
  T get(const char* what) {
    if (end - at < sizeof(T)) fail(std::string("ends inside ") + what);
    T v;
    std::memcpy(&v, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return v;
  }
  uint32_t u32(const char* what) { return get<uint32_t>(what); }
  // A count of items of `each` bytes that the rest of the record must be able to hold.
  uint32_t count(const char* what, size_t each) {
    const uint32_t n = u32(what);
    if (uint64_t(n) * each > end - at)
      fail(std::to_string(n) + " " + what + " need " + std::to_string(uint64_t(n) * each) + " bytes; " +
           std::to_string(end - at) + " are left");
    return n;
  }
  std::array<float, 3> vec3(const char* what) { return {get<float>(what), get<float>(what), get<float>(what)}; }
  std::array<double, 3> dvec3(const char* what) {
    return {get<double>(what), get<double>(what), get<double>(what)};
  }
};

RecordedType read_type(Cursor& c, size_t index) {
  RecordedType t;
  if (c.u32("the type's index") != index) c.fail("types must come in order; expected type " + std::to_string(index));
  const uint32_t name_len = c.count("name bytes", 1);
  t.name.assign(c.bytes, c.at, name_len);
  c.at += name_len;
  t.voxel = c.get<double>("the voxel");
  t.origin = c.dvec3("the origin");
  for (auto& d : t.dims) d = c.u32("the dimensions");
  t.lo = c.dvec3("the bounds");
  t.hi = c.dvec3("the bounds");
  t.centre = c.dvec3("the centre");
  t.radius = c.get<double>("the radius");
  const uint32_t surface = c.u32("the surface's kind");
  if (surface > 1) c.fail("surface kind " + std::to_string(surface) + " is not 0 (mesh) or 1 (voxmap surface)");
  t.from_mesh = surface == 0;
  t.vertices.resize(c.count("vertices", 12));
  for (auto& v : t.vertices) v = c.vec3("a vertex");
  t.triangles.resize(c.count("triangles", 12));
  for (auto& tri : t.triangles)
    for (auto& v : tri) {
      v = c.u32("a triangle");
      if (v >= t.vertices.size())
        c.fail("a triangle's vertex " + std::to_string(v) + " is not below " + std::to_string(t.vertices.size()));
    }
  t.shell_points.resize(c.count("shell points", 24));
  for (auto& p : t.shell_points) p = c.vec3("a shell point");
  t.shell_normals.resize(t.shell_points.size());
  for (auto& p : t.shell_normals) p = c.vec3("a shell normal");
  return t;
}

void read_stats(Cursor& c, FrameStats& s) {
  for (uint64_t* v : {&s.frame, &s.pairs, &s.tested, &s.touching, &s.responses, &s.wall_hits, &s.lookups, &s.hits,
                      &s.contacts, &s.device_cycles, &s.ccd_iterations, &s.ccd_queries, &s.ccd_limited, &s.ccd_toi,
                      &s.ccd_dropped, &s.ccd_lookups})
    *v = c.get<uint64_t>("the frame's counters");
  for (double* v : {&s.t_integrate, &s.t_bounds, &s.t_broadphase, &s.t_narrow, &s.t_response})
    *v = c.get<double>("the frame's stage times");
}

RecordedFrame read_frame(Cursor& c, const Recording& r) {
  RecordedFrame f;
  read_stats(c, f.stats);
  const uint32_t n = c.count("bodies", 28);
  if (n != r.body_types.size())
    c.fail(std::to_string(n) + " bodies; the recording has " + std::to_string(r.body_types.size()));
  f.positions.resize(n);
  f.rotations.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    f.positions[i] = c.vec3("a position");
    for (float& q : f.rotations[i]) q = c.get<float>("a rotation");
  }
  f.pairs.resize(c.count("pairs", 9));
  for (BodyPair& p : f.pairs) {
    p.first = c.u32("a pair");
    p.second = c.u32("a pair");
    if (p.first >= p.second || p.second >= n)
      c.fail("pair (" + std::to_string(p.first) + ", " + std::to_string(p.second) + ") is not two bodies in order");
  }
  f.pair_flags.assign(c.bytes.begin() + std::ptrdiff_t(c.at), c.bytes.begin() + std::ptrdiff_t(c.at + f.pairs.size()));
  c.at += f.pairs.size();
  for (uint8_t flags : f.pair_flags)
    if (flags & ~(kPairTested | kPairTouching) || flags == kPairTouching) c.fail("a pair's flags are invalid");
  f.contacts.resize(c.count("contacts", 37));
  for (RecordedContact& k : f.contacts) {
    k.pair = c.u32("a contact");
    if (k.pair >= f.pairs.size() || !(f.pair_flags[k.pair] & kPairTouching))
      c.fail("a contact's pair " + std::to_string(k.pair) + " is not a touching pair of the frame");
    k.a_in_b = c.get<uint8_t>("a contact") != 0;
    k.point = c.u32("a contact");
    k.position = c.vec3("a contact");
    k.normal = c.vec3("a contact");
    k.depth = c.get<float>("a contact");
  }
  return f;
}

// Reads the record at `at` into r; false (and r.truncated, r.note) when the bytes end inside it.
bool read_record(const std::string& b, size_t& at, const std::string& name, Recording& r) {
  const size_t start = at, left = b.size() - at;
  uint32_t kind = 0, len = 0;
  if (left >= 4) std::memcpy(&kind, b.data() + at, 4);
  if (left >= 8) std::memcpy(&len, b.data() + at + 4, 4);
  if (left < 8 || left - 8 < uint64_t(len) + 4) {
    r.truncated = true;
    r.note = name + ": truncated at byte " + std::to_string(b.size()) + " inside a " +
             (left >= 4 ? kind_name(kind) : "new") + " record that starts at byte " + std::to_string(start) +
             ": read " + std::to_string(r.frames.size()) + " whole frame" + (r.frames.size() == 1 ? "" : "s");
    return false;
  }
  at += 8;
  const uint32_t crc = uint32_t(crc32_z(0L, reinterpret_cast<const Bytef*>(b.data() + at), len));
  uint32_t stored;
  std::memcpy(&stored, b.data() + at + len, 4);
  if (crc != stored)
    throw RecordError(name + ": byte " + std::to_string(start) + ": the " + kind_name(kind) +
                      " record fails its CRC-32 (the file is damaged)");
  Cursor c{b, at, at + len, name, kind_name(kind)};
  const bool header_done = !r.body_types.empty() || !r.frames.empty();
  if (kind == kRun && start == 16) {
    r.run.assign(b, at, len);
    c.at = c.end;
  } else if (kind == kType && start > 16 && !header_done) {
    r.types.push_back(read_type(c, r.types.size()));
  } else if (kind == kBodies && !r.types.empty() && r.body_types.empty()) {
    r.body_types.resize(c.count("bodies", 4));
    for (uint32_t& t : r.body_types)
      if ((t = c.u32("a body's type")) >= r.types.size())
        c.fail("a body's type " + std::to_string(t) + " is not below " + std::to_string(r.types.size()));
    if (r.body_types.empty()) c.fail("no bodies");
  } else if (kind == kFrame && !r.body_types.empty()) {
    r.frames.push_back(read_frame(c, r));
  } else {
    c.fail(std::string("a ") + kind_name(kind) + " record (kind " + std::to_string(kind) +
           ") cannot come here: the order is run, types, bodies, frames");
  }
  if (c.at != c.end) c.fail(std::to_string(c.end - c.at) + " bytes are left over");
  at += len + 4;
  return true;
}

}  // namespace

Recording parse_recording(const std::string& b, const std::string& name) {
  if (b.size() < 8 || std::memcmp(b.data(), kMagic, 8) != 0) {
    if (b.size() < 8 && std::memcmp(b.data(), kMagic, b.size()) == 0)
      throw RecordError(name + ": truncated inside the file header (" + std::to_string(b.size()) + " bytes)");
    throw RecordError(name + ": not a voxcd recording (it does not start with VOXCDREC)");
  }
  if (b.size() < 16) throw RecordError(name + ": truncated inside the file header (" + std::to_string(b.size()) + " bytes)");
  Recording r;
  std::memcpy(&r.version, b.data() + 8, 4);
  if (r.version != kRecordVersion)
    throw RecordError(name + ": a recording of format version " + std::to_string(r.version) + "; this voxcd reads version " +
                      std::to_string(kRecordVersion) + " (docs/view.md)");
  uint32_t flags;
  std::memcpy(&flags, b.data() + 12, 4);
  if (flags != 0) throw RecordError(name + ": byte 12: header flags " + std::to_string(flags) + " are not 0");
  size_t at = 16;
  while (at < b.size() && read_record(b, at, name, r)) {
  }
  if (r.body_types.empty())
    throw RecordError(name + ": ends at byte " + std::to_string(b.size()) +
                      " before its types and bodies were written: nothing to show");
  return r;
}

Recording read_recording(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RecordError(path + ": cannot open");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_recording(bytes, path);
}

bool is_recording(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char m[8] = {};
  return in.read(m, 8) && std::memcmp(m, kMagic, 8) == 0;
}

}  // namespace voxcd
