// N-body scenes: instances of object types with rigid state, and the paper's simulation environment (a cube of side
// 100 at a density of 2.5%, random momentum, Euler integration, wall and object-object response), stepped frame by
// frame with a broadphase and pair tests on a device backend. docs/simulate.md describes it.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/pairs/collider.h"
#include "voxcd/host/scene/body.h"
#include "voxcd/host/scene/body_bounds.h"
#include "voxcd/host/scene/ccd.h"
#include "voxcd/host/scene/errors.h"
#include "voxcd/host/scene/exchange.h"
#include "voxcd/host/scene/partition.h"
#include "voxcd/host/scene/placement.h"
#include "voxcd/host/scene/response.h"
#include "voxcd/host/scene/run_config.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

struct Scene {
  double side = 100;  // the environment: the cube [0, side]^3, walls on its faces
  std::vector<std::shared_ptr<const ObjectType>> types;
  std::vector<Body> bodies;
};

// The paper's scene: 64 objects filling 2.5% of a cube of side 100, so 390.625 cubic units each, at voxel 1.
constexpr double kPaperObjectVolume = 0.025 * 100 * 100 * 100 / 64;

// The default voxel of an object of `volume` cubic world units and longest side `extent`: the paper's voxel (1)
// scaled with the object, cbrt(volume / kPaperObjectVolume), so that an object has as many voxels at every size
// as at the paper's (the 36-face polytope: 12.26 along its longest side; any solid at least 7.31, a cube's).
// Exactly 1 for the paper's scene. Bounded to [extent / kDefaultMostAcross, extent / kDefaultFewestAcross], so
// that a flat or thin object, whose volume says little of its size, still gets a usable voxmap.
constexpr double kDefaultFewestAcross = 4, kDefaultMostAcross = 64;
double default_voxel(double volume, double extent);

// The scene of a run (check()ed first): a scene file's (make_file_scene, scene_file.h), or the built-in scene of the
// paper's environment (Section 7): types[0].count copies of one shape (a built-in name or a mesh file) scaled so
// that they fill `density` of the cube, voxelised at its voxel or its resolution (by default at default_voxel: the
// paper's accuracy of one unit at the paper's object size, scaled with the object), placed without overlapping
// bounding spheres (place_bodies), with random orientations, random velocities of up to `speed` times the object's
// bounding radius per frame and random spins of up to `spin` radians per frame. check()'s errors; for the built-in
// scene std::invalid_argument "scene: ..." for a voxel that makes the object larger than kMaxVoxelsAcross voxels or
// fewer than kMinVoxelsAcross across and for objects whose bounding spheres do not fit the cube at that density
// (naming the density and the largest that fits), MeshError for the shape.
Scene make_scene(const RunConfig& c);

// A hash of the bodies' states (bit patterns of positions, orientations and velocities): equal runs, equal hash.
uint64_t state_hash(const std::vector<Body>& bodies);

class Simulation {
 public:
  // The device is configured from the scene: only its object types are loaded, with memories grown to fit them (or
  // as the configuration's `device` says). Of the configuration, only how it runs matters (WorldDef, device, ccd,
  // midphase, cull, exchange); the scene is `scene`.
  Simulation(Scene scene, const RunConfig& config);
  // One frame: integrate, bounce off the walls (with ccd: advance without tunnelling, ContinuousCollision), bounds,
  // broadphase, pair tests, response. std::invalid_argument from the constructor when ccd is asked of a device
  // without distance voxmaps. The frame lasts `dt` units of time, the bodies' velocities being per unit: a frame
  // step is dt = 1 (whose arithmetic is the same as before dt existed: x * 1.0 is x), World::step(dt) seconds.
  FrameStats step(double dt = 1);
  const Scene& scene() const { return scene_; }
  // Body i to change between frames (a pose set, a velocity): the next frame tells the broadphase it moved
  // unexpectedly.
  Body& edit_body(size_t i);
  // Replaces every body (of the same types, which the device holds): the next frame starts from these.
  void set_bodies(std::vector<Body> bodies);
  const Broadphase& broadphase() const { return *broadphase_; }
  const DeviceConfig& device_config() const { return collider_->device().config(); }
  uint64_t frame() const { return frame_; }
  // The last frame's pairs tested on the device (global body indices, in pair order) and their results, contacts
  // included (this rank's, in a distributed run).
  const std::vector<BodyPair>& tested_pairs() const { return requests_pairs_; }
  const std::vector<PairResult>& results() const { return results_; }
  // The threads of the frame (WorldDef::threads; null on one thread).
  const std::shared_ptr<ThreadPool>& pool() const { return pool_; }
  // A hash of every body's state (bit patterns of positions, orientations and velocities): equal runs, equal hash.
  uint64_t state_hash() const { return voxcd::state_hash(scene_.bodies); }

