#include "voxcd/host/api/collide.h"

#include <algorithm>
#include <memory>

#include "voxcd/host/api/access.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

// The device of the last query, kept while the next asks for the same two objects: a collider loads the objects
// into the device's memories once.
struct Collider::Impl {
  CollideOptions options;
  std::shared_ptr<ThreadPool> pool;  // given (the free collide()'s shared pool), else the device's own
  std::shared_ptr<const ObjectType> a, b;
  std::unique_ptr<PairCollider> collider;

  PairCollider& collider_for(const Object& oa, const Object& ob) {
    const std::shared_ptr<const ObjectType>& ta = ApiAccess::type_of(oa);
    const std::shared_ptr<const ObjectType>& tb = ApiAccess::type_of(ob);
    if (collider && a == ta && b == tb) return *collider;
    collider.reset();
    a.reset(), b.reset();
    const int bits = oa.distance_bits() && ob.distance_bits() ? std::max(oa.distance_bits(), ob.distance_bits()) : 0;
    const DeviceConfig cfg = device_config_for(options.backend, options.lanes, {ta.get(), tb.get()}, bits);
    DeviceOptions dopt;
    dopt.threads = options.threads;
    dopt.pool = pool;
    collider = std::make_unique<PairCollider>(make_device(options.backend, cfg, dopt),
                                              std::vector<std::shared_ptr<const ObjectType>>{ta, tb});
    a = ta, b = tb;
    return *collider;
  }

  std::vector<Contacts> collide(const Object& oa, const Object& ob, const std::vector<std::pair<Pose, Pose>>& poses) {
    std::vector<PairRequest> reqs(poses.size());
    for (size_t i = 0; i < poses.size(); ++i) {
      reqs[i].a = 0;
      reqs[i].b = 1;
      reqs[i].pose_a = poses[i].first;
      reqs[i].pose_b = poses[i].second;
    }
    PairOptions p;
    p.mode = options.mode;
    p.both_directions = options.both_directions;
    p.margin = options.margin;
    return collider_for(oa, ob).collide(reqs, p);
  }
};

Collider::Collider(const CollideOptions& options) : impl_(std::make_unique<Impl>()) { impl_->options = options; }
Collider::~Collider() = default;
Collider::Collider(Collider&&) noexcept = default;
Collider& Collider::operator=(Collider&&) noexcept = default;

Contacts Collider::collide(const Object& a, const Pose& pose_a, const Object& b, const Pose& pose_b) {
  return impl_->collide(a, b, {{pose_a, pose_b}}).at(0);
}

std::vector<Contacts> Collider::collide(const Object& a, const Object& b,
                                        const std::vector<std::pair<Pose, Pose>>& poses) {
  return impl_->collide(a, b, poses);
}

const CollideOptions& Collider::options() const { return impl_->options; }

unsigned Collider::worker_threads() const {
  if (!impl_->collider) return 0;
  const std::shared_ptr<ThreadPool>& pool = impl_->collider->pool();
  return pool ? pool->size() - 1 : 0;
}

namespace {

// The free collide()'s pool for threads 0 (every hardware thread), shared by every caller: one pool, whatever the
// number of threads that query.
std::shared_ptr<ThreadPool> shared_pool() {
  static const std::shared_ptr<ThreadPool> pool = std::make_shared<ThreadPool>(0);
  return pool;
}

}  // namespace

Contacts collide(const Object& a, const Pose& pose_a, const Object& b, const Pose& pose_b,
                 const CollideOptions& options) {
  return collide(a, b, {{pose_a, pose_b}}, options).at(0);
}

std::vector<Contacts> collide(const Object& a, const Object& b, const std::vector<std::pair<Pose, Pose>>& poses,
                              const CollideOptions& options) {
  Collider::Impl once;
  once.options = options;
  if (options.threads == 0 && options.backend == "cpu") once.pool = shared_pool();
  return once.collide(a, b, poses);
}

}  // namespace voxcd
