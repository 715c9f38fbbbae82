// Continuous collision (RunConfig::ccd, host/scene/ccd.h): small bodies moving ten of their lengths a frame pass
// through a thin plate, each other and the walls without it, and never with it; runs without it keep their hashes;
// runs with it are the same on one and two threads; `voxcd simulate` takes "ccd" from a scene file and refuses --ccd
// without distance voxmaps.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "voxcd/host/device/device.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/scene/scene.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261124); }

constexpr double kSide = 20;
constexpr double kCube = 0.4;     // the small bodies' side: 4 voxels of 0.1
constexpr double kSpeed = 4;      // world units per frame: ten body lengths
constexpr double kPlateHalf = 4;  // the plate is 8 x 8 x 0.1

std::shared_ptr<const ObjectType> box_type(const std::string& name, const Eigen::Vector3d& half, double voxel) {
  ObjectOptions o;
  o.voxel = voxel;
  o.distance_bits = 8;
  o.band = 4;
  return std::make_shared<const ObjectType>(
      make_object_type(make_object(make_box(-half, half), "test:" + name, 0, o), name));
}

// The types every test shares (type 0 the plate, type 1 the small cube), built once.
const std::vector<std::shared_ptr<const ObjectType>>& types() {
  static const std::vector<std::shared_ptr<const ObjectType>> t = {
      box_type("plate", Eigen::Vector3d(kPlateHalf, kPlateHalf, 0.05), 0.1),
      box_type("cube", Eigen::Vector3d::Constant(kCube / 2), 0.1)};
  return t;
}

Body body(uint32_t type, const Eigen::Vector3d& at, const Eigen::Quaterniond& q, const Eigen::Vector3d& v) {
  Body b;
  b.type = type;
  b.pose.rotation = q;
  b.pose.translation = at - q * types()[type]->centre;
  b.velocity = v;
  return b;
}

Eigen::Vector3d centre(const Scene& s, size_t i) {
  const Body& b = s.bodies[i];
  return b.pose.rotation * s.types[b.type]->centre + b.pose.translation;
}

RunConfig options(bool ccd, unsigned threads = 1) {
  RunConfig o;
  o.distance_bits = 8;
  o.ccd = ccd;
  o.threads = threads;
  return o;
}

// A tilted plate in the middle of the cube and `count` small cubes on both sides heading straight at it.
Scene plate_scene(uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Scene s;
  s.side = kSide;
  s.types = types();
  const Eigen::Quaterniond tilt(Eigen::AngleAxisd(0.35 * u(rng), Eigen::Vector3d(u(rng), u(rng), 0).normalized()));
  const Eigen::Vector3d mid = Eigen::Vector3d::Constant(kSide / 2), n = tilt * Eigen::Vector3d::UnitZ();
  s.bodies.push_back(body(0, mid, tilt, Eigen::Vector3d::Zero()));
  std::vector<Eigen::Vector3d> local;
  while (int(local.size()) < count) {
    const double side = u(rng) < 0 ? -1 : 1;
    const Eigen::Vector3d p(3 * u(rng), 3 * u(rng), side * (2.5 + 1.5 * std::abs(u(rng))));
    bool clear = true;
    for (const auto& q : local) clear = clear && (q - p).norm() > 2 * kCube;
    if (!clear) continue;
    local.push_back(p);
    const Eigen::Quaterniond q(Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized());
    s.bodies.push_back(body(1, mid + tilt * p, q, -side * kSpeed * n));
  }
  return s;
}

// Pass-throughs of the plate (body 0) between two frames: in the plate's frame, a small body's centre is over the
// plate's face (strictly inside its extent) on one side at one frame and on the other side at the next, and the
// straight line between the two crosses the plate's plane inside the extent too. (The plate moves when bodies hit
// it, so the path in its frame is not straight: a body that went round the plate's edge ends outside the extent.)
int plate_crossings(const Scene& before, const Scene& after) {
  int k = 0;
  auto local = [](const Scene& s, size_t i) {
    const Body& p = s.bodies[0];
    return Eigen::Vector3d(p.pose.rotation.inverse() * (centre(s, i) - centre(s, 0)));
  };
  for (size_t i = 1; i < after.bodies.size(); ++i) {
    const Eigen::Vector3d a = local(before, i), b = local(after, i);
    if ((a.z() < 0) == (b.z() < 0)) continue;
    const Eigen::Vector3d x = a + (b - a) * (a.z() / (a.z() - b.z()));
    auto over = [](const Eigen::Vector3d& p) { return std::abs(p.x()) < kPlateHalf && std::abs(p.y()) < kPlateHalf; };
    if (over(a) && over(b) && over(x)) ++k;
  }
  return k;
}

