#include "voxcd/host/object/object_file.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <tuple>

#include "voxcd/host/object/detail/object_io.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/ref/fnv1a.h"

namespace voxcd {

namespace {

constexpr char kMagic[8] = {'V', 'O', 'X', 'C', 'D', 'O', 'B', 'J'};
// Version 3 adds the distance section and shell points on the surface; it is written only for objects that have
// either, so every other object is written as version 2, byte for byte as before. Versions 1 (no report section)
// and 2 are still read.
// Version 4 adds the report's second section (after the distance section): the counts of non-manifold parts and
// conservative distance cells, written only when one of them is not 0.
// Version 5 holds the voxmap or the shell (or both) in its sparse form (header flags 2 and 4), with version 4's
// sections after them and the reserved sparse distance section before the checksum; it is written only for objects
// held sparse.
constexpr uint32_t kVersion = 2, kVersionDistance = 3, kVersionReport2 = 4, kVersionSparse = 5;
// The report's second section (version 4): its count, then the counts, in file order.
constexpr uint32_t kReport2Counts = 4;
// Header flags: the shell's points lie on the surface (PointShell::on_surface; version 3 on); the voxmap, the shell, the
// distance field is sparse (version 5; the field in the sparse distance section).
constexpr uint32_t kFlagSurfaceShell = 1, kFlagSparseVoxmap = 2, kFlagSparseShell = 4, kFlagSparseDistance = 8;
// The report section's fields (version 2), in file order.
constexpr int kReportCounts = 19;
constexpr uint32_t kClosed = 1, kFlipped = 2, kPointsOnly = 4, kSurfaceOnly = 8, kReportFlags = 15;

std::array<uint64_t*, kReportCounts> report_fields(MeshReport& m, VoxelizeReport& v) {
  return {reinterpret_cast<uint64_t*>(&m.input_vertices), reinterpret_cast<uint64_t*>(&m.input_triangles),
          reinterpret_cast<uint64_t*>(&m.vertices), reinterpret_cast<uint64_t*>(&m.triangles),
          reinterpret_cast<uint64_t*>(&m.welded), reinterpret_cast<uint64_t*>(&m.welded_near),
          reinterpret_cast<uint64_t*>(&m.dropped_nonfinite),
          reinterpret_cast<uint64_t*>(&m.dropped_repeated), reinterpret_cast<uint64_t*>(&m.dropped_collinear),
          reinterpret_cast<uint64_t*>(&m.dropped_duplicate), reinterpret_cast<uint64_t*>(&m.reoriented),
          reinterpret_cast<uint64_t*>(&m.open_edges), reinterpret_cast<uint64_t*>(&m.nonmanifold_edges),
          reinterpret_cast<uint64_t*>(&m.inconsistent_edges), reinterpret_cast<uint64_t*>(&m.components),
          reinterpret_cast<uint64_t*>(&m.closed_components), reinterpret_cast<uint64_t*>(&m.sheet_components),
          &v.uncertain, &v.evaluated};
}
std::array<uint64_t*, kReport2Counts> report2_fields(MeshReport& m, VoxelizeReport& v) {
  return {reinterpret_cast<uint64_t*>(&m.nonmanifold_parts), reinterpret_cast<uint64_t*>(&m.dropped_internal),
          reinterpret_cast<uint64_t*>(&m.fin_triangles), &v.conservative};
}
static_assert(sizeof(size_t) == sizeof(uint64_t), "report counts are stored as u64");

using detail::get_grid;
using detail::get_vec;
using detail::put_grid;
using detail::put_vec;
using detail::Reader;
using detail::Writer;

// The distance section of version 3 (write_object describes it).
void read_distance(Reader& r, const GridPlacement& g, DistanceField& f) {
  const uint32_t bits = r.get<uint32_t>("the distance bits");
  if (bits != 0 && !valid_distance_bits(int(bits)))
    r.bad("distance bits " + std::to_string(bits) + " are not 0, " + distance_bits_text());
  const double step = r.get<double>("the distance step");
  if (bits == 0 ? step != 0 : !(std::isfinite(step) && step > 0))
    r.bad(bits == 0 ? "the distance step of an object without a field is not 0"
                    : "the distance step " + std::to_string(step) + " is not a positive finite number");
  const uint64_t count = r.get<uint64_t>("the distance node count");
  const uint64_t nodes = (uint64_t(g.dims[0]) + 1) * (uint64_t(g.dims[1]) + 1) * (uint64_t(g.dims[2]) + 1);
  if (count != (bits ? nodes : 0))
    r.bad("distance node count " + std::to_string(count) + " does not match the voxmap's grid (" +
          std::to_string(bits ? nodes : 0) + ")");
  if (bits == 0) return;
  const uint64_t bytes = (count * bits + 7) / 8;
  r.need(bytes, "the distance node values");
  f.bits = int(bits);
  f.step = step;
  f.dims = g.dims;
  f.q.resize(count);
  const unsigned char* p = reinterpret_cast<const unsigned char*>(r.buf.data() + r.pos);
  const uint64_t mask = (uint64_t{1} << bits) - 1, sign = uint64_t{1} << (bits - 1);
  for (uint64_t i = 0; i < count; ++i) {
    const uint64_t at = i * bits;
    uint64_t v = 0;
    for (uint64_t b = at / 8; b <= (at + bits - 1) / 8; ++b) v |= uint64_t(p[b]) << (8 * (b - at / 8));
    v = (v >> (at % 8)) & mask;
    f.q[i] = int16_t(int64_t(v ^ sign) - int64_t(sign));
  }
  r.field = r.pos;
  if ((count * bits) % 8 && (p[bytes - 1] >> ((count * bits) % 8)) != 0) {
    r.field = r.pos + bytes - 1;
    r.bad("the last distance byte has bits set beyond the last node");
  }
  r.pos += bytes;
}

}  // namespace

namespace {

// ObjectFileError for an object no object file can hold: shell arrays of different lengths, a distance field on
// another grid, a grid dimension of 0 or above kObjectMaxDim.
void check_writable(const std::string& path, const ObjectFile& obj) {
  const PointShell& sh = obj.shell;
  if (!obj.shell_sparse() && (sh.points.size() != sh.size() || sh.normals.size() != sh.size()))
    throw ObjectFileError(path + ": the shell's cells, points and normals differ in number");
  if (!obj.shell_sparse() && sh.on_surface && sh.coords.size() != sh.size())
    throw ObjectFileError(path + ": the shell's coordinates and cells differ in number");
  if (obj.shell_sparse()) {
    const SparseShell& ss = obj.sparse_shell;
    uint64_t points = 0;
    for (uint64_t m : ss.masks) points += uint64_t(__builtin_popcountll(m));
    if (ss.masks.size() != ss.bricks.size() || points != ss.normals.size())
      throw ObjectFileError(path + ": the sparse shell's bricks, masks and normals differ in number");
  }
  const DistanceField& df = obj.distance;
  if (!df.empty() && (df.dims != obj.voxmap_grid().dims || df.q.size() != df.node_index(0, 0, df.dims[2] + 1)))
    throw ObjectFileError(path + ": the distance field's grid is not the voxmap's");
  for (const GridPlacement* g : {&obj.voxmap_grid(), &obj.shell_grid()})
    for (uint32_t d : g->dims)
      if (d == 0 || d > kObjectMaxDim)
        throw ObjectFileError(path + ": grid dimension " + std::to_string(d) + " does not fit an object file");
}

void put_voxmap(Writer& w, const Voxmap& vm) {
  put_grid(w, vm.grid());
  const auto c = vm.counts();
  w.put(c[kEmpty]);
  w.put(c[kSurface]);
  w.put(c[kInterior]);
  w.put(uint32_t{64});  // MEMW of the image below
  w.put(uint64_t(vm.words().size()));
  for (uint64_t word : vm.words()) w.put(word);
}

void put_shell(Writer& w, const PointShell& s) {
  put_grid(w, s.grid);
  w.put(uint32_t(kObjectShellFrac));
  w.put(uint64_t(s.size()));
  for (size_t k = 0; k < s.size(); ++k)
    for (int a = 0; a < 3; ++a)
      w.put(s.on_surface ? s.coords[k][a] : int32_t((2 * int64_t(s.cells[k][a]) + 1) << (kObjectShellFrac - 1)));
  for (size_t k = 0; k < s.size(); ++k) put_vec(w, s.points[k]);
  for (size_t k = 0; k < s.size(); ++k) put_vec(w, s.normals[k]);
}

// Report (version 2): flags, weld tolerance, counts; all zero when the object has none.
void put_report(Writer& w, const ObjectFile& obj) {
  MeshReport m = obj.has_report ? obj.mesh_report : MeshReport{};
  VoxelizeReport v = obj.has_report ? obj.voxelize_report : VoxelizeReport{};
  uint32_t flags = 0;
  if (obj.has_report)
    flags = 16 | (m.closed ? kClosed : 0) | (m.flipped ? kFlipped : 0) | (m.points_only ? kPointsOnly : 0) |
            (m.surface_only ? kSurfaceOnly : 0);
  w.put(flags);
  w.put(m.weld_tolerance);
  for (uint64_t* f : report_fields(m, v)) w.put(*f);
}

// Distance section (version 3): SB, step, node count, then the node values packed SB bits each.
void put_distance(Writer& w, const DistanceField& df) {
  w.put(uint32_t(df.bits));
  w.put(df.empty() ? 0.0 : df.step);
  w.put(uint64_t(df.empty() ? 0 : df.q.size()));
  if (df.empty()) return;
  const uint64_t mask = (uint64_t{1} << df.bits) - 1;
  uint64_t acc = 0;
  int have = 0;
  for (int16_t v : df.q) {
    acc |= (uint64_t(int64_t(v)) & mask) << have;
    for (have += df.bits; have >= 8; have -= 8, acc >>= 8) w.buf += char(acc & 0xff);
  }
  if (have > 0) w.buf += char(acc & 0xff);
}

// The file being written: path.tmp, renamed into place only once written whole, and removed when writing fails.
class TmpFile {
 public:
  explicit TmpFile(const std::string& path) : path_(path), tmp_(path + ".tmp"), out_(tmp_, std::ios::binary | std::ios::trunc) {
    if (!out_) throw ObjectFileError(path_ + ": cannot write " + tmp_);
  }
  ~TmpFile() {
    if (!done_) {
      out_.close();
      std::remove(tmp_.c_str());
    }
  }
  TmpFile(const TmpFile&) = delete;
  TmpFile& operator=(const TmpFile&) = delete;
  std::ostream& stream() { return out_; }
  void commit() {
    if (!out_.flush()) throw ObjectFileError(path_ + ": write failed");
    out_.close();
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0) throw ObjectFileError(path_ + ": cannot rename " + tmp_ + " into place");
    done_ = true;
  }

