// Internal to host/object (object_write.cpp, object_read.cpp): the object file's layout constants shared by its
// writer and its reader: magic, versions, header flags and the report sections' fields.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::detail {

inline constexpr char kMagic[8] = {'V', 'O', 'X', 'C', 'D', 'O', 'B', 'J'};
// Version 3 adds the distance section and shell points on the surface; it is written only for objects that have
// either, so every other object is written as version 2, byte for byte as before. Versions 1 (no report section)
// and 2 are still read.
// Version 4 adds the report's second section (after the distance section): the counts of non-manifold parts and
// conservative distance cells, written only when one of them is not 0.
// Version 5 holds the voxmap or the shell (or both) in its sparse form (header flags 2 and 4), with version 4's
// sections after them and the reserved sparse distance section before the checksum; it is written only for objects
// held sparse.
inline constexpr uint32_t kVersion = 2, kVersionDistance = 3, kVersionReport2 = 4, kVersionSparse = 5;
// The report's second section (version 4): its count, then the counts, in file order.
inline constexpr uint32_t kReport2Counts = 4;
// Header flags: the shell's points lie on the surface (PointShell::on_surface; version 3 on); the voxmap, the shell, the
// distance field is sparse (version 5; the field in the sparse distance section).
inline constexpr uint32_t kFlagSurfaceShell = 1, kFlagSparseVoxmap = 2, kFlagSparseShell = 4, kFlagSparseDistance = 8;
// The report section's fields (version 2), in file order.
inline constexpr int kReportCounts = 19;
inline constexpr uint32_t kClosed = 1, kFlipped = 2, kPointsOnly = 4, kSurfaceOnly = 8, kReportFlags = 15;

inline std::array<uint64_t*, kReportCounts> report_fields(MeshReport& m, VoxelizeReport& v) {
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
inline std::array<uint64_t*, kReport2Counts> report2_fields(MeshReport& m, VoxelizeReport& v) {
  return {reinterpret_cast<uint64_t*>(&m.nonmanifold_parts), reinterpret_cast<uint64_t*>(&m.dropped_internal),
          reinterpret_cast<uint64_t*>(&m.fin_triangles), &v.conservative};
}
static_assert(sizeof(size_t) == sizeof(uint64_t), "report counts are stored as u64");

}  // namespace voxcd::detail