 private:
  // Bounds and spheres of bodies [first, end) (sized by size_bounds()); compute_bounds(): of every body, on the pool.
  void compute_bounds(size_t first, size_t end);
  void compute_bounds();
  void size_bounds();
  // Explicit Euler on bodies [first, end), renormalising the orientation; bounce off the walls by the bounding
  // sphere. Returns the bounces.
  uint64_t integrate(size_t first, size_t end);
  // Every body integrated and bounded, a block at a time (st: wall hits, t_integrate and t_bounds).
  void integrate_and_bound(FrameStats& st);
  // The frame's motion and the bounds: integrate_and_bound(), or with ccd the advance without tunnelling (its
  // statistics into st), then the bounds.
  void advance(FrameStats& st);
  // The mid-phase, the pair tests and the tested pairs' outcomes (requests_, requests_pairs_, results_, outcomes_).
  void narrow(const std::vector<BodyPair>& pairs, const PairOptions& po);
  // The mid-phase's verdict on every pair (keep_: the enclosing spheres, then the oriented boxes), then the kept
  // pairs as requests in pair order; sizes the results and outcomes. Returns the requests.
  size_t midphase(const std::vector<BodyPair>& pairs);
  // The kept pairs of pairs[first, end) as requests from requests_[q] on.
  void make_requests(const std::vector<BodyPair>& pairs, size_t first, size_t end, size_t q);
  // The parts of the pair tests (test_first_): consecutive requests of near-equal weight (shell points looked up).
  void cut_tests(const PairOptions& po);
  // The device runs parts (the cpu backend): each part of the requests, to its outcomes, in one loop, each part timed
  // on its own, then the parts' cycles joined in order.
  void narrow_parts(const PairOptions& po);
  // The response to every touching pair that approaches along its contact normal (respond()), in pair order.
  void respond_all(FrameStats& st);
  void outcome(size_t q);
  // The per-body state that follows the bodies (moved_, fixed_), after they were made or replaced.
  void bodies_changed();
  std::unique_ptr<Broadphase> new_broadphase() const;
  // The broadphase's pairs, or in a distributed run those of this rank's slab (global body indices, sorted).
  const std::vector<BodyPair>& find_pairs();
  // The outcomes of the tested pairs, in pair order (every rank's in a distributed run).
  void gather_outcomes(FrameStats& st);

  Scene scene_;
  RunConfig opt_;
  std::unique_ptr<Broadphase> broadphase_;
  std::unique_ptr<PairCollider> collider_;
  std::unique_ptr<ContinuousCollision> ccd_;  // when opt.ccd
  std::vector<BodyBounds> bounds_;
  // Each body's enclosing sphere this frame (bounds_'s, in 32 bytes: the mid-phase's first test reads only these).
  struct Sphere {
    Eigen::Vector3d centre;
    double radius;
    bool overlaps(const Sphere& o) const {  // as spheres_overlap()
      const double r = radius + o.radius;
      return (centre - o.centre).squaredNorm() <= r * r;
    }
  };
  std::vector<Sphere> sphere_;
  std::vector<uint8_t> moved_;  // bytes, not bits: the threads write them body by body
  std::vector<uint32_t> edited_;  // bodies changed between frames (edit_body), flagged moved in the next frame
  // Per body: not dynamic (static or kinematic); a pair of two such bodies is not tested. any_fixed_: one is.
  std::vector<uint8_t> fixed_;
  bool any_fixed_ = false;
  double dt_ = 1;               // the frame's length (step(dt)); a new length flags every body moved
  std::shared_ptr<ThreadPool> pool_;  // null on one thread
  std::vector<uint8_t> keep_;         // the mid-phase's verdict per broadphase pair
  std::vector<PartSlot<std::vector<uint32_t>>> passing_;  // midphase(): per range, its pairs whose spheres overlap
  std::vector<PartSlot<uint64_t>> part_counts_;
  std::vector<PartSlot<std::array<double, 2>>> part_seconds_;  // integrate_and_bound(): each part's two steps
  std::vector<size_t> part_first_;  // midphase(): the first request of each range of broadphase pairs
  std::vector<uint64_t> weight_;    // cut_tests(): the requests' weights, summed (weight_[q]: those before q)
  std::vector<size_t> test_first_;  // cut_tests(): the first request of each part of the pair tests
  std::vector<PartSlot<PairCollider::Part>> narrow_parts_;
  std::vector<PairCollider::Part*> part_ptrs_;
  std::vector<PairRequest> requests_;
  std::vector<BodyPair> requests_pairs_;  // the bodies of each request
  std::vector<PairResult> results_;
  std::vector<PairOutcome> outcomes_;
  // Distributed: this frame's slabs, the bodies of this rank's slab, their bounds and the pairs it owns.
  Slabs slabs_;
  std::vector<uint32_t> local_;
  std::vector<BodyBounds> local_bounds_;
  std::vector<BodyPair> owned_;
  uint64_t frame_ = 0;
};

}  // namespace voxcd
