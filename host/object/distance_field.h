// The signed distance field of an object, sampled at the nodes of its voxmap's grid and quantised as a distance
// device stores it (docs/contract.md, "Distance voxmaps"; docs/objects.md): node (X, Y, Z) sits at the voxel corner
// origin + voxel * (X, Y, Z), its value is the exact distance to the mesh's surface in voxels, negative inside the
// solid, divided by the step and rounded, clamped to the band.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/ref/config.h"

namespace voxcd {

// The bits a distance field's node values may have: the SB of a distance device.
inline constexpr std::array<int, 3> kDistanceBits = {4, 8, 16};
inline bool valid_distance_bits(int bits) {
  return std::find(kDistanceBits.begin(), kDistanceBits.end(), bits) != kDistanceBits.end();
}
// "4, 8 or 16": kDistanceBits for messages.
inline std::string distance_bits_text() {
  std::string s;
  for (size_t i = 0; i < kDistanceBits.size(); ++i)
    s += (i == 0 ? "" : i + 1 == kDistanceBits.size() ? " or " : ", ") + std::to_string(kDistanceBits[i]);
  return s;
}

struct DistanceField {
  int bits = 0;       // SB: 4, 8 or 16; 0 for an object without a field
  double step = 0;    // voxels per unit of a node value: the band is +-2^(bits-1) * step voxels
  std::array<uint32_t, 3> dims = {0, 0, 0};  // cells per axis (the voxmap's); nodes are dims + 1 per axis
  std::vector<int16_t> q;                    // node (X, Y, Z) at X + (nx+1) * (Y + (ny+1) * Z)

  bool empty() const { return bits == 0; }
  int qmax() const { return (1 << (bits - 1)) - 1; }  // far outside (and every value the band clamps to it)
  int qmin() const { return -(1 << (bits - 1)); }     // far inside
  double band() const { return step * double(1 << (bits - 1)); }  // voxels
  uint64_t node_index(uint64_t X, uint64_t Y, uint64_t Z) const {
    return X + (uint64_t(dims[0]) + 1) * (Y + (uint64_t(dims[1]) + 1) * Z);
  }
  int at(uint64_t X, uint64_t Y, uint64_t Z) const { return q[node_index(X, Y, Z)]; }
  // Every node of cell (x, y, z) is <= 0: at any margin >= 0 every point of the cell is a hit. Such a cell lies
  // inside, or is a conservative cell (a surface the nodes do not resolve: docs/objects.md), where a contact has the
  // 2-bit voxmap's bound rather than the field's (docs/pairs.md).
  bool hits_everywhere(uint64_t x, uint64_t y, uint64_t z) const {
    for (int k = 0; k < 8; ++k)
      if (at(x + (k & 1), y + (k >> 1 & 1), z + (k >> 2 & 1)) > 0) return false;
    return true;
  }
  // Cell (x, y, z) shares a node with a conservative cell of this field on voxmap `vm` (its grid): a surface cell
  // whose nodes are all <= 0. A hit there has the 2-bit voxmap's bound, (sqrt(3) + e) voxels, rather than the
  // field's (docs/pairs.md): the lowered nodes reach into the cells around.
  bool near_conservative(const Voxmap& vm, uint32_t x, uint32_t y, uint32_t z) const;

  // The trilinear interpolant of the node values at grid coordinates g (voxel units from the grid's origin),
  // in voxels (value * step), with its gradient (per voxel) when `gradient` is not null. g outside the grid is
  // clamped to it. The device computes the same interpolant in exact integers (with truncated weights).
  double sample(const Eigen::Vector3d& g, Eigen::Vector3d* gradient = nullptr) const;

  // The device's memory image of this field for cfg (cfg.distance(), cfg.SB == bits): the 8 parity banks of
  // docs/contract.md, starting at a bank boundary; slots that hold no node are 0.
  std::vector<uint64_t> device_words(const DeviceConfig& cfg) const;
};

struct DistanceOptions {
  int bits = 8;            // SB: 4, 8 or 16
  double band = 4.0;       // voxels: the step is band / 2^(bits-1)
  unsigned threads = 0;    // 0: one per hardware thread; never changes the result
  // Lower the nodes of the cells the field does not resolve (docs/objects.md, "Conservative cells"). Off gives the
  // measured field alone (tests compare it with brute force); every object voxcd builds has it on.
  bool conservative = true;
};

// The field of a mesh as repair() left it, on the voxmap's grid: each node's exact distance to the nearest
// triangle (point-triangle distance), its sign from the solid voxelize computed (inside: negative; sheets, which
// bound no solid, give the unsigned distance). Then (opt.conservative) every cell whose surface the nodes do not
// resolve (a part thinner than a voxel, a sharp edge, a sheet) is made conservative: its nodes are lowered to at most 0, so that every point
// in it is a hit (docs/objects.md, "Conservative cells"); *conservative, when given, gets their number. Only the
// voxmap's grid is used. MeshError for bits not 4, 8 or 16, a band that is not finite and > 0, or a point cloud.
// The result never depends on opt.threads.
DistanceField distance_field(const Mesh& mesh, const Voxmap& voxmap, const DistanceOptions& opt,
                             uint64_t* conservative = nullptr);

}  // namespace voxcd
