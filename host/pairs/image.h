// The device image (internal to host): object types placed one after another in the device's shell and voxmap
// memories, and the device configuration that fits a set of types (memory sizes, matrix width).
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/device/device.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/pairs/detail/shell_order.h"
#include "voxcd/host/pairs/errors.h"

namespace voxcd {

// The memory image of a set of object types, each type's shell words and voxmap words placed after the previous
// type's. Only the types added are loaded. On a distance device (cfg.distance()) a type's map is its distance field
// in parity banks, starting on a bank boundary. On a sparse device (cfg.sparse()) a type stored sparse (its voxmap,
// or on a distance device its field) is placed as a sparse map, its table then its bricks, and a shell given as
// sparse words (detail::sparse_block_order) as those words (docs/contract.md, "Sparse voxmaps and shells").
class DeviceImage {
 public:
  struct Placement {
    uint32_t shell_base = 0, shell_count = 0;  // the shell's words
    uint32_t points = 0;                       // its points (shell_count for a dense shell)
    uint32_t map_base = 0, map_words = 0;      // the map's words (a sparse map's table)
    uint32_t brick_base = 0, brick_units = 0;  // a sparse map's bricks
    uint8_t sparse = 0;                        // Job::sparse of a job on these
    std::array<uint32_t, 3> dims = {1, 1, 1};
  };

  explicit DeviceImage(const DeviceConfig& cfg) : cfg_(cfg) {}
  // Places a type and returns its index. CapacityError naming the type and what it needs against what is left,
  // a dimension above 2^DW, or (on a distance device) a type without a distance field of at most SB bits;
  // RangeError from the shell's quantisation into PW/PF. With `order`, shell word k is the type's point order[k]
  // (a permutation of its points), else point k.
  uint32_t add(const ObjectType& t, const std::vector<uint32_t>& order = {});
  // The same with the shell in `order` (a dense order: shell word k is point order.point[k]; a sparse one: its words).
  uint32_t add(const ObjectType& t, const detail::ShellOrder& order);
  const Placement& placement(uint32_t i) const { return placements_.at(i); }
  size_t size() const { return placements_.size(); }
  const DeviceMemory& memory() const { return mem_; }
  const DeviceConfig& config() const { return cfg_; }

 private:
  DeviceConfig cfg_;
  DeviceMemory mem_;
  std::vector<Placement> placements_;
};

// cfg with SAW and MAW grown (never shrunk) until the types fit; CapacityError naming the sizes when even the
// largest memories allowed (SAW 24, MAW 28) are too small, or a voxmap exceeds 2^DW voxels on an axis.
DeviceConfig fit_memory(DeviceConfig cfg, const std::vector<const ObjectType*>& types);

// The matrix width that holds every pose of types of such different sizes: M's entries reach A's shell spacing over
// B's voxel (*ratio, the largest), and must lie below 2^(MW - MF - 1); cfg.MW when it suffices.
int matrix_width_for(const DeviceConfig& cfg, const std::vector<const ObjectType*>& types, double* ratio = nullptr);

// The device configuration for testing `types` on `backend`: the default widths at `lanes` (and SB =
// distance_bits when > 0: a distance device; BL = 3, a sparse device, when a type is stored sparse), MW widened for types of very different voxels (matrix_width_for),
// memories grown to fit the types (fit_memory) on every backend but rtl, whose models are built for the default
// widths and depths (CapacityError saying what to change when the types need a wider MW there). `voxcd pair`,
// collide() and Simulation (without a whole configuration) use it.
DeviceConfig device_config_for(const std::string& backend, int lanes, const std::vector<const ObjectType*>& types,
                               int distance_bits = 0);

// Voxmap words a type takes on cfg's device: its states, or its distance field in parity banks (a multiple of 8); a
// type stored sparse on a sparse device: its table and its bricks (each part from a bank boundary on a distance
// device).
uint64_t type_map_words(const DeviceConfig& cfg, const ObjectType& t);
// Shell words a type takes: its points, or on a sparse device its centre shell's sparse words.
uint64_t type_shell_words(const DeviceConfig& cfg, const ObjectType& t);
// Whether the type's map goes sparse on cfg's device (a sparse device, the type's map stored sparse), and its shell
// (a sparse device, the type's centre shell stored sparse): a type stored dense keeps dense jobs on a sparse device.
bool map_is_sparse(const DeviceConfig& cfg, const ObjectType& t);
bool shell_is_sparse(const DeviceConfig& cfg, const ObjectType& t);
// The shell's order as the pair tests place it on cfg's device: its blocks, as sparse words where shell_is_sparse.
detail::ShellOrder shell_order(const DeviceConfig& cfg, const ObjectType& t);

}  // namespace voxcd
