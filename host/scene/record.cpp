#include "voxcd/host/scene/record.h"

#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include <nlohmann/json.hpp>

#include "voxcd/host/object/voxmap_surface.h"
#include "voxcd/host/scene/simulate.h"
#include "voxcd/version.h"

namespace voxcd {

namespace {

// docs/view.md: the file header, then records of {kind, payload length, payload, CRC-32 of the payload}.
constexpr char kMagic[8] = {'V', 'O', 'X', 'C', 'D', 'R', 'E', 'C'};
constexpr uint32_t kRun = 1, kType = 2, kBodies = 3, kFrame = 4;
constexpr size_t kFileHeader = 16, kRecordHeader = 8, kRecordTrailer = 4;
// Fixed part of a frame record: 16 counters (u64) and 5 stage times (f64).
constexpr size_t kFrameStats = 16 * 8 + 5 * 8;

static_assert(sizeof(float) == 4 && sizeof(double) == 8, "IEEE 754 binary32 and binary64");

template <class T>
void put_raw(std::string& b, T v) {
  char c[sizeof(T)];
  std::memcpy(c, &v, sizeof(T));
  b.append(c, sizeof(T));
}
void put_u32(std::string& b, uint32_t v) { put_raw(b, v); }
void put_u64(std::string& b, uint64_t v) { put_raw(b, v); }
void put_f32(std::string& b, double v) { put_raw(b, float(v)); }
void put_f64(std::string& b, double v) { put_raw(b, v); }

uint32_t crc_of(const char* p, size_t n) {
  return uint32_t(crc32_z(0L, reinterpret_cast<const Bytef*>(p), n));
}

uint32_t count32(size_t n, const std::string& what) {
  if (n > UINT32_MAX) throw RecordError("recording: " + what + " (" + std::to_string(n) + ") exceed 2^32 - 1");
  return uint32_t(n);
}

std::string type_payload(uint32_t index, const RecordedType& t) {
  std::string b;
  put_u32(b, index);
  put_u32(b, count32(t.name.size(), "the type's name bytes"));
  b += t.name;
  put_f64(b, t.voxel);
  for (double v : t.origin) put_f64(b, v);
  for (uint32_t v : t.dims) put_u32(b, v);
  for (const auto* a : {&t.lo, &t.hi, &t.centre})
    for (double v : *a) put_f64(b, v);
  put_f64(b, t.radius);
  put_u32(b, t.from_mesh ? 0 : 1);
  put_u32(b, count32(t.vertices.size(), "vertices"));
  for (const auto& p : t.vertices)
    for (float v : p) put_raw(b, v);
  put_u32(b, count32(t.triangles.size(), "triangles"));
  for (const auto& tri : t.triangles)
    for (uint32_t v : tri) put_u32(b, v);
  put_u32(b, count32(t.shell_points.size(), "shell points"));
  for (const auto& p : t.shell_points)
    for (float v : p) put_raw(b, v);
  for (const auto& p : t.shell_normals)
    for (float v : p) put_raw(b, v);
  return b;
}

void put_stats(std::string& b, const FrameStats& s) {
  for (uint64_t v : {s.frame, s.pairs, s.tested, s.touching, s.responses, s.wall_hits, s.lookups, s.hits, s.contacts,
                     s.device_cycles, s.ccd_iterations, s.ccd_queries, s.ccd_limited, s.ccd_toi, s.ccd_dropped,
                     s.ccd_lookups})
    put_u64(b, v);
  for (double v : {s.t_integrate, s.t_bounds, s.t_broadphase, s.t_narrow, s.t_response}) put_f64(b, v);
}

}  // namespace

RecordedType recorded_type(const ObjectType& t) {
  RecordedType r;
  r.name = t.name;
  const Voxmap& v = t.voxmap();
  r.voxel = v.voxel();
  for (int i = 0; i < 3; ++i) {
    r.origin[size_t(i)] = v.origin()[i];
    r.dims[size_t(i)] = v.dims()[size_t(i)];
    r.lo[size_t(i)] = t.lo[i];
    r.hi[size_t(i)] = t.hi[i];
    r.centre[size_t(i)] = t.centre[i];
  }
  r.radius = t.radius;
  r.from_mesh = t.mesh && !t.mesh->triangles.empty();
  const Mesh surface = r.from_mesh ? Mesh{} : voxmap_surface(v);
  const Mesh& m = r.from_mesh ? *t.mesh : surface;
  for (const auto& p : m.vertices) r.vertices.push_back({float(p.x()), float(p.y()), float(p.z())});
  r.triangles = m.triangles;
  const PointShell& s = t.shell();
  for (size_t k = 0; k < s.size(); ++k) {
    r.shell_points.push_back({float(s.points[k].x()), float(s.points[k].y()), float(s.points[k].z())});
    r.shell_normals.push_back({float(s.normals[k].x()), float(s.normals[k].y()), float(s.normals[k].z())});
  }
  return r;
}

std::string record_settings(const SimulationSummary& s) {
  nlohmann::json j;
  j["tool"] = std::string("voxcd ") + VOXCD_VERSION;
  const RunConfig& c = s.config;
  j["scene"] = c.where;
  j["shape"] = s.shape();
  j["objects"] = c.objects();
  j["side"] = c.side;
  j["density"] = c.density;
  j["seed"] = c.seed;
  j["frames"] = c.frames;
  j["broadphase"] = c.broadphase;
  j["pruning"] = c.broadphase;  // "broadphase"'s deprecated spelling, for one release (docs/view.md)
  j["backend"] = c.backend;
  j["mode"] = mode_name(c.mode);
  j["both_directions"] = c.both_directions;
  j["distance_bits"] = s.distance_bits();
  j["margin"] = c.margin;
  j["ccd"] = c.ccd;
  j["lanes"] = c.lanes;
  j["device"] = s.device.to_string();
  j["clock_mhz"] = s.clock.mhz;
  j["clock_source"] = s.clock.source;
  j["clock_estimate"] = s.clock.estimate;
  return j.dump();
}

RecordWriter::RecordWriter(const std::string& path, const Simulation& sim, const std::string& run) : path_(path) {
  f_ = std::fopen(path.c_str(), "wb");
  if (!f_) throw RecordError(path + ": cannot write the recording: " + std::strerror(errno));
  std::string head(kMagic, sizeof kMagic);
  put_u32(head, kRecordVersion);
  put_u32(head, 0);  // flags: none defined
  if (std::fwrite(head.data(), 1, head.size(), f_) != head.size())
    throw RecordError(path + ": cannot write the recording's header: " + std::strerror(errno));
  bytes_ = head.size();
  put(kRun, run);
  const Scene& sc = sim.scene();
  for (size_t i = 0; i < sc.types.size(); ++i) put(kType, type_payload(uint32_t(i), recorded_type(*sc.types[i])));
  std::string b;
  put_u32(b, count32(sc.bodies.size(), "bodies"));
  for (const Body& body : sc.bodies) put_u32(b, body.type);
  put(kBodies, b);
}

RecordWriter::~RecordWriter() {
  if (f_) std::fclose(f_);
}

void RecordWriter::close() {
  if (!f_) return;
  const bool ok = std::fclose(f_) == 0;
  f_ = nullptr;
  if (!ok) throw RecordError(path_ + ": cannot close the recording: " + std::strerror(errno));
}

void RecordWriter::put(uint32_t kind, const std::string& payload) {
  if (!f_) throw RecordError(path_ + ": the recording is closed");
  std::string& b = buf_;
  b.clear();
  put_u32(b, kind);
  put_u32(b, count32(payload.size(), "a record's bytes"));
  b += payload;
  put_u32(b, crc_of(payload.data(), payload.size()));
  // One write and a flush per record: a reader sees whole records, or a short last one it leaves for later.
  if (std::fwrite(b.data(), 1, b.size(), f_) != b.size() || std::fflush(f_) != 0)
    throw RecordError(path_ + ": cannot write the recording at byte " + std::to_string(bytes_) + ": " +
                      std::strerror(errno));
  bytes_ += b.size();
}

void RecordWriter::frame(const Simulation& sim, const FrameStats& st) {
  std::string b;
  b.reserve(kFrameStats + 28 * sim.scene().bodies.size() + 4096);
  put_stats(b, st);
  const auto& bodies = sim.scene().bodies;
  put_u32(b, count32(bodies.size(), "bodies"));
  for (const Body& body : bodies) {
    for (int i = 0; i < 3; ++i) put_f32(b, body.pose.translation[i]);
    const Eigen::Quaterniond& q = body.pose.rotation;
    for (double v : {q.w(), q.x(), q.y(), q.z()}) put_f32(b, v);
  }
  // The broadphase's pairs; the tested ones are a subsequence of them in the same order (Simulation::narrow).
  const std::vector<BodyPair>& pairs = sim.broadphase().pairs();
  const std::vector<BodyPair>& tested = sim.tested_pairs();
  const std::vector<PairResult>& results = sim.results();
  put_u32(b, count32(pairs.size(), "pairs"));
  for (const BodyPair& p : pairs) put_u32(b, p.first), put_u32(b, p.second);
  std::vector<uint32_t> where(tested.size());  // each tested pair's index among the broadphase's
  size_t j = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    uint8_t flags = 0;
    if (j < tested.size() && tested[j] == pairs[i]) {
      flags = kPairTested | (results[j].hits > 0 ? kPairTouching : 0);
      where[j++] = uint32_t(i);
    }
    b.push_back(char(flags));
  }
  if (j != tested.size())
    throw RecordError(path_ + ": frame " + std::to_string(st.frame) + ": a tested pair is not among the broadphase's");
  size_t contacts = 0;
  for (const PairResult& r : results) contacts += r.contacts.size();
  put_u32(b, count32(contacts, "contacts"));
  for (size_t q = 0; q < results.size(); ++q)
    for (const Contact& c : results[q].contacts) {
      put_u32(b, where[q]);
      b.push_back(char(c.a_in_b ? 1 : 0));
      put_u32(b, c.point);
      for (int i = 0; i < 3; ++i) put_f32(b, c.position[i]);
      for (int i = 0; i < 3; ++i) put_f32(b, c.normal[i]);
      put_f32(b, c.depth);
    }
  put(kFrame, b);
  ++frames_;
}

}  // namespace voxcd
