#include "voxcd/host/scene/ccd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "voxcd/host/scene/scene.h"

namespace voxcd {

double ContinuousCollision::motion_bound(const ObjectType& t, const Body& b) const {
  // Its linear speed plus its spin times the farthest point's distance from the rotation centre (the body's origin),
  // as body_bounds' max_speed, over the frame (exact for a frame step: dt_ = 1).
  return (b.velocity.norm() + b.spin.norm() * (t.centre.norm() + t.radius)) * dt_;
}

// Bodies per part of the per-body loops, candidates per part of the bounds.
constexpr size_t kGrainBodies = 64, kGrainPairs = 32;

ContinuousCollision::ContinuousCollision(const std::vector<std::shared_ptr<const ObjectType>>& types,
                                         const DeviceConfig& cfg, uint32_t max_iterations, bool cull, ThreadPool* pool)
    : bound_(types, cfg), max_iterations_(max_iterations), cull_(cull), pool_(pool), swept_(make_broadphase("sap")) {}

void ContinuousCollision::pose_at(size_t i, double t, Body& b) const {
  // The integration of Simulation::step over the time since the segment's start: at h = 1 exactly its arithmetic.
  if (!b.moves()) return;
  const double h = (t - s0_[i]) * dt_;
  b.pose.translation = t0_[i] + b.velocity * h;
  const Eigen::Quaterniond w(0, b.spin.x(), b.spin.y(), b.spin.z());
  Eigen::Quaterniond q = q0_[i];
  q.coeffs() += (0.5 * h) * (w * q0_[i]).coeffs();
  b.pose.rotation = q.normalized();
}

void ContinuousCollision::candidates(const Scene& scene, double t) {
  // Every body's sphere grown by what its motion bound allows over the rest of the frame.
  const size_t n = scene.bodies.size();
  sweep_.resize(n);
  for_ranges(pool_, pool_ranges(pool_, n, kGrainBodies), [&](size_t, size_t first, size_t end) {
    for (size_t i = first; i < end; ++i) {
      const Body& b = scene.bodies[i];
      const ObjectType& ty = *scene.types[b.type];
      BodyBounds& s = sweep_[i];
      s.centre = b.pose.rotation * ty.centre + b.pose.translation;
      s.radius = ty.radius + speed_[i] * (1 - t);
      s.box.lo = s.centre - Eigen::Vector3d::Constant(s.radius);
      s.box.hi = s.centre + Eigen::Vector3d::Constant(s.radius);
    }
  });
  swept_->update(sweep_, calls_++);
  cand_.clear();
  // (A pair of which neither body is dynamic is not a candidate: as in the frame, it is not tested.)
  for (const BodyPair& p : swept_->pairs())
    if (spheres_overlap(sweep_[p.first], sweep_[p.second]) &&
        (scene.bodies[p.first].pushed() || scene.bodies[p.second].pushed()))
      cand_.push_back(p);
}

void ContinuousCollision::restart(const Scene& scene, size_t i, double t) {
  t0_[i] = scene.bodies[i].pose.translation;
  q0_[i] = scene.bodies[i].pose.rotation;
  s0_[i] = t;
}

void ContinuousCollision::query(Scene& scene, PairCollider& collider, double rest, CcdStats& st) {
  // The pairs that could close their geometric gap before the frame's end go to the device, in one batch.
  requests_.clear();
  queried_.clear();
  geo_.resize(cand_.size());
  query_.resize(cand_.size());
  for_ranges(pool_, pool_ranges(pool_, cand_.size(), kGrainPairs), [&](size_t, size_t first, size_t end) {
    for (size_t k = first; k < end; ++k) {
      const uint32_t ia = cand_[k].first, ib = cand_[k].second;
      const Body &a = scene.bodies[ia], &b = scene.bodies[ib];
      geo_[k] = bound_.geometric(a.type, rot_[ia], a.pose.translation, b.type, rot_[ib], b.pose.translation);
      const double tol =
          kTolerance * std::min(scene.types[a.type]->voxmap().voxel(), scene.types[b.type]->voxmap().voxel());
      query_[k] = !(geo_[k] > tol && geo_[k] >= (speed_[ia] + speed_[ib]) * rest);
    }
  });
  for (size_t k = 0; k < cand_.size(); ++k) {
    if (!query_[k]) continue;
    const Body &a = scene.bodies[cand_[k].first], &b = scene.bodies[cand_[k].second];
    PairRequest r;
    r.a = a.type;
    r.b = b.type;
    r.pose_a = a.pose;
    r.pose_b = b.pose;
    requests_.push_back(r);
    queried_.push_back(uint32_t(k));
  }
  if (requests_.empty()) return;
  PairOptions po;
  po.mode = Mode::All;
  po.both_directions = true;
  po.cull = cull_;
  po.margin = bound_.margin();
  collider.collide(requests_, po, results_);
  st.queries += requests_.size();
  if (collider.device().models_cycles()) st.cycles += 1;  // the stream ends a cycle after its last completion
}

bool ContinuousCollision::pairs(Scene& scene, std::vector<uint8_t>& moved, double now, double rest, double& dt,
                                CcdStats& st) {
  bool responded = false;
  for (size_t q = 0; q < requests_.size(); ++q) {
    const PairResult& r = results_[q];
    st.lookups += r.lookups;
    st.cycles += r.device_cycles;
    const uint32_t ia = cand_[queried_[q]].first, ib = cand_[queried_[q]].second;
    Body &a = scene.bodies[ia], &b = scene.bodies[ib];
    const double va = scene.types[a.type]->voxmap().voxel(), vb = scene.types[b.type]->voxmap().voxel();
    const double lb = std::max(geo_[queried_[q]], bound_.device(a.type, b.type, r));
    if (lb <= kTolerance * std::min(va, vb)) {
      // Contact: the normal from A towards B over the contacts nearest the surfaces (the field's gradients), the
      // line between the spheres' centres when they give none.
      double dmin = std::numeric_limits<double>::infinity();
      for (const Contact& c : r.contacts) dmin = std::min(dmin, -c.depth);
      Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
      for (const Contact& c : r.contacts)
        if (-c.depth <= dmin + std::max(va, vb)) nrm += c.a_in_b ? c.normal : -c.normal;
      if (nrm.squaredNorm() < 1e-12)
        nrm = (b.pose.rotation * scene.types[b.type]->centre + b.pose.translation) -
              (a.pose.rotation * scene.types[a.type]->centre + a.pose.translation);
      if (nrm.squaredNorm() < 1e-24) nrm = Eigen::Vector3d::UnitX();
      nrm.normalize();
      if (respond(a, b, nrm)) {
        restart(scene, ia, now);
        restart(scene, ib, now);
        speed_[ia] = motion_bound(*scene.types[a.type], a);
        speed_[ib] = motion_bound(*scene.types[b.type], b);
        moved[ia] = moved[ib] = 1;
        limit_[ia] = limit_[ib] = 1;
        ++st.toi;
        ++st.pair_toi;
        responded = true;
      }
      continue;  // touching and separating: it does not limit the step
    }
    const double vs = speed_[ia] + speed_[ib];
    if (vs > 0 && lb < vs * rest) {
      dt = std::min(dt, lb / vs);
      limit_[ia] = limit_[ib] = 1;
      limited_.push_back(uint64_t(ia) << 32 | ib);
    }
  }
  return responded;
}

void ContinuousCollision::walls(Scene& scene, std::vector<uint8_t>& moved, double now, double rest, double& dt,
                                CcdStats& st, uint64_t& wall_hits) {
  // By the enclosing sphere: its centre moves along an axis at most that velocity component plus the spin times
  // the centre's distance from the rotation centre. Body by body on the pool (each reflection touches its body
  // alone); the parts' steps and counts joined in part order (a minimum and sums: the same whatever the parts).
  const Ranges r = pool_ranges(pool_, scene.bodies.size(), kGrainBodies);
  if (parts_.size() < r.parts) parts_.resize(r.parts);
  for_ranges(pool_, r, [&](size_t part, size_t first, size_t end) {
    PartResult& out = parts_[part].value;
    out = PartResult();
    out.dt = dt;
    for (size_t i = first; i < end; ++i) {
      Body& b = scene.bodies[i];
      const ObjectType& t = *scene.types[b.type];
      const Eigen::Vector3d c = b.pose.rotation * t.centre + b.pose.translation;
      if (!b.pushed()) continue;  // static and kinematic bodies ignore the walls
      const double tol = kTolerance * t.voxmap().voxel(), swing = b.spin.norm() * t.centre.norm() * dt_;
      for (int ax = 0; ax < 3; ++ax) {
        const double low = c[ax] - t.radius, high = scene.side - c[ax] - t.radius;
        if ((low <= tol && b.velocity[ax] < 0) || (high <= tol && b.velocity[ax] > 0)) {
          restart(scene, i, now);
          b.velocity[ax] = -b.velocity[ax];
          moved[i] = 1;
          limit_[i] = 1;
          ++out.toi;
        }
        const double rate_low = std::max(0.0, -b.velocity[ax]) * dt_ + swing;  // per frame
        const double rate_high = std::max(0.0, b.velocity[ax]) * dt_ + swing;
        if (low > tol && rate_low > 0 && low < rate_low * rest) out.dt = std::min(out.dt, low / rate_low), limit_[i] = 1;
        if (high > tol && rate_high > 0 && high < rate_high * rest)
          out.dt = std::min(out.dt, high / rate_high), limit_[i] = 1;
      }
    }
  });
  for (size_t p = 0; p < r.parts; ++p) {
    const PartResult& out = parts_[p].value;
    dt = std::min(dt, out.dt);
    st.toi += out.toi;
    wall_hits += out.toi;
  }
}

CcdStats ContinuousCollision::advance(Scene& scene, PairCollider& collider, std::vector<uint8_t>& moved,
                                      uint64_t& wall_hits, double frame_dt, bool with_walls) {
  CcdStats st;
  dt_ = frame_dt;
  const size_t n = scene.bodies.size();
  t0_.resize(n);
  q0_.resize(n);
  s0_.assign(n, 0.0);
  speed_.resize(n);
  rot_.resize(n);
  limit_.assign(n, 0);
  limited_.clear();
  const Ranges bodies = pool_ranges(pool_, n, kGrainBodies);
  if (parts_.size() < bodies.parts) parts_.resize(bodies.parts);
  for_ranges(pool_, bodies, [&](size_t, size_t first, size_t end) {
    for (size_t i = first; i < end; ++i) {
      restart(scene, i, 0.0);
      speed_[i] = motion_bound(*scene.types[scene.bodies[i].type], scene.bodies[i]);
    }
  });
  double now = 0;
  bool rebuild = true;
  for (uint32_t iter = 0; now < 1; ++iter) {
    if (iter == max_iterations_) {
      // The cap: the bodies that limited the last step keep their place for the rest of the frame; the others
      // could not reach them, another body or a wall before the frame's end, so they finish it.
      for_ranges(pool_, bodies, [&](size_t part, size_t first, size_t end) {
        uint64_t dropped = 0;
        for (size_t i = first; i < end; ++i) {
          if (limit_[i]) ++dropped;
          else pose_at(i, 1.0, scene.bodies[i]);
        }
        parts_[part].value.dropped = dropped;
      });
      for (size_t p = 0; p < bodies.parts; ++p) st.dropped += parts_[p].value.dropped;
      break;
    }
    if (rebuild) candidates(scene, now);
    rebuild = false;
    ++st.iterations;
    const double rest = 1 - now;
    std::fill(limit_.begin(), limit_.end(), 0);
    for_ranges(pool_, bodies, [&](size_t, size_t first, size_t end) {
      for (size_t i = first; i < end; ++i) rot_[i] = scene.bodies[i].pose.rotation.toRotationMatrix();
    });
    query(scene, collider, rest, st);
    double dt = rest;
    const bool responded = pairs(scene, moved, now, rest, dt, st);
    if (with_walls) walls(scene, moved, now, rest, dt, st, wall_hits);
    // A response can make a body faster than its swept sphere allowed: find the candidates again, then step.
    if (responded) {
      rebuild = true;
      continue;
    }
    now = dt >= rest ? 1.0 : now + dt;
    for_ranges(pool_, bodies, [&](size_t, size_t first, size_t end) {
      for (size_t i = first; i < end; ++i) pose_at(i, now, scene.bodies[i]);
    });
  }
  std::sort(limited_.begin(), limited_.end());
  st.limited = uint64_t(std::unique(limited_.begin(), limited_.end()) - limited_.begin());
  return st;
}

}  // namespace voxcd
