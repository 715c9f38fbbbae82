// Poses as people and tools write them: the one parser every door uses (`voxcd pair --pose`, `voxcd view --pose`,
// the viewer's page, the Python module's poses) and the text it reads back. A pose the tool prints goes back in.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <string>

#include "voxcd/host/object/frame.h"

namespace voxcd {

// A pose from a translation and a rotation in degrees about x, then y, then z (world axes): R = Rz Ry Rx, as
// `voxcd pair --pose tx,ty,tz,rx,ry,rz` gives B's pose in A's frame.
RigidPose euler_pose(const Eigen::Vector3d& translation, const Eigen::Vector3d& degrees = Eigen::Vector3d::Zero());

// The degrees about x, y and z that euler_pose turns into rotation `q` (ry in [-90, 90]).
Eigen::Vector3d euler_degrees(const Eigen::Quaterniond& q);

// The pose of n numbers, in one of five forms:
//    3  tx, ty, tz                        a translation
//    6  tx, ty, tz, rx, ry, rz            then degrees about x, then y, then z (euler_pose)
//    7  tx, ty, tz, qw, qx, qy, qz        then a unit quaternion (as the tool prints a pose: pose_text); one whose norm
//                                         is within 1e-12 of 1 is kept as it is, one within 1e-3 normalised
//   12  r00 r01 r02 tx r10 ... r22 tz     a 3 x 4 matrix [R | t], row-major; R a rotation to 1e-6
//   16  the 3 x 4 above, then 0 0 0 1     a 4 x 4 homogeneous matrix, row-major
// std::invalid_argument saying what is wrong, for the caller to prefix with where the pose came from: another count
// ("4 numbers; give 3 (tx,ty,tz), ..."), a number that is not finite ("number 4 of 6 (nan) is not finite"), a
// quaternion of another norm, a matrix that is not a rotation or whose last row is not 0 0 0 1.
RigidPose pose_from_numbers(const double* v, size_t n);

// The pose of a text: its numbers comma separated ("1,0,0,90,0,0"), or JSON: an array of them, or the object
// `voxcd pair --json` prints for a pose ({"translation": [tx, ty, tz], "rotation_wxyz": [qw, qx, qy, qz]}).
// std::invalid_argument quoting the word or the text ("'x' in '1,x,3' is not a number", "'nan' in 'nan,0,0' is not a
// finite number", "'1,2' has 2 numbers; give 3 (tx,ty,tz), ...").
RigidPose parse_pose(const std::string& text);

// "tx,ty,tz,qw,qx,qy,qz", each number with 17 significant digits: parse_pose(pose_text(p)) is p, bit for bit.
std::string pose_text(const RigidPose& p);

}  // namespace voxcd
