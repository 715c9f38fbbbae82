// The stepper: a Simulation's frame (motion and bounds, broadphase, pair tests, response) and its bodies' state
// between frames; the state hash.
#include <Eigen/Geometry>
#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "voxcd/host/scene/detail/now.h"
#include "voxcd/host/scene/detail/placed.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/ref/fnv1a.h"

namespace voxcd {

namespace {

using detail::now;
using detail::placed;
using detail::Placed;

// Bodies per part of the per-body loops (integration, bounds: about 50 ns a body).
constexpr size_t kGrainBodies = 64;
constexpr size_t kBlockBodies = 64;    // bodies integrated, then bounded, in turn (8 KiB of bodies)

}  // namespace

std::unique_ptr<Broadphase> Simulation::new_broadphase() const {
  std::unique_ptr<Broadphase> b = make_broadphase(opt_.broadphase);
  b->set_pool(pool_.get());
  return b;
}

Simulation::Simulation(Scene scene, const RunConfig& opt) : scene_(std::move(scene)), opt_(opt) {
  // One pool for every stage and the device (a loop inside a loop of it runs on the thread that asked).
  const unsigned threads = opt.threads ? opt.threads : ThreadPool::available_cpus();
  if (threads > 1) pool_ = std::make_shared<ThreadPool>(threads);
  broadphase_ = new_broadphase();
  if (opt.exchange && broadphase_->predicate() == "all")
    throw std::invalid_argument("broadphase " + opt.broadphase + ": it pairs every body with every other, so it cannot "
                                "be split over ranks by space; a distributed run needs grid, sap, tree, ...");
  std::vector<const ObjectType*> types;
  for (const auto& t : scene_.types) types.push_back(t.get());
  const DeviceConfig cfg =
      opt.device ? *opt.device : device_config_for(opt.backend, opt.lanes, types, opt.distance_bits);
  DeviceOptions dopt;
  dopt.threads = threads;
  dopt.pool = pool_;
  collider_ = std::make_unique<PairCollider>(make_device(opt.backend, cfg, dopt), scene_.types, pool_);
  bodies_changed();
  if (opt.ccd) {
    if (!cfg.distance())
      throw std::invalid_argument("ccd: continuous collision bounds each step by the distance fields: it needs a "
                                  "distance device (distance_bits " + distance_bits_text() + ")");
    ccd_ = std::make_unique<ContinuousCollision>(scene_.types, cfg, opt.ccd_max_iterations, opt.cull, pool_.get());
  }
}


void Simulation::bodies_changed() {
  const size_t n = scene_.bodies.size();
  moved_.assign(n, 1);
  edited_.clear();
  fixed_.resize(n);
  any_fixed_ = false;
  for (size_t i = 0; i < n; ++i) {
    fixed_[i] = !scene_.bodies[i].pushed();
    any_fixed_ = any_fixed_ || fixed_[i];
  }
}

Body& Simulation::edit_body(size_t i) {
  Body& b = scene_.bodies.at(i);
  edited_.push_back(uint32_t(i));
  return b;
}

void Simulation::set_bodies(std::vector<Body> bodies) {
  for (const Body& b : bodies)
    if (b.type >= scene_.types.size())
      throw std::out_of_range("Simulation::set_bodies: a body of type " + std::to_string(b.type) + " of " +
                              std::to_string(scene_.types.size()));
  scene_.bodies = std::move(bodies);
  bodies_changed();
  // A broadphase that keeps state between frames keys it by index: other bodies start a fresh one.
  if (broadphase_->keeps_state()) broadphase_ = new_broadphase();
  requests_.clear();
  requests_pairs_.clear();
  results_.clear();
  outcomes_.clear();
}

uint64_t Simulation::integrate(size_t first, size_t end) {
  uint64_t walls = 0;
  const double dt = dt_;  // 1 for a frame step: the products below are then the velocities themselves, bit for bit
  for (size_t i = first; i < end; ++i) {
    Body& b = scene_.bodies[i];
    if (!b.moves()) continue;
    b.pose.translation += b.velocity * dt;
    const Eigen::Quaterniond w(0, b.spin.x() * dt, b.spin.y() * dt, b.spin.z() * dt);
    Eigen::Quaterniond q = b.pose.rotation;
    q.coeffs() += 0.5 * (w * q).coeffs();
    b.pose.rotation = q.normalized();
    if (!opt_.walls || !b.pushed()) continue;
    const ObjectType& t = *scene_.types[b.type];
    const Eigen::Vector3d c = b.pose.rotation * t.centre + b.pose.translation;
    for (int a = 0; a < 3; ++a) {
      if ((c[a] - t.radius < 0 && b.velocity[a] < 0) || (c[a] + t.radius > scene_.side && b.velocity[a] > 0)) {
        b.velocity[a] = -b.velocity[a];
        moved_[i] = 1;
        ++walls;
      }
    }
  }
  return walls;
}

void Simulation::compute_bounds(size_t first, size_t end) {
  for (size_t i = first; i < end; ++i) {
    const Body& b = scene_.bodies[i];
    const ObjectType& t = *scene_.types[b.type];
    const Placed p = placed(t, b);
    bounds_[i] = body_bounds(t, b, p.R, p.c);
    bounds_[i].max_speed *= dt_;  // per frame of dt_ units of time (exact for a frame step: dt_ = 1)
    bounds_[i].moved_unexpectedly = moved_[i] != 0;
    sphere_[i] = {bounds_[i].centre, bounds_[i].radius};
  }
}

void Simulation::size_bounds() {
  bounds_.resize(scene_.bodies.size());
  sphere_.resize(scene_.bodies.size());
}

void Simulation::compute_bounds() {
  size_bounds();
  const size_t n = scene_.bodies.size();
  for_ranges(pool_.get(), pool_ranges(pool_.get(), n, kGrainBodies),
             [&](size_t, size_t first, size_t end) { compute_bounds(first, end); });
}

void Simulation::integrate_and_bound(FrameStats& st) {
  // Body by body on the pool, in blocks small enough to stay in the first-level cache between the two steps (one
  // pass over the bodies' memory, not two). Each part times its steps; the stage's time is split between
  // t_integrate and t_bounds in the proportion of their summed times.
  size_bounds();
  const Ranges r = pool_ranges(pool_.get(), scene_.bodies.size(), kGrainBodies);
  if (part_counts_.size() < r.parts) part_counts_.resize(r.parts);
  if (part_seconds_.size() < r.parts) part_seconds_.resize(r.parts);
  // (Without bodies no part runs: its counts must not be another loop's.)
  for (size_t p = 0; p < r.parts; ++p) part_counts_[p].value = 0, part_seconds_[p].value = {0, 0};
  const double t0 = now();
  for_ranges(pool_.get(), r, [&](size_t part, size_t first, size_t end) {
    uint64_t walls = 0;
    double ti = 0, tb = 0;
    for (size_t b = first; b < end; b += kBlockBodies) {
      const size_t e = std::min(end, b + kBlockBodies);
      const double a0 = now();
      walls += integrate(b, e);
      const double a1 = now();
      compute_bounds(b, e);
      ti += a1 - a0, tb += now() - a1;
    }
    part_counts_[part].value = walls;
    part_seconds_[part].value = {ti, tb};
  });
  const double wall = now() - t0;
  double ti = 0, tb = 0;
  for (size_t p = 0; p < r.parts; ++p) {
    st.wall_hits += part_counts_[p].value;
    ti += part_seconds_[p].value[0], tb += part_seconds_[p].value[1];
  }
  st.t_integrate = ti + tb > 0 ? wall * ti / (ti + tb) : 0;
  st.t_bounds = wall - st.t_integrate;
}

const std::vector<BodyPair>& Simulation::find_pairs() {
  if (!opt_.exchange) {
    broadphase_->update(bounds_, frame_);
    return broadphase_->pairs();
  }
  slabs_ = split_slabs(bounds_, opt_.exchange->ranks());
  const int me = opt_.exchange->rank();
  std::vector<uint32_t> local = slab_bodies(slabs_, me, bounds_);
  // A broadphase that keeps state between frames keys it by index: another set of bodies starts a fresh one.
  if (broadphase_->keeps_state() && local != local_) broadphase_ = new_broadphase();
  local_ = std::move(local);
  local_bounds_.clear();
  for (uint32_t i : local_) local_bounds_.push_back(bounds_[i]);
  broadphase_->update(local_bounds_, frame_);
  // Local indices ascend with the global ones, so the pairs stay sorted.
  owned_.clear();
  for (const BodyPair& p : broadphase_->pairs()) {
    const uint32_t a = local_[p.first], b = local_[p.second];
    if (pair_owner(slabs_, bounds_[a], bounds_[b]) == me) owned_.push_back({a, b});
  }
  return owned_;
}

void Simulation::gather_outcomes(FrameStats& st) {
  // The outcomes of the tested pairs (narrow() made them), and the frame's cycles.
  uint64_t cycles = 0;
  for (const PairOutcome& o : outcomes_) cycles += o.cycles;
  // The stream of the frame is taken one cycle after its last completion record.
  if (!requests_.empty() && collider_->device().models_cycles()) cycles += 1;
  if (!opt_.exchange) {
    st.device_cycles += cycles;
    return;
  }
  RankCounts own, total;
  own.pairs = st.pairs;
  own.tested = st.tested;
  own.cycles = cycles;
  outcomes_ = opt_.exchange->exchange(frame_, slabs_, outcomes_, own, total);
  st.pairs = total.pairs;
  st.tested = total.tested;
  st.device_cycles += total.cycles;
}

namespace {
// The frame's statistics of continuous collision (FrameStats::ccd_*) and the CcdStats count each one is.
constexpr std::pair<uint64_t FrameStats::*, uint64_t CcdStats::*> kCcdCounts[] = {
    {&FrameStats::ccd_iterations, &CcdStats::iterations}, {&FrameStats::ccd_queries, &CcdStats::queries},
    {&FrameStats::ccd_limited, &CcdStats::limited},       {&FrameStats::ccd_toi, &CcdStats::toi},
    {&FrameStats::ccd_dropped, &CcdStats::dropped},       {&FrameStats::ccd_lookups, &CcdStats::lookups}};
}  // namespace

void Simulation::advance(FrameStats& st) {
  if (!ccd_) {
    integrate_and_bound(st);
    return;
  }
  double t0 = now();
  const CcdStats c = ccd_->advance(scene_, *collider_, moved_, st.wall_hits, dt_, opt_.walls);
  for (const auto& [frame, ccd] : kCcdCounts) st.*frame = c.*ccd;
  st.responses += c.pair_toi;
  st.device_cycles += c.cycles;
  double t1 = now();
  st.t_integrate = t1 - t0;
  compute_bounds();
  st.t_bounds = now() - t1;
}

FrameStats Simulation::step(double dt) {
  FrameStats st;
  st.frame = frame_;
  // A frame of another length makes every motion bound the broadphase was given another (they are per frame).
  std::fill(moved_.begin(), moved_.end(), uint8_t(dt != dt_));
  dt_ = dt;
  for (const uint32_t i : edited_) moved_[i] = 1;
  edited_.clear();

  // Integrate (explicit Euler, or without tunnelling with ccd), bouncing off the walls, and the bounds.
  advance(st);
  double t2 = now();

  // The broadphase's pairs.
  const std::vector<BodyPair>& pairs = find_pairs();
  double t3 = now();
  st.t_broadphase = t3 - t2;

  // Mid-phase, the device, and each tested pair's outcome.
  PairOptions po;
  po.mode = opt_.mode;
  po.both_directions = opt_.both_directions;
  po.cull = opt_.cull;
  po.margin = opt_.margin;
  narrow(pairs, po);
  double t4 = now();
  st.t_narrow = t4 - t3;
  st.pairs = pairs.size();
  st.tested = requests_.size();
  gather_outcomes(st);

  // Response, in pair order (deterministic).
  respond_all(st);
  st.t_response = now() - t4;
  ++frame_;
  return st;
}

uint64_t state_hash(const std::vector<Body>& bodies) {
  // FNV-1a over each value's bit pattern, low byte first, from the state hash's own starting value (one digit short
  // of FNV's basis: every state hash recorded so far starts there).
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, 8);
    unsigned char bytes[8];
    for (int i = 0; i < 8; ++i) bytes[i] = static_cast<unsigned char>(bits >> (8 * i));
    h = fnv1a(bytes, 8, h);
  };
  for (const Body& b : bodies) {
    for (int i = 0; i < 3; ++i) mix(b.pose.translation[i]), mix(b.velocity[i]), mix(b.spin[i]);
    for (int i = 0; i < 4; ++i) mix(b.pose.rotation.coeffs()[i]);
  }
  return h;
}

}  // namespace voxcd
