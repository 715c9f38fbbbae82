// The object file's reader (read_object): every section read and checked, with errors that name the file and the
// byte (docs/objects.md, "The object file").
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

#include "voxcd/host/object/detail/object_format.h"
#include "voxcd/host/object/detail/object_io.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/ref/fnv1a.h"

namespace voxcd {

namespace {

using detail::get_grid;
using detail::get_vec;
using detail::Reader;
using detail::kClosed;
using detail::kFlagSparseDistance;
using detail::kFlagSparseShell;
using detail::kFlagSparseVoxmap;
using detail::kFlagSurfaceShell;
using detail::kFlipped;
using detail::kMagic;
using detail::kPointsOnly;
using detail::kReport2Counts;
using detail::kReportFlags;
using detail::kSurfaceOnly;
using detail::kVersionDistance;
using detail::kVersionReport2;
using detail::kVersionSparse;
using detail::report2_fields;
using detail::report_fields;

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

}  // namespace voxcd
