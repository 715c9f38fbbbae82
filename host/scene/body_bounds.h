// A body's world bounds, what the broadphase takes (body_bounds.cpp).
#pragma once

#include <Eigen/Core>

#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/scene/body.h"

namespace voxcd {

// A body's world bounds: its type's smallest enclosing sphere and the world box of its type's local box.
BodyBounds body_bounds(const ObjectType& t, const Body& b);
// The same, given R = b's rotation matrix and c = R * (t.lo + t.hi) / 2 + b's translation (its box's centre).
BodyBounds body_bounds(const ObjectType& t, const Body& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& c);

}  // namespace voxcd
