// Frames of an object: its grids in its own frame (GridFrame) and its placement in the world (Pose; public:
// <voxcd/voxcd.h>).
#pragma once

#include <Eigen/Geometry>

namespace voxcd {

// A rigid pose: world = rotation * local + translation.
struct Pose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};
// The same type by the name the library's folders use (a pose of a body, a pair's poses).
using RigidPose = Pose;

// A regular grid in an object's own frame: grid coordinate g maps to local = origin + voxel * g.
// For a voxmap, voxel (i, j, k) covers g in [i, i+1) x [j, j+1) x [k, k+1); shell words are grid coordinates.
struct GridFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double voxel = 1.0;
};

}  // namespace voxcd
