// The object file's writer (write_object): the object checked, then its sections written to a temporary file that is
// renamed into place once whole (docs/objects.md, "The object file").
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

using detail::put_grid;
using detail::put_vec;
using detail::Writer;
using detail::kClosed;
using detail::kFlagSparseDistance;
using detail::kFlagSparseShell;
using detail::kFlagSparseVoxmap;
using detail::kFlagSurfaceShell;
using detail::kFlipped;
using detail::kMagic;
using detail::kPointsOnly;
using detail::kReport2Counts;
using detail::kSurfaceOnly;
using detail::kVersion;
using detail::kVersionDistance;
using detail::kVersionReport2;
using detail::kVersionSparse;
using detail::report2_fields;
using detail::report_fields;

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

}  // namespace voxcd
