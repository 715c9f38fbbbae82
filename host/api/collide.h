// One pair query (public: <voxcd/voxcd.h>): collide(a, pose_a, b, pose_b, options) -> Contacts, and a batch of
// poses in one call. The device configuration that fits the two objects is derived (objects of different voxels
// included); the device is the cpu backend unless asked otherwise. docs/pairs.md states what a contact guarantees.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "voxcd/host/api/object.h"
#include "voxcd/host/object/frame.h"
#include "voxcd/host/pairs/contact.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// A rigid pose: world = rotation * local + translation.
using Pose = RigidPose;

struct CollideOptions {
  // All: every contact; First: at most the first contact of each direction (whether they touch, fastest);
  // Count: the number of hits only (Contacts::hits, no contacts).
  Mode mode = Mode::All;
  // Also test B's shell in A's voxmap: finds an object wholly inside the other, and contacts on both surfaces.
  bool both_directions = true;
  // Distance voxmaps (both objects with a field): contacts within this distance outside, world units.
  double margin = 0;
  std::string backend = "cpu";  // device_backends()
  int lanes = 4;
  unsigned threads = 0;         // 0: every hardware thread; never changes the contacts
};

// The contacts of b at pose_b against a at pose_a. On a distance device when both objects carry distance fields
// (the wider field's bits), else on 2-bit voxmaps. CapacityError when the objects cannot share a device (naming
// what to change), RangeError when a pose is not finite or does not fit the device's formats.
Contacts collide(const Object& a, const Pose& pose_a, const Object& b, const Pose& pose_b,
                 const CollideOptions& options = {});

// The same at many poses (pose of a, pose of b), in one batch: one result per pose, in order.
std::vector<Contacts> collide(const Object& a, const Object& b, const std::vector<std::pair<Pose, Pose>>& poses,
                              const CollideOptions& options = {});

}  // namespace voxcd