// Pass-throughs of two small bodies: along the line of their approach their order swaps while their centres come
// closer than a cube's side (their inscribed spheres would overlap).
int pair_crossings(const Scene& before, const Scene& after, size_t i, size_t j, const Eigen::Vector3d& line) {
  const Eigen::Vector3d r0 = centre(before, j) - centre(before, i), r1 = centre(after, j) - centre(after, i);
  if ((r0.dot(line) < 0) == (r1.dot(line) < 0)) return 0;
  const double s = r0.dot(line) / (r0.dot(line) - r1.dot(line));
  return (r0 + s * (r1 - r0)).norm() < kCube ? 1 : 0;
}

// Frames in which some small body has a corner outside the cube.
int outside(const Scene& s) {
  int k = 0;
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    const Body& b = s.bodies[i];
    const Eigen::Vector3d c = centre(s, i);
    const double h = b.type == 0 ? 0 : kCube / 2;
    if (b.type == 0) continue;
    for (int m = 0; m < 8; ++m) {
      const Eigen::Vector3d p = c + b.pose.rotation * Eigen::Vector3d(m & 1 ? h : -h, m & 2 ? h : -h, m & 4 ? h : -h);
      if ((p.array() < -1e-9).any() || (p.array() > kSide + 1e-9).any()) ++k;
    }
  }
  return k;
}

// Exact distances between two disjoint boxes (half extents ha, hb; poses pa, pb): the least over vertex-box and
// edge-edge pairs, where the closest points of two disjoint convex polyhedra lie.
double point_box(const Eigen::Vector3d& p, const RigidPose& pose, const Eigen::Vector3d& h) {
  const Eigen::Vector3d l = pose.rotation.inverse() * (p - pose.translation);
  return (l - l.cwiseMax(-h).cwiseMin(h)).norm();
}
// Ericson, Real-Time Collision Detection, 5.1.9.
double segment_segment(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                       const Eigen::Vector3d& q2) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r), c = d1.dot(r), b = d1.dot(d2);
  const double denom = a * e - b * b;
  double s = denom > 1e-15 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) t = 0, s = std::clamp(-c / a, 0.0, 1.0);
  else if (t > 1) t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
  return ((p1 + d1 * s) - (p2 + d2 * t)).norm();
}
std::array<Eigen::Vector3d, 8> corners(const RigidPose& pose, const Eigen::Vector3d& h) {
  std::array<Eigen::Vector3d, 8> c;
  for (int m = 0; m < 8; ++m)
    c[size_t(m)] = pose.rotation * Eigen::Vector3d(m & 1 ? h.x() : -h.x(), m & 2 ? h.y() : -h.y(), m & 4 ? h.z() : -h.z()) +
                   pose.translation;
  return c;
}
double box_distance(const RigidPose& pa, const Eigen::Vector3d& ha, const RigidPose& pb, const Eigen::Vector3d& hb) {
  const auto ca = corners(pa, ha), cb = corners(pb, hb);
  double d = std::numeric_limits<double>::infinity();
  for (const auto& v : ca) d = std::min(d, point_box(v, pb, hb));
  for (const auto& v : cb) d = std::min(d, point_box(v, pa, ha));
  // The 12 edges of a box: corners differing in one bit.
  for (int i = 0; i < 8; ++i)
    for (int bi : {1, 2, 4})
      if (!(i & bi))
        for (int j = 0; j < 8; ++j)
          for (int bj : {1, 2, 4})
            if (!(j & bj))
              d = std::min(d, segment_segment(ca[size_t(i)], ca[size_t(i | bi)], cb[size_t(j)], cb[size_t(j | bj)]));
  return d;
}

