// A body's world bounds for the broadphase: its type's enclosing sphere, its world box and its motion bound.
#include "voxcd/host/scene/body_bounds.h"

#include <Eigen/Geometry>

namespace voxcd {

BodyBounds body_bounds(const ObjectType& t, const Body& b) {
  const Eigen::Matrix3d R = b.pose.rotation.toRotationMatrix();
  return body_bounds(t, b, R, R * (0.5 * (t.lo + t.hi)) + b.pose.translation);
}

BodyBounds body_bounds(const ObjectType& t, const Body& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& c) {
  BodyBounds bb;
  bb.centre = R * t.centre + b.pose.translation;
  bb.radius = t.radius;
  const Eigen::Vector3d e = R.cwiseAbs() * (0.5 * (t.hi - t.lo));
  bb.box.lo = c - e;
  bb.box.hi = c + e;
  // No point of the body is farther than |centre| + radius from its origin.
  bb.max_speed = b.velocity.norm() + b.spin.norm() * (t.centre.norm() + t.radius);
  bb.max_accel = 0;  // velocities change only in responses, which flag the body
  return bb;
}

}  // namespace voxcd
