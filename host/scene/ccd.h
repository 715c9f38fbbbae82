// Continuous collision by conservative advancement (docs/simulate.md, "No tunnelling"): a frame's motion is taken in
// steps no longer than any candidate pair's lower bound on its distance (from the distance device) or any wall's gap
// allows, so no body passes through another or through a wall between frames.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/pairs/collider.h"
#include "voxcd/host/scene/distance_bound.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {

struct Scene;
struct Body;

// What one frame of continuous collision did.
struct CcdStats {
  uint64_t iterations = 0;  // advancement steps (each one batch of pair queries)
  uint64_t queries = 0;     // pair queries sent to the device, over all steps
  uint64_t limited = 0;     // distinct pairs whose distance bound cut a step short of the frame's end
  uint64_t toi = 0;         // time-of-impact events: pair responses and wall reflections during the advancement
  uint64_t pair_toi = 0;    // of those, pair responses
  uint64_t dropped = 0;     // bodies whose remaining motion the iteration cap dropped (0 unless the cap was reached)
  uint64_t lookups = 0;     // shell points the queries submitted
  uint64_t cycles = 0;      // device cycles of the queries' job streams
};

class ContinuousCollision {
 public:
  // types, cfg: as DistanceBound. max_iterations: advancement steps per frame before the cap drops the remaining
  // motion of the bodies still limited.
  // pool: threads for the per-body and per-candidate loops (null: the calling thread).
  ContinuousCollision(const std::vector<std::shared_ptr<const ObjectType>>& types, const DeviceConfig& cfg,
                      uint32_t max_iterations, bool cull, ThreadPool* pool = nullptr);
  // Moves every body through one frame of `frame_dt` units of time (the integration of Simulation::step, cut into
  // steps), responding at each time of impact and, with `with_walls`, reflecting off the cube's walls; sets moved[i]
  // to 1 for every body whose velocity changed. Deterministic whatever the threads. Times within the frame are
  // fractions of it (0 to 1) whatever its length.
  CcdStats advance(Scene& scene, PairCollider& collider, std::vector<uint8_t>& moved, uint64_t& wall_hits,
                   double frame_dt = 1, bool with_walls = true);
  const DistanceBound& bound() const { return bound_; }

  // Contact when a pair's bound is at most this fraction of the finer voxel (and a wall's gap at most this
  // fraction of the body's voxel).
  static constexpr double kTolerance = DistanceBound::kTolerance;

 private:
  // No point of body b moves farther in a frame (body_bounds' max_speed over the frame's dt_).
  double motion_bound(const ObjectType& t, const Body& b) const;
  // The pose of body i at time t of the frame, from its segment.
  void pose_at(size_t i, double t, Body& b) const;
  // A new segment for body i from its pose at t (its velocity changes at t).
  void restart(const Scene& scene, size_t i, double t);
  // The pairs whose swept spheres meet over the rest of the frame from t.
  void candidates(const Scene& scene, double t);
  // The candidates' geometric bounds; those that could be crossed within `rest` queried on the device in one batch.
  void query(Scene& scene, PairCollider& collider, double rest, CcdStats& st);
  // Responses of the pairs in contact and approaching (true when any), the step the others allow into dt.
  bool pairs(Scene& scene, std::vector<uint8_t>& moved, double now, double rest, double& dt, CcdStats& st);
  // Reflections off the walls reached, the step the others allow into dt.
  void walls(Scene& scene, std::vector<uint8_t>& moved, double now, double rest, double& dt, CcdStats& st,
             uint64_t& wall_hits);

  DistanceBound bound_;
  uint32_t max_iterations_;
  bool cull_;
  ThreadPool* pool_;
  // Per part of a loop over the bodies: the step it allows, time-of-impact events and wall hits, bodies dropped.
  struct PartResult {
    double dt = 0;
    uint64_t toi = 0, dropped = 0;
  };
  std::vector<PartSlot<PartResult>> parts_;
  std::vector<uint8_t> query_;     // per candidate: whether it goes to the device this step
  std::unique_ptr<Broadphase> swept_;
  // Per body: its motion since the start of its current segment (the frame's start or its last velocity change).
  std::vector<Eigen::Vector3d> t0_;
  std::vector<Eigen::Quaterniond> q0_;
  std::vector<double> s0_;
  std::vector<double> speed_;      // no point moves farther in a frame (world units)
  double dt_ = 1;                  // the frame's length in units of time (the velocities are per unit)
  std::vector<BodyBounds> sweep_;
  std::vector<BodyPair> cand_;
  uint64_t calls_ = 0;             // updates of the swept broadphase
  std::vector<Eigen::Matrix3d> rot_;
  std::vector<double> geo_;        // each candidate's geometric bound this step
  std::vector<PairRequest> requests_;
  std::vector<uint32_t> queried_;  // candidate index of each request
  std::vector<PairResult> results_;
  std::vector<uint8_t> limit_;     // body limited the last step (dropped at the cap)
  std::vector<uint64_t> limited_;  // pair keys that cut a step this frame
};

}  // namespace voxcd
