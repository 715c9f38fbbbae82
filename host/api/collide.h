// Pair queries (public: <voxcd/voxcd.h>): collide(a, pose_a, b, pose_b, options) -> Contacts and a batch of poses in
// one call, holding nothing once it returns; a Collider for repeated queries, which keeps the device loaded. The
// device configuration that fits the two objects is derived (objects of different voxels included); the device is
// the cpu backend unless asked otherwise. docs/pairs.md states what a contact guarantees.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "voxcd/host/api/object.h"
#include "voxcd/host/object/frame.h"
#include "voxcd/host/pairs/contact.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// Pose (a rigid pose: world = rotation * local + translation) is in voxcd/host/object/frame.h, Contacts (a pair
// query's contacts and counts) in voxcd/host/pairs/contact.h.

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

// Repeated queries, FCL's pattern: made once with its options, then collide() many times. It holds a device made
// for the last query's two objects, loaded with them, and kept while the next query asks for the same two (other
// objects make a new one); on the cpu backend with threads other than 1, a pool of worker threads of its own. Its
// results equal the free collide()'s. One thread at a time: give each thread its own Collider.
class Collider {
 public:
  explicit Collider(const CollideOptions& options = {});
  ~Collider();
  Collider(Collider&&) noexcept;
  Collider& operator=(Collider&&) noexcept;

  // As the free functions below, with this Collider's options.
  Contacts collide(const Object& a, const Pose& pose_a, const Object& b, const Pose& pose_b);
  std::vector<Contacts> collide(const Object& a, const Object& b, const std::vector<std::pair<Pose, Pose>>& poses);

  const CollideOptions& options() const;
  // Worker threads it holds now, besides the calling thread (0 before its first query, on one thread, or off cpu).
  unsigned worker_threads() const;

  struct Impl;  // internal (host/api/collide.cpp)

 private:
  std::unique_ptr<Impl> impl_;
};

// The contacts of b at pose_b against a at pose_a. On a distance device when both objects carry distance fields
// (the wider field's bits), else on 2-bit voxmaps. CapacityError when the objects cannot share a device (naming
// what to change), RangeError when a pose is not finite or does not fit the device's formats. Each call makes a
// device, loads the two objects and lets both go before it returns (a Collider keeps them for the next query); with
// threads 0 on the cpu backend it runs on one pool of every hardware thread that all callers share (made at the
// first such call, kept until the process exits; calls from several threads take turns on it), with another count
// on a pool of its own for the call.
Contacts collide(const Object& a, const Pose& pose_a, const Object& b, const Pose& pose_b,
                 const CollideOptions& options = {});

// The same at many poses (pose of a, pose of b), in one batch: one result per pose, in order.
std::vector<Contacts> collide(const Object& a, const Object& b, const std::vector<std::pair<Pose, Pose>>& poses,
                              const CollideOptions& options = {});

}  // namespace voxcd