 private:
  std::string path_, tmp_;
  std::ofstream out_;
  bool done_ = false;
};

}  // namespace

void write_object(const std::string& path, const ObjectFile& obj) {
  check_writable(path, obj);
  const PointShell& sh = obj.shell;
  const DistanceField& df = obj.distance;
  MeshReport mr = obj.has_report ? obj.mesh_report : MeshReport{};
  VoxelizeReport vr = obj.has_report ? obj.voxelize_report : VoxelizeReport{};
  bool v4 = false;
  for (uint64_t* f : report2_fields(mr, vr)) v4 |= *f != 0;
  const bool v5 = obj.voxmap_sparse() || obj.shell_sparse() || obj.distance_sparse();
  v4 = v4 || v5;
  const bool v3 = !df.empty() || sh.on_surface || v4;
  TmpFile file(path);
  Writer w;
  w.sink = &file.stream();
  w.buf.append(kMagic, 8);
  w.put(v5 ? kVersionSparse : v4 ? kVersionReport2 : v3 ? kVersionDistance : kVersion);
  w.put((sh.on_surface && !obj.shell_sparse() ? kFlagSurfaceShell : uint32_t{0}) |
        (obj.voxmap_sparse() ? kFlagSparseVoxmap : uint32_t{0}) | (obj.shell_sparse() ? kFlagSparseShell : uint32_t{0}) |
        (obj.distance_sparse() ? kFlagSparseDistance : uint32_t{0}));
  w.put(obj.source_hash);
  w.str(obj.source);
  w.put(obj.shell_ratio);
  put_vec(w, obj.shift);
  if (obj.voxmap_sparse()) {
    put_grid(w, obj.sparse_voxmap.grid());
    detail::put_sparse_voxmap(w, obj.sparse_voxmap);
  } else {
    put_voxmap(w, obj.voxmap);
  }
  if (obj.shell_sparse())
    detail::put_sparse_shell(w, obj.sparse_shell);
  else
    put_shell(w, sh);
  put_report(w, obj);
  if (v3) put_distance(w, df);
  // The report's second section (version 4 on): u32 count, then the counts as u64.
  if (v4) {
    w.put(kReport2Counts);
    for (uint64_t* f : report2_fields(mr, vr)) w.put(*f);
  }
  if (v5) detail::put_sparse_distance(w, obj);
  w.flush();
  const uint32_t crc = w.crc;
  w.put(crc);
  w.flush();
  file.commit();
}

