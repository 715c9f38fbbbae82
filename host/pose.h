// From world poses of two objects to the device job that tests A's shell against B's voxmap.
#pragma once

#include <Eigen/Geometry>

#include "ref/config.h"
#include "ref/float_model.h"
#include "ref/types.h"

namespace voxcd {

// A rigid pose: world = rotation * local + translation.
struct RigidPose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
};

// A regular grid in an object's own frame: grid coordinate g maps to local = origin + voxel * g.
// For a voxmap, voxel (i, j, k) covers g in [i, i+1) x [j, j+1) x [k, k+1); shell words are grid coordinates.
struct GridFrame {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double voxel = 1.0;
};

// The pose of A's shell grid in B's voxmap grid: g_B = M g_A + t, with M = R_B^T R_A * (vA / vB). Throws
// RangeError when a pose is not finite (NaN or infinite rotation or translation) naming which.
FloatPose relative_pose(const RigidPose& a, const GridFrame& shell_a, const RigidPose& b, const GridFrame& map_b);

// relative_pose quantised into job.M and job.t (RangeError naming the entry when it does not fit; the job is
// left unchanged then).
void pose_job(const DeviceConfig& cfg, const RigidPose& a, const GridFrame& shell_a, const RigidPose& b,
              const GridFrame& map_b, Job& job);

}  // namespace voxcd
