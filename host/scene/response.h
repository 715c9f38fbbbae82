// The response to a touching pair (response.cpp; Simulation::respond_all applies it to a frame's pairs).
#pragma once

#include <Eigen/Core>

#include "voxcd/host/scene/body.h"

namespace voxcd {

// The response to a touching pair, n the unit normal from A towards B: when they approach along n, the velocity
// components along n are exchanged (an elastic impulse between equal masses) and both spins reversed; a dynamic
// body against one that is not (static or kinematic: as of infinite mass) has its component along n reflected and
// its spin reversed, the other unchanged. False, and nothing changed, when they separate already or neither is
// dynamic.
bool respond(Body& a, Body& b, const Eigen::Vector3d& n);

}  // namespace voxcd
