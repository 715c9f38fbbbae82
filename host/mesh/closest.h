// Internal to the library (host/mesh: repair's cells; host/object: distance fields, surface shells): closest points
// on a triangle mesh. A bounding-volume tree over the triangles finds the nearest triangle to a point (exact
// point-triangle distance, ties to the lowest triangle index) within a radius; pseudo-normals give the outward normal
// of the feature the closest point lies on.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace voxcd::detail {

// Where on its triangle a closest point lies: inside the face, on edge k (corners k and k+1 mod 3), or at corner k.
enum class Feature : uint8_t { kFace, kEdge, kVertex };

struct Closest {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // on the triangle
  double d2 = HUGE_VAL;                             // squared distance to the query point
  uint32_t triangle = UINT32_MAX;                   // UINT32_MAX: no triangle within the radius
  Feature feature = Feature::kFace;
  uint8_t index = 0;  // the edge or corner k

  bool found() const { return triangle != UINT32_MAX; }
};

// The point of triangle abc closest to p, and its feature (Ericson, Real-Time Collision Detection, 5.1.5).
// triangle is left at UINT32_MAX for the caller to set.
Closest closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c);

// c with its feature moved to a corner of triangle abc when the closest point lies within eps of it, else to an
// edge within eps (c.point is kept): a point that rounding may put on an edge or corner takes that feature's normal.
Closest snap_feature(Closest c, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& cc,
                     double eps);

class TriangleTree {
 public:
  // Over `triangles` (indices into `vertices`), in the vertices' coordinates; copies what it needs.
  TriangleTree(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<uint32_t, 3>>& triangles);

  // The nearest triangle to p among those at squared distance <= max_d2 (ties: the lowest index); not found() when
  // there is none. The result is the minimum over every triangle, whatever max_d2 is as long as it admits one.
  Closest closest(const Eigen::Vector3d& p, double max_d2 = HUGE_VAL) const;

  // The first triangle the ray o + l d (l > min_l) meets, other than `skip`: its index in UINT32_MAX when none;
  // *l_out its l, *front_out whether it meets the side its normal points to (d . normal < 0).
  uint32_t first_hit(const Eigen::Vector3d& o, const Eigen::Vector3d& d, uint32_t skip, double min_l, double* l_out,
                     bool* front_out) const;

  size_t size() const { return tris_.size(); }

 private:
  struct Tri {
    Eigen::Vector3d a, b, c;
    uint32_t index;
  };
  struct Node {
    double lo[3], hi[3];
    uint32_t first = 0, count = 0;  // leaf: tris_[first, first + count)
    uint32_t right = 0;             // inner node: its left child follows it, its right child is `right`
  };
  uint32_t build(uint32_t first, uint32_t count);
  std::vector<Tri> tris_;
  std::vector<Node> nodes_;
};

// Angle-weighted pseudo-normals (Baerentzen and Aanaes 2005): a face's unit normal inside it, the normalised sum of
// the normals of the faces sharing an edge on the edge, the angle-weighted sum of the faces' normals at a vertex.
// On a closed, consistently oriented mesh the sign of (p - closest) . pseudo-normal is the side p lies on.
class PseudoNormals {
 public:
  PseudoNormals(const std::vector<Eigen::Vector3d>& vertices, const std::vector<std::array<uint32_t, 3>>& triangles);
  // The unit outward normal at a closest point (c.found()).
  Eigen::Vector3d at(const Closest& c) const;

 private:
  std::vector<std::array<uint32_t, 3>> triangles_;
  std::vector<Eigen::Vector3d> face_;    // per triangle, unit
  std::vector<Eigen::Vector3d> edge_;    // per triangle edge 3t + k, unit
  std::vector<Eigen::Vector3d> vertex_;  // per vertex, unit
};

}  // namespace voxcd::detail
