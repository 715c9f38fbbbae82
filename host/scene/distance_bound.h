// A lower bound on the distance between two bodies' solids from the distance device (docs/simulate.md, "The
// bound"), and from their enclosing spheres and contact boxes: what continuous collision (ccd.h) steps by.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <cstdint>
#include <memory>
#include <vector>

#include "voxcd/host/pairs/collider.h"

namespace voxcd {

// Per object type, the terms of the bound; then per pair, from one both-directions query (ALL mode at margin()).
class DistanceBound {
 public:
  // Per type, from the distance device cfg. std::invalid_argument naming the type when it has no distance field or
  // its band is too narrow to bound a distance (at most the interpolation's error).
  DistanceBound(const std::vector<std::shared_ptr<const ObjectType>>& types, const DeviceConfig& cfg);
  // The query's margin, world units: the largest distance every type's field still represents.
  double margin() const { return margin_; }
  // Contact (ContinuousCollision) when a pair's bound is at most this fraction of the finer of the two voxels;
  // every type's band must exceed s + sqrt(3) + this, in voxels, for a bound to be a bound.
  static constexpr double kTolerance = 0.5;
  // World units, for bodies of types ta, tb and a result of the query of pair (A, B) (both directions); may be
  // negative (touching or overlapping).
  double device(uint32_t ta, uint32_t tb, const PairResult& r) const;
  // The bound of the bounding spheres and oriented contact boxes (no device), for bodies of rotations Ra, Rb and
  // translations Ta, Tb: world units, may be negative.
  double geometric(uint32_t ta, const Eigen::Matrix3d& Ra, const Eigen::Vector3d& Ta, uint32_t tb,
                   const Eigen::Matrix3d& Rb, const Eigen::Vector3d& Tb) const;

 private:
  struct Type {
    double field_error = 0;  // world: rounding, interpolation and truncation of a looked-up distance
    double fixed_error = 0;  // world per unit voxel of the map: sqrt(3) x the fixed-point path's bound, in voxels
    double shell_gap = 0;    // world: every surface point is this close to a shell point
    double point_error = 0;  // world: the shell words' rounding (0 where they are exact)
    double pad = 0;          // world: the grid's margin around the contact box
    double none = 0;         // world: the distance a point inside the grid that reports nothing has at least
    double voxel = 0;
    double pmax = 0;         // the largest shell coordinate, shell units
    Eigen::Vector3d half = Eigen::Vector3d::Zero(), mid = Eigen::Vector3d::Zero();  // contact box
    double radius = 0;
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  };
  double direction(const Type& shell, const Type& map, double min_distance, bool any) const;
  std::vector<Type> types_;
  double margin_ = 0, fixed_unit_ = 0;
};

}  // namespace voxcd
