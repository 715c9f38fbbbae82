// Broadphases: from every body's bounding volumes to the pairs that may touch. Every broadphase sits behind one
// interface and reports exactly the pairs its predicate admits (sphere overlap or box overlap), sorted, each
// once, every frame; tests/host/broadphase/test_broadphase.cpp checks each against brute force of the same predicate.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace voxcd {

class ThreadPool;  // ref/util/thread_pool.h

struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  // Closed boxes: touching faces overlap.
  bool overlaps(const Aabb& o) const {
    return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all();
  }
};

// What a broadphase knows of one body in one frame (world coordinates; time in frames).
struct BodyBounds {
  Aabb box;                                              // encloses the body
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();      // of a sphere that encloses the body
  double radius = 0;
  // Bounds on the body's motion from this frame on, valid until a frame where `moved_unexpectedly` is set: no
  // point of the body moves faster than max_speed (world units per frame) plus max_accel * elapsed frames.
  double max_speed = 0;
  double max_accel = 0;
  bool moved_unexpectedly = false;  // a collision response or a teleport changed its motion since the last frame
};

// Two closed spheres overlap (touching counts).
inline bool spheres_overlap(const BodyBounds& a, const BodyBounds& b) {
  const double r = a.radius + b.radius;
  return (a.centre - b.centre).squaredNorm() <= r * r;
}

using BodyPair = std::pair<uint32_t, uint32_t>;  // first < second

struct BroadphaseStats {
  uint64_t overlap_tests = 0;  // bounding-volume tests done in the last update
  uint64_t pairs = 0;          // pairs reported by the last update
};

class Broadphase {
 public:
  virtual ~Broadphase() = default;
  virtual std::string name() const = 0;
  // "sphere" or "box": the predicate whose pairs this broadphase reports ("all" for all-pairs: every pair).
  virtual std::string predicate() const = 0;
  // One frame: every body's bounds, in the same order each frame. A different body count starts afresh.
  virtual void update(const std::vector<BodyBounds>& bodies, uint64_t frame) = 0;
  // The pairs of the last update whose bounding volumes overlap under predicate(): ascending, each once.
  virtual const std::vector<BodyPair>& pairs() const = 0;
  virtual BroadphaseStats stats() const = 0;
  // Whether update() builds on the previous frame's bodies (by index): a caller that changes which bodies it
  // passes, keeping their count, must then start a fresh broadphase. The others rebuild every frame.
  virtual bool keeps_state() const { return false; }
  // Threads for update() (grid: the pair search and the sort; the others run on the calling thread). The pairs
  // never depend on it. Null: the calling thread.
  void set_pool(ThreadPool* pool) { pool_ = pool; }

 protected:
  ThreadPool* pool_ = nullptr;
};

// "all" (every pair, the paper's baseline), "sphere" (bounding spheres, all pairs tested), "sap" (sort and sweep on
// AABBs, the paper's fast AABB), "coherent" (sweep and prune kept sorted by insertion sort from the last frame),
// "queue" (priority queue of wake-up times from the motion bounds, sphere predicate), "tree" (dynamic AABB tree,
// for large N), "grid" (uniform grid rebuilt every frame, in levels by box size).
std::vector<std::string> broadphase_names();
// Throws std::invalid_argument naming the unknown name and listing the known ones.
std::unique_ptr<Broadphase> make_broadphase(const std::string& name);

}  // namespace voxcd
