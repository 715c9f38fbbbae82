#include "host/scene.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <stdexcept>

#include "host/mesh.h"
#include "host/shapes.h"

namespace voxcd {

namespace {

// Do the two bodies' oriented boxes meet? Each box is its type's contact bounds (lo..hi in the type's frame:
// every non-empty voxel and shell point) grown by one of its voxels, which covers the fixed-point error of a job
// (a small fraction of a voxel) and rounding here. Gottschalk's separating-axis test: 3 + 3 face axes and 9 edge
// cross products, with a relative slack on the near-parallel cross products.
// Ra, ca: A's rotation and the centre of its box in the world (as compute_bounds keeps them for every body).
bool boxes_overlap(const ObjectType& ta, const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca, const ObjectType& tb,
                   const Eigen::Matrix3d& Rb, const Eigen::Vector3d& cb) {
  const double ga = ta.voxmap().voxel(), gb = tb.voxmap().voxel();
  const Eigen::Vector3d ea = 0.5 * (ta.hi - ta.lo) + Eigen::Vector3d::Constant(ga);
  const Eigen::Vector3d eb = 0.5 * (tb.hi - tb.lo) + Eigen::Vector3d::Constant(gb);
  // B's axes and centre in A's frame.
  const Eigen::Matrix3d R = Ra.transpose() * Rb;
  const Eigen::Vector3d t = Ra.transpose() * (cb - ca);
  Eigen::Matrix3d AbsR;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) AbsR(i, j) = std::abs(R(i, j)) + 1e-9;
  for (int i = 0; i < 3; ++i)
    if (std::abs(t[i]) > ea[i] + eb.dot(AbsR.row(i))) return false;
  for (int j = 0; j < 3; ++j)
    if (std::abs(t.dot(R.col(j))) > ea.dot(AbsR.col(j)) + eb[j]) return false;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ea[i1] * AbsR(i2, j) + ea[i2] * AbsR(i1, j);
      const double rb = eb[j1] * AbsR(i, j2) + eb[j2] * AbsR(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) return false;
    }
  }
  return true;
}


double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace

Eigen::Quaterniond scene_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

Eigen::Vector3d scene_direction(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Vector3d d;
  do d = Eigen::Vector3d(n(rng), n(rng), n(rng));
  while (d.squaredNorm() < 1e-12);
  return d.normalized();
}

BodyBounds body_bounds(const ObjectType& t, const Body& b) {
  const Eigen::Matrix3d R = b.pose.rotation.toRotationMatrix();
  return body_bounds(t, b, R, R * (0.5 * (t.lo + t.hi)) + b.pose.translation);
}

BodyBounds body_bounds(const ObjectType& t, const Body& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& c) {
  BodyBounds bb;
  bb.centre = R * t.centre + b.pose.translation;
  bb.radius = t.radius;
  const Eigen::Vector3d e = R.cwiseAbs() * (0.5 * (t.hi - t.lo));
  bb.box.lo = c - e;
  bb.box.hi = c + e;
  // No point of the body is farther than |centre| + radius from its origin.
  bb.max_speed = b.velocity.norm() + b.spin.norm() * (t.centre.norm() + t.radius);
  bb.max_accel = 0;  // velocities change only in responses, which flag the body
  return bb;
}

Scene make_scene(const SceneSpec& spec) {
  if (spec.objects == 0) throw std::invalid_argument("scene: objects must be at least 1");
  if (!(spec.side > 0) || !std::isfinite(spec.side)) throw std::invalid_argument("scene: side must be positive");
  if (!(spec.density > 0 && spec.density <= 0.3))
    throw std::invalid_argument("scene: density " + std::to_string(spec.density) + " is outside (0, 0.3]");
  if (!(spec.speed >= 0) || !std::isfinite(spec.speed)) throw std::invalid_argument("scene: speed must be >= 0");
  if (!(spec.spin >= 0) || !std::isfinite(spec.spin)) throw std::invalid_argument("scene: spin must be >= 0");
  if (!(spec.voxel > 0) || !std::isfinite(spec.voxel)) throw std::invalid_argument("scene: voxel must be > 0");
  std::string source;
  uint64_t hash = 0;
  Mesh mesh = load_source(spec.shape, &source, &hash);
  // Scale so that the objects fill `density` of the cube, and centre the mesh on its box's centre.
  const double volume = mesh.volume();
  const double s = std::cbrt(spec.density * spec.side * spec.side * spec.side / double(spec.objects) / volume);
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  const Eigen::Vector3d mid = 0.5 * (lo + hi);
  for (auto& v : mesh.vertices) v = (v - mid) * s;
  const double extent = (hi - lo).maxCoeff() * s;
  if (extent / spec.voxel > 1020) {
    char across[32];  // as a double: a tiny voxel makes the count too large for an int, or infinite
    std::snprintf(across, sizeof across, "%.6g", extent / spec.voxel);
    throw std::invalid_argument("scene: voxel " + std::to_string(spec.voxel) + " makes each object " + across +
                                " voxels across, above 2^10");
  }
  if (extent / spec.voxel < 2)
    throw std::invalid_argument("scene: voxel " + std::to_string(spec.voxel) + " is larger than half the object (" +
                                std::to_string(extent) + " across); objects would be a voxel or two");
  ObjectOptions oo;
  oo.voxel = spec.voxel;
  Scene scene;
  scene.side = spec.side;
  auto type = std::make_shared<ObjectType>(
      make_object_type(make_object(mesh, source, hash, oo), spec.shape + " x" + std::to_string(s)));
  scene.types.push_back(type);
  const double r = type->radius;
  if (2 * r >= spec.side) throw std::invalid_argument("scene: the objects do not fit the cube");
  try {
    place_bodies(scene, {spec.objects}, spec.speed, spec.spin, spec.seed);
  } catch (const PlacementError& e) {
    throw std::invalid_argument("scene: could not place object " + std::to_string(e.instance) + " without overlap");
  }
  return scene;
}