namespace {

// The header after the magic number: the version and the flags, each checked.
void read_header(Reader& r, uint32_t& version, uint32_t& flags) {
  r.need(8, "the magic number");
  if (std::memcmp(r.buf.data(), kMagic, 8) != 0) r.bad("not a voxcd object file (bad magic)");
  r.pos = 8;
  version = r.get<uint32_t>("the version");
  if (version < 1 || version > kVersionSparse)
    r.bad("object file version " + std::to_string(version) + " is not supported (this reader knows versions 1 to " +
          std::to_string(kVersionSparse) + ")");
  flags = r.get<uint32_t>("the flags");
  const uint32_t known_flags = (version >= kVersionDistance ? kFlagSurfaceShell : 0) |
                               (version >= kVersionSparse ? kFlagSparseVoxmap | kFlagSparseShell | kFlagSparseDistance : 0);
  if (flags & ~known_flags)
    r.bad("unknown flags " + std::to_string(flags) + " (version " + std::to_string(version) + " knows " +
          std::to_string(known_flags) + ")");
  if ((flags & kFlagSurfaceShell) && (flags & kFlagSparseShell))
    r.bad("flags " + std::to_string(flags) + ": a shell on the surface is never sparse");
  if (version >= kVersionSparse && !(flags & (kFlagSparseVoxmap | kFlagSparseShell | kFlagSparseDistance)))
    r.bad("a version 5 file holds its voxmap, its shell or its distance field sparse, and its flags say none");
}

// Where the voxmap section's checks point once the whole file is read.
struct VoxmapAt {
  uint64_t counts[3];
  size_t counts_at = 0, words_at = 0;
};

VoxmapAt read_voxmap(Reader& r, const GridPlacement& g, Voxmap& vm) {
  VoxmapAt at;
  at.counts_at = r.pos;
  for (auto& c : at.counts) c = r.get<uint64_t>("the state counts");
  if (const uint32_t memw = r.get<uint32_t>("the voxmap word width"); memw != 64)
    r.bad("voxmap word width " + std::to_string(memw) + " is not 64");
  const uint64_t nwords = r.get<uint64_t>("the voxmap word count");
  if (nwords != (g.size() + 31) / 32)
    r.bad("voxmap word count " + std::to_string(nwords) + " does not match its dimensions (" +
          std::to_string((g.size() + 31) / 32) + ")");
  r.need(nwords, "the voxmap words", 8);
  vm = Voxmap(g);
  at.words_at = r.pos;
  std::memcpy(vm.words().data(), r.buf.data() + r.pos, nwords * 8);
  r.field = r.pos;
  r.pos += nwords * 8;
  if (const uint64_t used = g.size() % 32; used && (vm.words().back() >> (2 * used)) != 0) {
    r.field = r.pos - 8;
    r.bad("the voxmap's last word has bits set beyond its last voxel");
  }
  return at;
}

// The shell's words into cells (and coords for a surface shell), each checked against the grid.
void read_shell_words(Reader& r, uint64_t n, PointShell& s) {
  const GridPlacement& sg = s.grid;
  for (uint64_t k = 0; k < n; ++k)
    for (int a = 0; a < 3; ++a) {
      const int32_t w = r.get<int32_t>("a shell word");
      if (s.on_surface) {
        // Any point of the grid's closed box; its voxel is the one whose closed cube holds it.
        if (w < 0 || int64_t(w) > (int64_t(sg.dims[a]) << kObjectShellFrac))
          r.bad("shell word " + std::to_string(k) + " lies outside the shell grid");
        s.coords[k][a] = w;
        s.cells[k][a] = std::min(uint32_t(w >> kObjectShellFrac), sg.dims[a] - 1);
        continue;
      }
      const int32_t unit = 1 << (kObjectShellFrac - 1);
      if (w < 0 || w % unit != 0 || (w / unit) % 2 != 1 || uint32_t(w / unit / 2) >= sg.dims[a])
        r.bad("shell word " + std::to_string(k) + " is not a voxel centre of the shell grid");
      s.cells[k][a] = uint32_t(w / unit / 2);
    }
}

// The shell's points in order: by their voxels' linear index (then z, y, x for a surface shell).
void check_shell_order(Reader& r, const PointShell& s, size_t words_at) {
  const GridPlacement& sg = s.grid;
  auto lin = [&](uint64_t i) {
    return s.cells[i][0] + uint64_t(sg.dims[0]) * (s.cells[i][1] + uint64_t(sg.dims[1]) * s.cells[i][2]);
  };
  for (uint64_t k = 1; k < s.cells.size(); ++k) {
    bool after = lin(k) > lin(k - 1);
    if (s.on_surface && lin(k) == lin(k - 1)) {
      const auto &c = s.coords[k], &p = s.coords[k - 1];
      after = std::make_tuple(c[2], c[1], c[0]) > std::make_tuple(p[2], p[1], p[0]);
    }
    if (!after) {
      r.field = words_at + 12 * k;
      r.bad("shell word " + std::to_string(k) + " is not after shell word " + std::to_string(k - 1) +
            (s.on_surface ? " in the order of their voxels' linear index, then z, y, x" : " in linear-index order"));
    }
  }
}

void read_shell(Reader& r, bool on_surface, PointShell& s) {
  s.grid = get_grid(r, "the shell grid");
  if (r.get<uint32_t>("the shell word format") != uint32_t(kObjectShellFrac)) r.bad("unexpected shell word format");
  const uint64_t n = r.get<uint64_t>("the shell point count");
  r.need(n, "the shell points", 12 + 24 + 24);
  s.on_surface = on_surface;
  s.cells.resize(n);
  s.points.resize(n);
  s.normals.resize(n);
  if (s.on_surface) s.coords.resize(n);
  const size_t words_at = r.pos;
  read_shell_words(r, n, s);
  check_shell_order(r, s, words_at);
  for (uint64_t k = 0; k < n; ++k) {
    s.points[k] = get_vec(r, "a shell point");
    if (!s.points[k].allFinite()) r.bad("shell point " + std::to_string(k) + " is not finite");
  }
  for (uint64_t k = 0; k < n; ++k) {
    s.normals[k] = get_vec(r, "a shell normal");
    if (!s.normals[k].allFinite()) r.bad("shell normal " + std::to_string(k) + " is not finite");
  }
}

// The report (version 2) and its second section (version 4).
void read_report(Reader& r, uint32_t version, ObjectFile& obj) {
  const uint32_t flags = r.get<uint32_t>("the report flags");
  if (flags & ~uint32_t(16 | kReportFlags)) r.bad("unknown report flags " + std::to_string(flags));
  obj.has_report = flags & 16;
  MeshReport& m = obj.mesh_report;
  m.closed = flags & kClosed;
  m.flipped = flags & kFlipped;
  m.points_only = flags & kPointsOnly;
  m.surface_only = flags & kSurfaceOnly;
  m.weld_tolerance = r.get<double>("the weld tolerance");
  if (!(std::isfinite(m.weld_tolerance) && m.weld_tolerance >= 0)) r.bad("the weld tolerance is not a finite number >= 0");
  for (uint64_t* f : report_fields(m, obj.voxelize_report)) *f = r.get<uint64_t>("the report counts");
  if (version >= kVersionDistance) read_distance(r, obj.voxmap.grid(), obj.distance);
  if (version < kVersionReport2) return;
  const uint32_t k = r.get<uint32_t>("the count of the report's second section");
  if (k != kReport2Counts)
    r.bad("the report's second section holds " + std::to_string(k) + " counts; version 4 has " +
          std::to_string(kReport2Counts));
  for (uint64_t* f : report2_fields(obj.mesh_report, obj.voxelize_report)) *f = r.get<uint64_t>("the report's second section");
}

// The checks that need the whole file: nothing after the checksum, the checksum, the voxmap's states and counts.
void check_whole(Reader& r, const VoxmapAt& at, const Voxmap& vm, bool dense_voxmap) {
  const std::string& buf = r.buf;
  uint32_t stored_crc;
  std::memcpy(&stored_crc, buf.data() + buf.size() - 4, 4);
  const uint32_t crc = uint32_t(crc32_z(0L, reinterpret_cast<const Bytef*>(buf.data()), buf.size() - 4));
  r.get<uint32_t>("the checksum");
  if (r.pos != buf.size()) {
    r.field = r.pos;
    r.bad(std::to_string(buf.size() - r.pos) + " unexpected bytes after the checksum");
  }
  if (crc != stored_crc) r.bad("checksum mismatch: the file is corrupt");
  if (!dense_voxmap) return;  // a sparse voxmap's states and counts were checked as it was read
  const auto c = vm.counts();
  if (c[kReserved] != 0) {
    r.field = at.words_at;
    r.bad("the voxmap holds " + std::to_string(c[kReserved]) + " voxels in the reserved state 3");
  }
  if (c[kEmpty] != at.counts[0] || c[kSurface] != at.counts[1] || c[kInterior] != at.counts[2]) {
    r.field = at.counts_at;
    r.bad("state counts do not match the voxmap");
  }
}

}  // namespace