TEST(Ccd, TheBoundNeverExceedsTheDistance) {
  // A plate and a small cube at random orientations, separated by a random plane at gaps from 0 to past the band.
  const uint64_t seed = test_seed();
  std::printf("seed %llu (VOXCD_SEED replays)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<const ObjectType*> tp = {types()[0].get(), types()[1].get()};
  const DeviceConfig cfg = device_config_for("cpu", 4, tp, 8);
  PairCollider collider(make_device("cpu", cfg, DeviceOptions{}), types());
  const DistanceBound bound(types(), cfg);
  PairOptions po;
  po.both_directions = true;
  po.margin = bound.margin();
  const Eigen::Vector3d ha(kPlateHalf, kPlateHalf, 0.05), hb = Eigen::Vector3d::Constant(kCube / 2);
  std::vector<PairRequest> req;
  std::vector<double> exact;
  for (int k = 0; k < 400; ++k) {
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_a.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    r.pose_a.translation = Eigen::Vector3d::Constant(10);
    r.pose_b.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    // Over the plate's face or past its edge; then pushed along n until the plane n.x = c separates them by `gap`.
    // Half of them across the plate's face, the others across a random plane (edges and corners).
    const Eigen::Vector3d n = k % 2 ? Eigen::Vector3d(r.pose_a.rotation * Eigen::Vector3d::UnitZ() * (u(rng) < 0.5 ? -1 : 1))
                                    : Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    r.pose_b.translation = r.pose_a.translation + r.pose_a.rotation * Eigen::Vector3d(5 * (2 * u(rng) - 1), 5 * (2 * u(rng) - 1), 0);
    double top = -1e300, low = 1e300;
    for (const auto& v : corners(r.pose_a, ha)) top = std::max(top, n.dot(v));
    for (const auto& v : corners(r.pose_b, hb)) low = std::min(low, n.dot(v));
    const double gap = 0.6 * u(rng) * u(rng);
    r.pose_b.translation += n * (top + gap - low);
    req.push_back(r);
    exact.push_back(box_distance(r.pose_a, ha, r.pose_b, hb));
  }
  const std::vector<PairResult> res = collider.collide(req, po);
  double slack = 0, worst = 1e300;
  int close = 0;
  for (size_t k = 0; k < req.size(); ++k) {
    const double b = bound.device(0, 1, res[k]);
    EXPECT_LE(b, exact[k]) << "pose " << k << ", seed " << seed;
    worst = std::min(worst, exact[k] - b);
    if (exact[k] < 0.3) slack += exact[k] - b, ++close;
  }
  std::printf("%d poses of 400 within 0.3 of contact: bound below the exact distance by %.3f on average (voxel 0.1); "
              "least slack %.4f\n", close, slack / close, worst);
  EXPECT_GT(close, 100);
}

TEST(Ccd, SmallFastBodiesPassThroughAThinPlateOnlyWithoutIt) {
  const uint64_t seed = test_seed();
  std::printf("seed %llu (VOXCD_SEED replays)\n", (unsigned long long)seed);
  int without = 0, with = 0;
  for (uint64_t k = 0; k < 4; ++k) {
    for (bool ccd : {false, true}) {
      Simulation sim(plate_scene(seed + k, 10), options(ccd));
      int crossings = 0, dropped = 0;
      for (int f = 0; f < 25; ++f) {
        const Scene before = sim.scene();
        const FrameStats st = sim.step();
        crossings += plate_crossings(before, sim.scene());
        dropped += int(st.ccd_dropped);
        if (!ccd) {
          EXPECT_EQ(st.ccd_iterations, 0u);
        }
      }
      (ccd ? with : without) += crossings;
      if (ccd) {
        EXPECT_EQ(crossings, 0) << "seed " << seed + k << ", " << dropped << " bodies dropped at the cap";
      }
    }
  }
  std::printf("plate pass-throughs in 4 scenes of 10 bodies, 25 frames: %d without ccd, %d with\n", without, with);
  EXPECT_GT(without, 10) << "the scene must show tunnelling without ccd, seed " << seed;
  EXPECT_EQ(with, 0);
}

TEST(Ccd, HeadOnBodiesPassThroughEachOtherOnlyWithoutIt) {
  const uint64_t seed = test_seed();
  std::printf("seed %llu (VOXCD_SEED replays)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  int without = 0, with = 0;
  for (int k = 0; k < 4; ++k) {
    // Three pairs on parallel lines, each pair closing at 8 units a frame (20 body lengths).
    Scene s;
    s.side = kSide;
    s.types = types();
    Eigen::Vector3d line(g(rng), g(rng), g(rng));
    line.normalize();
    const Eigen::Vector3d side = line.unitOrthogonal(), up = line.cross(side);
    for (int p = 0; p < 3; ++p) {
      const Eigen::Vector3d mid = Eigen::Vector3d::Constant(kSide / 2) + (p - 1) * 3.0 * side + 0.3 * g(rng) * up;
      const double gap = 5 + g(rng) * 0.5;
      auto q = [&] { return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized(); };
      s.bodies.push_back(body(1, mid - gap * line, q(), kSpeed * line));
      s.bodies.push_back(body(1, mid + gap * line + 0.1 * g(rng) * up, q(), -kSpeed * line));
    }
    for (bool ccd : {false, true}) {
      Simulation sim(s, options(ccd));
      int crossings = 0;
      // Until the first wall bounce: after it the bodies no longer travel along their line.
      for (int f = 0; f < 3; ++f) {
        const Scene before = sim.scene();
        sim.step();
        for (size_t i = 0; i + 1 < s.bodies.size(); i += 2) crossings += pair_crossings(before, sim.scene(), i, i + 1, line);
      }
      (ccd ? with : without) += crossings;
    }
  }
  std::printf("head-on pass-throughs of 12 pairs: %d without ccd, %d with\n", without, with);
  EXPECT_GT(without, 6);
  EXPECT_EQ(with, 0);
}

TEST(Ccd, FastBodiesLeaveTheCubeOnlyWithoutIt) {
  const uint64_t seed = test_seed();
  std::printf("seed %llu (VOXCD_SEED replays)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(2, kSide - 2);
  Scene s;
  s.side = kSide;
  s.types = types();
  for (int i = 0; i < 12; ++i) {
    Eigen::Vector3d v(g(rng), g(rng), g(rng));
    s.bodies.push_back(body(1, Eigen::Vector3d(u(rng), u(rng), u(rng)),
                            Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized(), kSpeed * v.normalized()));
  }
  int without = 0, with = 0;
  for (bool ccd : {false, true}) {
    Simulation sim(s, options(ccd));
    for (int f = 0; f < 40; ++f) {
      sim.step();
      (ccd ? with : without) += outside(sim.scene());
    }
  }
  std::printf("corners outside the cube over 40 frames of 12 bodies: %d without ccd, %d with\n", without, with);
  EXPECT_GT(without, 0);
  EXPECT_EQ(with, 0);
}

TEST(Ccd, DeterministicOnOneAndTwoThreadsAndEveryBroadphase) {
  uint64_t h[2] = {0, 0};
  for (unsigned threads : {1u, 2u}) {
    Simulation sim(plate_scene(test_seed(), 10), options(true, threads));
    uint64_t iterations = 0, events = 0;
    for (int f = 0; f < 15; ++f) {
      const FrameStats st = sim.step();
      iterations += st.ccd_iterations;
      events += st.ccd_toi;
    }
    EXPECT_GT(iterations, 15u);
    EXPECT_GT(events, 0u);
    h[threads - 1] = sim.state_hash();
  }
  EXPECT_EQ(h[0], h[1]);
  // And whatever the frame's broadphase (the queue's wake-ups hold under the advancement's motion bounds).
  for (const char* pruning : {"sap", "queue"}) {
    RunConfig o = options(true, 2);
    o.broadphase = pruning;
    Simulation sim(plate_scene(test_seed(), 10), o);
    for (int f = 0; f < 15; ++f) sim.step();
    EXPECT_EQ(sim.state_hash(), h[0]) << pruning;
  }
}

TEST(Ccd, WithoutItTheRunIsUnchanged) {
  // The paper's scene on the 2-bit device and the plate scene on a distance device, both without ccd: the hashes the
  // stepper gave before continuous collision existed (its scene.cpp of commit e3ee135 linked against this library).
  // The plates' fields have had conservative cells since (docs/objects.md; 0x519c3f6f68caa220 before them, the same
  // stepper on the measured fields alone).
  {
    RunConfig spec;
    Simulation sim(make_scene(spec), RunConfig{});
    for (int f = 0; f < 300; ++f) sim.step();
    EXPECT_EQ(sim.state_hash(), 0xe535ccc7878ddda4ull) << std::hex << sim.state_hash();
  }
  {
    Simulation sim(plate_scene(7, 10), options(false));
    for (int f = 0; f < 40; ++f) sim.step();
    EXPECT_EQ(sim.state_hash(), 0x40b4593e8d5fa8cdull) << std::hex << sim.state_hash();
  }
}

TEST(Ccd, TheCapDropsTheRestOfTheFrameAndCountsIt) {
  RunConfig o = options(true);
  o.ccd_max_iterations = 1;
  Simulation sim(plate_scene(test_seed(), 10), o);
  uint64_t dropped = 0;
  for (int f = 0; f < 10; ++f) {
    const Scene before = sim.scene();
    const FrameStats st = sim.step();
    EXPECT_LE(st.ccd_iterations, 1u);
    dropped += st.ccd_dropped;
    EXPECT_EQ(plate_crossings(before, sim.scene()), 0);
  }
  EXPECT_GT(dropped, 0u);
}

TEST(Ccd, NeedsADistanceDevice) {
  RunConfig o;
  o.ccd = true;
  Scene s;
  s.side = kSide;
  s.types = types();
  s.bodies.push_back(body(1, Eigen::Vector3d::Constant(5), Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero()));
  EXPECT_THROW(Simulation(s, o), std::invalid_argument);
}

std::string run(const std::string& args, int* status) {
  const std::string cmd = std::string(VOXCD_BIN) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  *status = pclose(p);
  return out;
}

TEST(CcdCli, SceneFileKeyRunsThroughSimulate) {
  const std::string path = ::testing::TempDir() + "voxcd_ccd_scene.json";
  std::ofstream(path) << R"({"types": [{"shape": "cube", "count": 8, "size": 1, "voxel": 0.25}],
  "environment": {"side": 12, "speed": 3, "seed": 5}, "distance_bits": 8, "ccd": true, "frames": 6})";
  int status = 0;
  const std::string out = run("simulate " + path + " --json --threads 1", &status);
  ASSERT_EQ(status, 0) << out;
  EXPECT_NE(out.find("\"ccd\": true"), std::string::npos) << out;
  EXPECT_NE(out.find("\"no_tunnelling\": {\"iterations\": "), std::string::npos) << out;
  EXPECT_NE(out.find("\"time_of_impact_events\""), std::string::npos) << out;
  const std::string text = run("simulate " + path + " --threads 1 --no-progress", &status);
  ASSERT_EQ(status, 0) << text;
  EXPECT_NE(text.find("no tunnelling"), std::string::npos) << text;
  // Without ccd the summary has no such line.
  const std::string off = run("simulate --distance-bits 8 --objects 4 --frames 2 --threads 1", &status);
  ASSERT_EQ(status, 0) << off;
  EXPECT_EQ(off.find("no tunnelling"), std::string::npos) << off;
  const std::string json = run("simulate --distance-bits 8 --objects 4 --frames 2 --threads 1 --json", &status);
  ASSERT_EQ(status, 0) << json;
  EXPECT_EQ(json.find("no_tunnelling"), std::string::npos) << json;
}

TEST(CcdCli, CcdWithoutDistanceBitsIsAClearError) {
  int status = 0;
  const std::string out = run("simulate --ccd --frames 1", &status);
  EXPECT_NE(status, 0);
  EXPECT_NE(out.find("--ccd"), std::string::npos) << out;
  EXPECT_NE(out.find("--distance-bits"), std::string::npos) << out;
}

}  // namespace
}  // namespace voxcd