void place_bodies(Scene& scene, const std::vector<uint64_t>& counts, double speed, double spin, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
  const double side = scene.side;
  for (size_t i = 0; i < counts.size(); ++i) {
    const ObjectType& type = *scene.types.at(i);
    const double r = type.radius;
    for (uint64_t k = 0; k < counts[i]; ++k) {
      Body b;
      b.type = uint32_t(i);
      b.pose.rotation = scene_rotation(rng);
      Eigen::Vector3d c;
      bool placed = false;
      for (int attempt = 0; attempt < 10000 && !placed; ++attempt) {
        c = Eigen::Vector3d(r + u(rng) * (side - 2 * r), r + u(rng) * (side - 2 * r), r + u(rng) * (side - 2 * r));
        placed = true;
        for (size_t o = 0; o < centres.size(); ++o)
          if ((centres[o] - c).squaredNorm() < (r + radii[o]) * (r + radii[o])) {
            placed = false;
            break;
          }
      }
      if (!placed) throw PlacementError(uint32_t(i), k);
      centres.push_back(c);
      radii.push_back(r);
      b.pose.translation = c - b.pose.rotation * type.centre;
      b.velocity = scene_direction(rng) * (speed * r * u(rng));
      b.spin = scene_direction(rng) * (spin * u(rng));
      scene.bodies.push_back(b);
    }
  }
}

Simulation::Simulation(Scene scene, const SimOptions& opt) : scene_(std::move(scene)), opt_(opt) {
  broadphase_ = make_broadphase(opt.pruning);
  DeviceConfig cfg;
  cfg.LANES = opt.lanes;
  std::vector<const ObjectType*> types;
  for (const auto& t : scene_.types) types.push_back(t.get());
  if (opt.device)
    cfg = *opt.device;
  else if (opt.backend != "rtl")
    cfg = fit_memory(cfg, types);
  DeviceOptions dopt;
  dopt.threads = opt.threads;
  collider_ = std::make_unique<PairCollider>(make_device(opt.backend, cfg, dopt), scene_.types);
  moved_.assign(scene_.bodies.size(), true);
}

void Simulation::compute_bounds() {
  const size_t n = scene_.bodies.size();
  bounds_.resize(n);
  rot_.resize(n);
  box_centre_.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const Body& b = scene_.bodies[i];
    const ObjectType& t = *scene_.types[b.type];
    rot_[i] = b.pose.rotation.toRotationMatrix();
    box_centre_[i] = rot_[i] * (0.5 * (t.lo + t.hi)) + b.pose.translation;
    bounds_[i] = body_bounds(t, b, rot_[i], box_centre_[i]);
    bounds_[i].moved_unexpectedly = moved_[i];
  }
}