ObjectFile read_object(const std::string& path, ObjectRead forms) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ObjectFileError(path + ": cannot open");
  const std::string buf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Reader r{buf, path};
  uint32_t version = 0, header_flags = 0;
  read_header(r, version, header_flags);
  ObjectFile obj;
  obj.source_hash = r.get<uint64_t>("the source hash");
  obj.source = r.str("the source name");
  obj.shell_ratio = r.get<double>("the shell ratio");
  if (!(std::isfinite(obj.shell_ratio) && obj.shell_ratio > 0)) r.bad("the shell ratio is not a positive number");
  obj.shift = get_vec(r, "the grid shift");
  if (!obj.shift.allFinite()) r.bad("the grid shift is not finite");
  const GridPlacement g = get_grid(r, "the voxmap grid");
  VoxmapAt at{};
  if (header_flags & kFlagSparseVoxmap)
    detail::read_sparse_voxmap(r, g, obj.sparse_voxmap);
  else
    at = read_voxmap(r, g, obj.voxmap);
  if (header_flags & kFlagSparseShell)
    detail::read_sparse_shell(r, obj.sparse_shell);
  else
    read_shell(r, header_flags & kFlagSurfaceShell, obj.shell);
  if (version >= 2) read_report(r, version, obj);
  if (version >= kVersionSparse) detail::read_sparse_distance(r, obj);
  if (obj.distance_sparse() != bool(header_flags & kFlagSparseDistance))
    r.bad(std::string("the flags say the distance field is ") + (obj.distance_sparse() ? "not " : "") +
          "sparse, and the sparse distance section " + (obj.distance_sparse() ? "holds one" : "holds none"));
  if (obj.distance_sparse() && !obj.distance.empty())
    r.bad("the object holds both a dense and a sparse distance field");
  check_whole(r, at, obj.voxmap, !(header_flags & kFlagSparseVoxmap));
  if (forms == ObjectRead::kWithDense) add_dense_forms(obj);
  return obj;
}

bool ObjectFile::distance_near_conservative(const Eigen::Vector3d& g) const {
  if (distance_sparse()) return sparse_distance.near_conservative(g);
  if (distance.empty() || voxmap.words().empty()) return false;
  uint32_t v[3];
  for (int i = 0; i < 3; ++i) v[i] = uint32_t(std::clamp(std::floor(g[i]), 0.0, double(distance.dims[i]) - 1));
  return distance.near_conservative(voxmap, v[0], v[1], v[2]);
}

void add_dense_forms(ObjectFile& obj) {
  if (obj.voxmap_sparse() && !obj.has_dense_voxmap()) {
    const auto& d = obj.sparse_voxmap.dims();
    if (std::max({d[0], d[1], d[2]}) <= kMaxDenseDim) obj.voxmap = obj.sparse_voxmap.to_dense();
  }
  if (obj.shell_sparse() && obj.shell.size() == 0) {
    const auto& d = obj.sparse_shell.grid.dims;
    if (std::max({d[0], d[1], d[2]}) <= ShellOptions{}.max_dim) obj.shell = obj.sparse_shell.to_point_shell();
  }
}

}  // namespace voxcd
