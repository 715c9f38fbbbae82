// The sparse point shell (docs/contract.md, "Shell bricks"): the centre shell's points as shell bricks of 4^3 voxels of
// the shell grid, one occupancy bit a voxel, ordered into chains of neighbouring bricks. A device generates the points
// from the words (ref's shell_points); the host keeps one 32-bit normal a point. docs/objects.md, "Sparse objects".
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "voxcd/host/object/point_shell.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// A shell brick holds voxels 4 b + d of the shell grid, d in 0..3 per axis, voxel d at bit d_x + 4 d_y + 16 d_z.
constexpr uint32_t kShellBrickEdge = 4;

struct SparseShell {
  GridPlacement grid;                           // the shell grid, as PointShell::grid
  std::vector<std::array<uint16_t, 3>> bricks;  // in chain order: brick b covers voxels 4 b .. 4 b + 3
  std::vector<uint64_t> masks;                  // each brick's occupancy (not 0)
  // One a point, in point order: the bricks in order, each brick's set bits in ascending order (ref's shell_points).
  // Octahedral, 16 bits a coordinate (host/object/detail/octahedral.h).
  std::vector<uint32_t> normals;

  size_t size() const { return normals.size(); }
  bool empty() const { return bricks.empty(); }
  // Origin words: one before the first brick, and one wherever a brick is not a step of -2..1 bricks per axis from
  // the one before it.
  uint64_t origin_words() const;
  // Shell words: bricks and origin words.
  uint64_t words() const { return bricks.size() + origin_words(); }
  // Device memory with cfg's PW: ceil(3 PW / 8) bytes a word.
  uint64_t bytes(const DeviceConfig& cfg = DeviceConfig{}) const { return words() * ((3 * uint64_t(cfg.PW) + 7) / 8); }
  // The device's words (ref/sparse.h): origin words as above, then a brick word per brick (its step from the one
  // before, 0 after an origin word). ref's shell_points of them are the points in point order, each the centre of its
  // voxel with PF fraction bits. std::invalid_argument when 3 PW < 72, PF < 1, or an origin does not fit its word.
  std::vector<ShellWord> device_words(const DeviceConfig& cfg) const;
  // The voxel of every point, in point order.
  std::vector<std::array<uint32_t, 3>> cells() const;
  Eigen::Vector3d normal(size_t k) const;
  // The same points as a dense centre shell: cells in linear-index order, points in the object's frame, the normals
  // decoded.
  PointShell to_point_shell() const;
  // The sparse form of a centre shell (std::invalid_argument for a shell on the surface): its bricks in chain order
  // (detail/shell_chain.h), its normals encoded.
  static SparseShell from_point_shell(const PointShell& s);
};

// The shell point_shell(mesh, opt) builds without opt.on_surface (the same grid and points; each normal is the same
// triangle's, encoded), built layer by layer into shell bricks without a dense array of the shell grid, so that it
// can be made at any resolution opt.max_dim allows. MeshError as point_shell throws them.
SparseShell sparse_point_shell(const Mesh& mesh, const ShellOptions& opt);

}  // namespace voxcd
