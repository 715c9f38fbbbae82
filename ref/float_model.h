// The same transform in double precision, the quantisation of a float pose into a job, and the documented
// bound on how far the fixed-point path can be from exact arithmetic (docs/contract.md derives it).
#pragma once

#include "voxcd/ref/config.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// A pose of A's shell in B's voxel grid: p_B = M * p_A + t, with p_A in A's voxel units and p_B in B's.
// M is the rotation from A's frame to B's times s_A / s_B; t is in B's voxel units.
struct FloatPose {
  double M[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  double t[3] = {0, 0, 0};
};

FixedFormat matrix_format(const DeviceConfig& cfg);       // MW bits, MF fraction
FixedFormat translation_format(const DeviceConfig& cfg);  // TW bits, TF fraction
FixedFormat point_format(const DeviceConfig& cfg);        // PW bits, PF fraction

// Writes the quantised pose into job.M and job.t. Throws RangeError naming the entry (M01, T2, ...) and its
// format when an entry is not finite or does not fit.
void quantize_pose(const DeviceConfig& cfg, const FloatPose& pose, Job& job);
// Quantises a point in the shell object's voxel units into a shell word; RangeError names `what`.
ShellWord quantize_point(const DeviceConfig& cfg, const double p[3], const std::string& what);
// The real value of a shell word.
void point_value(const DeviceConfig& cfg, const ShellWord& w, double p[3]);

// The double-precision model: out = M * p + t.
void float_transform(const FloatPose& pose, const double p[3], double out[3]);

// Bound, in B's voxel units, on |fixed-point result - exact result| on axis i for the float point p, given the
// job's quantised matrix:  2^-(MF+1) * |p|_1  +  |Mq_i|_1 * 2^-(PF+1)  +  2^-(TF+1).
// Set point_quantised when p is exactly a shell word's value (then its term is 0).
double error_bound(const DeviceConfig& cfg, const Job& job, int axis, const double p[3], bool point_quantised);
// The design's per-axis bound for points with max|p_j| <= max_abs_p:
// 3 * 2^-(MF+1) * max_abs_p + |Mq_i|_1 * 2^-(PF+1) + 2^-(TF+1), the largest over the three axes.
double error_bound_max(const DeviceConfig& cfg, const Job& job, double max_abs_p);

}  // namespace voxcd
