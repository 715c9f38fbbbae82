// Internal to the voxeliser (host/object/voxelize.cpp): the generalized winding number of a triangle soup as an exact
// integer part plus the winding number of a few cap triangles. The caps close the soup's boundary (a cone from
// each boundary loop's centroid), so soup - caps is a closed chain whose winding number is the signed count of ray
// crossings; the caps' own winding number is a sum of solid angles, evaluated with a tree (Barill et al. 2018:
// exact near, dipole far). Coordinates are the voxeliser's grid coordinates (voxels).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace voxcd::detail {

using GridPoint = std::array<int64_t, 3>;  // snapped grid coordinates, the voxeliser's fixed point

// A triangle of the closed chain: corners in snapped grid coordinates, and its multiplicity (+1 for a triangle of
// the soup, -1 for a cap).
struct ChainTriangle {
  GridPoint a, b, c;
  int32_t weight;
};

// The caps of the soup `tris` (indices into `q`): for every closed walk of its boundary (edges whose uses do not
// cancel), the cone from the walk's centroid, so that the caps' boundary equals the soup's. Empty for a closed
// soup.
std::vector<ChainTriangle> boundary_caps(const std::vector<GridPoint>& q,
                                         const std::vector<std::array<uint32_t, 3>>& tris, int frac_bits);

// Winding number of triangle abc seen from the origin: its signed solid angle / 4 pi (Van Oosterom & Strackee).
double triangle_winding(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

// The caps' winding number as a field over grid coordinates.
class CapField {
 public:
  CapField(const std::vector<ChainTriangle>& caps, int frac_bits);
  bool empty() const { return tris_.empty(); }
  // The winding number of the caps at p: exact for nodes nearer than kFar times their radius, dipole beyond.
  double value(const Eigen::Vector3d& p) const;
  // need(x, y, z, near, bound): near is the exact winding number of the caps close to the voxel's centre and
  // bound a rigorous bound on the rest (area / (4 pi distance^2) per far node), so the caps' winding number lies
  // in [near - bound, near + bound]; near is NaN when the rest was not bounded below the limit.
  using NeedFn = std::function<void(uint32_t, uint32_t, uint32_t, double, double)>;
  // Calls need for each voxel in [lo, hi) (voxel indices; centre at index + 1/2) where the caps' winding number
  // may reach `limit` in magnitude. Everywhere else it is proved below `limit`.
  void uncertain_voxels(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, double limit,
                        const NeedFn& need) const;

 private:
  struct Tri {
    Eigen::Vector3d a, b, c;
    double weight;
  };
  struct Node {
    Eigen::Vector3d centre;     // of its bounding box
    double radius = 0;          // half the box's diagonal
    double abs_area = 0;        // sum of |weight| x area
    Eigen::Vector3d dipole;     // sum of weight x vector area
    Eigen::Vector3d centroid;   // area-weighted centre of its triangles
    uint32_t first = 0, count = 0;  // leaf: tris_[first, first + count)
    uint32_t left = 0, right = 0;   // inner: children (count == 0)
  };
  uint32_t build(uint32_t first, uint32_t count);
  // The voxels of block [lo, hi) from the nodes in lists[depth] (consumed), the bound gathered so far; the lists
  // after `depth` are the recursion's working lists.
  void certify(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, size_t depth,
               std::vector<std::vector<uint32_t>>& lists, double bound, double limit, const NeedFn& need) const;
  // certify on the block's eight children, each from the open nodes in lists[depth + 1].
  void certify_children(const std::array<uint32_t, 3>& lo, const std::array<uint32_t, 3>& hi, size_t depth,
                        std::vector<std::vector<uint32_t>>& lists, double bound, double limit,
                        const NeedFn& need) const;
  std::vector<Tri> tris_;
  std::vector<Node> nodes_;
};

}  // namespace voxcd::detail
