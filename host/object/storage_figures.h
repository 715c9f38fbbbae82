// What an object takes in device memory with the default widths, in the forms it is stored in and in the other
// forms (docs/objects.md, "Sparse objects" and "Sparse distance field"). One set of figures for `voxcd voxelize` and
// `voxcd info` (host/report/object_report.h prints them), the Python module's Object.memory and the viewer's object
// page.
#pragma once

#include <array>
#include <cstdint>

#include "voxcd/host/object/object_file.h"
#include "voxcd/ref/config.h"

namespace voxcd {

// Device memory of the voxmap image (MEMW-bit words) and the shell words (three PW-bit coordinates each), in bytes
// rounded up to whole words and whole bytes.
struct ObjectMemory {
  uint64_t voxmap_bytes = 0, shell_bytes = 0;
};

// The dense forms' bytes, whichever form is stored.
ObjectMemory dense_memory(const ObjectFile& obj, const DeviceConfig& cfg = DeviceConfig{});
// The stored forms' bytes: a sparse voxmap its table and bricks, a sparse shell its shell words.
ObjectMemory object_memory(const ObjectFile& obj, const DeviceConfig& cfg = DeviceConfig{});

// A distance field's device memory with the default widths and SB = its bits (BL 3 for a sparse field): words and
// bytes, and the node values stored.
struct DistanceMemory {
  DeviceConfig cfg;
  uint64_t words = 0, bytes = 0, nodes = 0;
};

// A dense distance map of `bits`-bit nodes on a grid of `dims` voxels: the 8 parity banks' words (map_words).
DistanceMemory dense_distance_memory(int bits, const std::array<uint32_t, 3>& dims);
// The object's dense field (all zero without one).
DistanceMemory distance_memory(const ObjectFile& obj);
// The object's sparse field: the table and brick words of its device image.
DistanceMemory sparse_distance_memory(const ObjectFile& obj);

// The object's field in the form it is stored in and as a dense map on the same grid. A dense field's sparse form
// is not known without the mesh (its bricks may refine), so only a field stored sparse has sparse figures: `counts`,
// its cells, bricks per level and conservative sub-cells.
struct DistanceFigures {
  bool present = false, sparse = false;
  DistanceMemory stored, dense;
  SparseFieldCounts counts;
};
DistanceFigures distance_figures(const ObjectFile& obj);

// The bytes of both forms of the voxmap and the shell (a shell on the surface has no sparse form), and the sparse
// forms' make-up, as stored or as they would be.
struct StorageFigures {
  bool voxmap_sparse = false, shell_sparse = false, shell_has_sparse = false;
  uint64_t dense_voxmap = 0, dense_shell = 0;
  int bl = 0;
  std::array<uint64_t, 3> coarse{};
  std::array<uint64_t, 4> cells{};  // per code
  uint64_t table_bytes = 0, brick_bytes = 0;
  uint64_t shell_words = 0, shell_bricks = 0, origin_words = 0, sparse_shell = 0;
  uint64_t sparse_voxmap() const { return table_bytes + brick_bytes; }
  uint64_t sparse_shell_bytes() const { return shell_has_sparse ? sparse_shell : dense_shell; }
};

StorageFigures storage_figures(const ObjectFile& obj);

}  // namespace voxcd
