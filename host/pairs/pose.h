// From world poses of two objects to the device job that tests A's shell against B's voxmap.
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

// A pose from a translation and a rotation in degrees about x, then y, then z (world axes): R = Rz Ry Rx, as
// `voxcd pair --pose tx,ty,tz,rx,ry,rz` gives B's pose in A's frame.
RigidPose euler_pose(const Eigen::Vector3d& translation, const Eigen::Vector3d& degrees = Eigen::Vector3d::Zero());

// The numbers of "tx,ty,tz[,rx,ry,rz]" (euler_pose's arguments), three or six; std::invalid_argument saying what is
// wrong with `s` ("'x' in '1,x,3' is not a number", or "... not a finite number" with `finite`, where NaN and
// infinities are refused too; "'1,2' has 2 numbers; give tx,ty,tz or tx,ty,tz,rx,ry,rz").
std::vector<double> parse_pose_numbers(const std::string& s, bool finite);

// The pose of A's shell grid in B's voxmap grid: g_B = M g_A + t, with M = R_B^T R_A * (vA / vB). Throws
// RangeError when a pose is not finite (NaN or infinite rotation or translation) naming which.
FloatPose relative_pose(const RigidPose& a, const GridFrame& shell_a, const RigidPose& b, const GridFrame& map_b);

// relative_pose quantised into job.M and job.t (RangeError naming the entry when it does not fit; the job is
// left unchanged then).
void pose_job(const DeviceConfig& cfg, const RigidPose& a, const GridFrame& shell_a, const RigidPose& b,
              const GridFrame& map_b, Job& job);

}  // namespace voxcd