FrameStats Simulation::step() {
  FrameStats st;
  st.frame = frame_;
  const size_t n = scene_.bodies.size();
  std::fill(moved_.begin(), moved_.end(), false);

  // Integrate (explicit Euler), renormalising the orientation; bounce off the walls by the bounding sphere.
  double t0 = now();
  for (size_t i = 0; i < n; ++i) {
    Body& b = scene_.bodies[i];
    b.pose.translation += b.velocity;
    const Eigen::Quaterniond w(0, b.spin.x(), b.spin.y(), b.spin.z());
    Eigen::Quaterniond q = b.pose.rotation;
    q.coeffs() += 0.5 * (w * q).coeffs();
    b.pose.rotation = q.normalized();
    const ObjectType& t = *scene_.types[b.type];
    const Eigen::Vector3d c = b.pose.rotation * t.centre + b.pose.translation;
    for (int a = 0; a < 3; ++a) {
      if ((c[a] - t.radius < 0 && b.velocity[a] < 0) || (c[a] + t.radius > scene_.side && b.velocity[a] > 0)) {
        b.velocity[a] = -b.velocity[a];
        moved_[i] = true;
        ++st.wall_hits;
      }
    }
  }
  double t1 = now();
  st.t_integrate = t1 - t0;

  compute_bounds();
  double t2 = now();
  st.t_bounds = t2 - t1;

  broadphase_->update(bounds_, frame_);
  const std::vector<BodyPair>& pairs = broadphase_->pairs();
  double t3 = now();
  st.t_broadphase = t3 - t2;

  // Mid-phase: the enclosing spheres, then the oriented boxes of the two bodies (separating-axis test over the 15
  // axes), then the device.
  requests_.clear();
  tested_.clear();
  for (size_t k = 0; k < pairs.size(); ++k) {
    const uint32_t ia = pairs[k].first, ib = pairs[k].second;
    const Body &a = scene_.bodies[ia], &b = scene_.bodies[ib];
    if (opt_.midphase && (!spheres_overlap(bounds_[ia], bounds_[ib]) ||
                          !boxes_overlap(*scene_.types[a.type], rot_[ia], box_centre_[ia], *scene_.types[b.type],
                                         rot_[ib], box_centre_[ib])))
      continue;
    PairRequest r;
    r.a = a.type;
    r.b = b.type;
    r.pose_a = a.pose;
    r.pose_b = b.pose;
    requests_.push_back(r);
    tested_.push_back(uint32_t(k));
  }
  PairOptions po;
  po.mode = opt_.mode;
  po.both_directions = opt_.both_directions;
  po.cull = opt_.cull;
  collider_->collide(requests_, po, results_);
  double t4 = now();
  st.t_narrow = t4 - t3;
  st.pairs = pairs.size();
  st.tested = requests_.size();

  // Response, in the broadphase's order (deterministic): for a touching pair that is approaching along the contact
  // normal, exchange the velocity components along it (an elastic impulse between equal masses) and reverse both
  // spins (the paper's rotation response). A pair already separating is left alone, so it cannot stick.
  for (size_t q = 0; q < requests_.size(); ++q) {
    const PairResult& r = results_[q];
    const size_t k = tested_[q];
    st.lookups += r.lookups;
    st.hits += r.hits;
    st.contacts += r.contacts.size();
    st.device_cycles += r.cycles;
    if (r.hits == 0) continue;
    ++st.touching;
    Body &a = scene_.bodies[pairs[k].first], &b = scene_.bodies[pairs[k].second];
    // The normal from A towards B: A's outward normals where A's shell is in B, minus B's where B's is in A; the
    // line between the bounding spheres' centres when the contacts give none (COUNT, or normals that cancel).
    Eigen::Vector3d nrm = Eigen::Vector3d::Zero();
    for (const Contact& c : r.contacts) nrm += c.a_in_b ? c.normal : -c.normal;
    if (nrm.squaredNorm() < 1e-12) nrm = bounds_[pairs[k].second].centre - bounds_[pairs[k].first].centre;
    if (nrm.squaredNorm() < 1e-24) nrm = Eigen::Vector3d::UnitX();
    nrm.normalize();
    const double closing = (b.velocity - a.velocity).dot(nrm);
    if (closing >= 0) continue;  // separating already
    a.velocity += closing * nrm;
    b.velocity -= closing * nrm;
    a.spin = -a.spin;
    b.spin = -b.spin;
    moved_[pairs[k].first] = moved_[pairs[k].second] = true;
    ++st.responses;
  }
  // The stream of the frame is taken one cycle after its last completion record.
  if (st.tested > 0 && collider_->device().models_cycles()) st.device_cycles += 1;
  st.t_response = now() - t4;
  ++frame_;
  return st;
}

uint64_t Simulation::state_hash() const {
  uint64_t h = 1469598103934665603ull;
  auto mix = [&](double v) {
    uint64_t bits;
    std::memcpy(&bits, &v, 8);
    for (int i = 0; i < 8; ++i) {
      h ^= (bits >> (8 * i)) & 0xff;
      h *= 1099511628211ull;
    }
  };
  for (const Body& b : scene_.bodies) {
    for (int i = 0; i < 3; ++i) mix(b.pose.translation[i]), mix(b.velocity[i]), mix(b.spin[i]);
    for (int i = 0; i < 4; ++i) mix(b.pose.rotation.coeffs()[i]);
  }
  return h;
}

}  // namespace voxcd
