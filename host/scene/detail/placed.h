// A body's rotation matrix and the world centre of its type's box: what the bounds and the mid-phase's box test take.
#pragma once

#include <Eigen/Geometry>

#include "voxcd/host/object/object_type.h"
#include "voxcd/host/scene/body.h"

namespace voxcd::detail {

struct Placed {
  Eigen::Matrix3d R;
  Eigen::Vector3d c;
};
// (R from a local, not read back from the result: a 16-byte load across two stores that were just made stalls.)
inline Placed placed(const ObjectType& t, const Body& b) {
  const Eigen::Matrix3d R = b.pose.rotation.toRotationMatrix();
  const Eigen::Vector3d c = R * (0.5 * (t.lo + t.hi)) + b.pose.translation;
  return {R, c};
}

}  // namespace voxcd::detail
