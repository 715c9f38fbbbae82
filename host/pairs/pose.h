// From world poses of two objects to the device job that tests A's shell against B's voxmap (poses as text and
// numbers: pose_text.h).
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "voxcd/host/object/frame.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// A distance job's threshold for a margin of `margin` world units on a map of `voxel` world units per voxel and
// `step` voxels per node unit: floor(margin / (voxel * step) * 2^(3 WB)) (a hit is D <= threshold, D an integer).
// RangeError naming the margin and the range it must lie in when it is not finite or does not fit IW bits.
int64_t distance_threshold(const DeviceConfig& cfg, double margin, double voxel, double step);

// The pose of A's shell grid in B's voxmap grid: g_B = M g_A + t, with M = R_B^T R_A * (vA / vB). Throws
// RangeError when a pose is not finite (NaN or infinite rotation or translation) naming which.
FloatPose relative_pose(const RigidPose& a, const GridFrame& shell_a, const RigidPose& b, const GridFrame& map_b);

// relative_pose quantised into job.M and job.t (RangeError naming the entry when it does not fit; the job is
// left unchanged then).
void pose_job(const DeviceConfig& cfg, const RigidPose& a, const GridFrame& shell_a, const RigidPose& b,
              const GridFrame& map_b, Job& job);

}  // namespace voxcd
