#include "voxcd/host/api/collide.h"

#include <algorithm>
#include <memory>

#include "voxcd/host/device/device.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/pairs/collide.h"

namespace voxcd {

namespace {

// The collider of the last query on this thread, kept while the next asks for the same objects and device: a
// collider loads the objects into the device's memories once.
struct Cached {
  std::shared_ptr<const ObjectType> a, b;
  std::string backend;
  int lanes = 0;
  unsigned threads = 0;
  std::unique_ptr<PairCollider> collider;
};

PairCollider& collider_for(const Object& a, const Object& b, const CollideOptions& o) {
  thread_local Cached c;
  if (c.collider && c.a == a.type() && c.b == b.type() && c.backend == o.backend && c.lanes == o.lanes &&
      c.threads == o.threads)
    return *c.collider;
  c.collider.reset();
  const int bits = a.distance_bits() && b.distance_bits() ? std::max(a.distance_bits(), b.distance_bits()) : 0;
  const DeviceConfig cfg = device_config_for(o.backend, o.lanes, {a.type().get(), b.type().get()}, bits);
  DeviceOptions dopt;
  dopt.threads = o.threads;
  c.collider = std::make_unique<PairCollider>(make_device(o.backend, cfg, dopt),
                                              std::vector<std::shared_ptr<const ObjectType>>{a.type(), b.type()});
  c.a = a.type(), c.b = b.type(), c.backend = o.backend, c.lanes = o.lanes, c.threads = o.threads;
  return *c.collider;
}

PairOptions pair_options(const CollideOptions& o) {
  PairOptions p;
  p.mode = o.mode;
  p.both_directions = o.both_directions;
  p.margin = o.margin;
  return p;
}

}  // namespace

Contacts collide(const Object& a, const Pose& pose_a, const Object& b, const Pose& pose_b,
                 const CollideOptions& options) {
  return collide(a, b, {{pose_a, pose_b}}, options).at(0);
}

std::vector<Contacts> collide(const Object& a, const Object& b, const std::vector<std::pair<Pose, Pose>>& poses,
                              const CollideOptions& options) {
  std::vector<PairRequest> reqs(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    reqs[i].a = 0;
    reqs[i].b = 1;
    reqs[i].pose_a = poses[i].first;
    reqs[i].pose_b = poses[i].second;
  }
  return collider_for(a, b, options).collide(reqs, pair_options(options));
}

}  // namespace voxcd
