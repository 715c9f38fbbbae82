// N-body scenes: enclosing spheres that really enclose (the paper's does not always), the paper's environment as
// specified, and simulations that are deterministic and the same whatever the broadphase, thread count or backend
// (every broadphase is conservative, so the touching pairs, and so the responses, are the same).
#include <gtest/gtest.h>

#include <random>

#include "voxcd/host/object/bounds.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/object/shapes.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

TEST(Bounds, SmallestSphereAgainstBruteForce) {
  std::mt19937_64 rng(test::seed(11));
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Eigen::Vector3d> p(2 + rng() % 9);
    for (auto& q : p) q = Eigen::Vector3d(u(rng), u(rng), 0.3 * u(rng));
    const Sphere s = min_sphere(p);
    for (const auto& q : p) ASSERT_TRUE(s.contains(q)) << "trial " << trial;
    // No sphere through 2 or 3 of the points that encloses all of them is smaller (the minimum is one of those,
    // or a 4-point one, which is never smaller than the best enclosing 2- or 3-point sphere when one exists).
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < p.size(); ++i)
      for (size_t j = i + 1; j < p.size(); ++j) {
        const Sphere c{0.5 * (p[i] + p[j]), 0.5 * (p[i] - p[j]).norm()};
        bool all = true;
        for (const auto& q : p) all = all && c.contains(q, 1e-9);
        if (all) {
          best = std::min(best, c.radius);
        }
      }
    if (std::isfinite(best)) {
      EXPECT_LE(s.radius, best * (1 + 1e-9)) << "trial " << trial;
    }
  }
}

TEST(Bounds, ThePapersSphereMissesAVertexOfATetrahedron) {
  // A regular tetrahedron: the longest chord is an edge; the sphere on it leaves the other two vertices out.
  const std::vector<Eigen::Vector3d> tet = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  const Sphere paper = longest_chord_sphere(tet);
  int outside = 0;
  for (const auto& v : tet) outside += !paper.contains(v);
  EXPECT_EQ(outside, 2);
  const Sphere s = min_sphere(tet);
  for (const auto& v : tet) EXPECT_TRUE(s.contains(v));
  EXPECT_NEAR(s.radius, std::sqrt(3.0), 1e-9);
  EXPECT_NEAR(s.centre.norm(), 0.0, 1e-9);
}

TEST(Bounds, ObjectTypeSphereEnclosesMeshAndShell) {
  for (const char* name : {"polytope36", "stellated", "torus", "plate"}) {
    const Mesh m = make_shape(name);
    ObjectOptions o;
    o.voxel = 0.1;
    const ObjectType t = make_object_type(make_object(m, name, 0, o), name);
    const Sphere s{t.centre, t.radius};
    for (const auto& v : m.vertices) EXPECT_TRUE(s.contains(v)) << name;
    for (const auto& p : t.shell().points) EXPECT_TRUE(s.contains(p)) << name;
    // And it is not needlessly large: within a voxel diagonal of the mesh's own smallest sphere.
    EXPECT_LE(t.radius, min_sphere(m.vertices).radius + std::sqrt(3.0) * 0.1 + 1e-9) << name;
  }
}

TEST(Scene, ThePapersEnvironment) {
  RunConfig spec;
  spec.types[0].count = 128;
  spec.seed = 5;
  const Scene sc = make_scene(spec);
  ASSERT_EQ(sc.bodies.size(), 128u);
  const ObjectType& t = *sc.types[0];
  // Density: the voxelised solid brackets the mesh volume; the objects fill 2.5% of the cube.
  const auto n = t.voxmap().counts();
  const double v3 = std::pow(t.voxmap().voxel(), 3);
  EXPECT_LE(double(n[kInterior]) * v3 * 128, 0.025 * 1e6);
  EXPECT_GE(double(n[kInterior] + n[kSurface]) * v3 * 128, 0.025 * 1e6);
  for (size_t i = 0; i < sc.bodies.size(); ++i) {
    const BodyBounds bi = body_bounds(t, sc.bodies[i]);
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(bi.centre[a] - bi.radius, -1e-9);
      EXPECT_LE(bi.centre[a] + bi.radius, 100 + 1e-9);
    }
    EXPECT_LE(sc.bodies[i].velocity.norm(), 0.1 * t.radius + 1e-12);
    for (size_t j = i + 1; j < sc.bodies.size(); ++j)
      EXPECT_FALSE(spheres_overlap(bi, body_bounds(t, sc.bodies[j]))) << i << " " << j;
  }
  RunConfig bad = spec;
  bad.density = 0;
  EXPECT_THROW(make_scene(bad), OptionError);
  bad = spec;
  bad.types[0].voxel = 1e-4;
  EXPECT_THROW(make_scene(bad), std::invalid_argument);
}

uint64_t run(const RunConfig& spec, RunConfig opt, int frames, uint64_t* touching = nullptr) {
  Simulation sim(make_scene(spec), opt);
  uint64_t t = 0;
  for (int f = 0; f < frames; ++f) t += sim.step().touching;
  if (touching) *touching = t;
  return sim.state_hash();
}

TEST(Simulate, EveryBroadphaseAndThreadCountGivesTheSameRun) {
  RunConfig spec;
  spec.types[0].count = 40;
  spec.density = 0.05;  // twice the paper's, so that objects meet often
  spec.speed = 0.3;
  spec.types[0].voxel = 1.5;
  spec.seed = 3;
  RunConfig opt;
  uint64_t touching = 0;
  const uint64_t want = run(spec, opt, 150, &touching);
  EXPECT_GT(touching, 20u) << "the run must have collisions for the comparison to mean something";
  for (const std::string& b : broadphase_names()) {
    for (unsigned threads : {1u, 2u}) {
      opt.broadphase = b;
      opt.threads = threads;
      EXPECT_EQ(run(spec, opt, 150), want) << "pruning " << b << " threads " << threads;
    }
  }
  spec.seed = 4;
  opt = RunConfig{};
  EXPECT_NE(run(spec, opt, 150), want) << "another seed, another run";
}

TEST(Simulate, MidphaseDropsPairsButNoContact) {
  // The oriented-box mid-phase drops broadphase pairs before the device; a dropped pair can have no hit, so every
  // frame's hits and the whole run are the same with it off.
  RunConfig spec;
  spec.types[0].count = 60;
  spec.density = 0.05;
  spec.speed = 0.3;
  spec.types[0].voxel = 1.5;
  spec.seed = 5;
  RunConfig on, off;
  off.midphase = false;
  Simulation a(make_scene(spec), on), b(make_scene(spec), off);
  uint64_t pairs = 0, tested = 0, touching = 0;
  for (int f = 0; f < 200; ++f) {
    const FrameStats sa = a.step(), sb = b.step();
    ASSERT_EQ(sa.pairs, sb.pairs) << "frame " << f;
    ASSERT_EQ(sb.tested, sb.pairs) << "frame " << f;
    ASSERT_EQ(sa.hits, sb.hits) << "frame " << f;
    ASSERT_EQ(sa.touching, sb.touching) << "frame " << f;
    pairs += sa.pairs, tested += sa.tested, touching += sa.touching;
  }
  EXPECT_EQ(a.state_hash(), b.state_hash());
  EXPECT_GT(touching, 20u) << "the run must have collisions for the comparison to mean something";
  EXPECT_LT(tested, pairs) << "the mid-phase dropped no pair";
  std::printf("mid-phase: %llu of %llu broadphase pairs tested, %llu touching\n", (unsigned long long)tested,
              (unsigned long long)pairs, (unsigned long long)touching);
}

TEST(Simulate, BackendsAgreeAndBodiesStayInTheCube) {
  RunConfig spec;
  spec.types[0].count = 16;
  spec.density = 0.05;
  spec.speed = 0.5;
  spec.types[0].voxel = 1.5;
  RunConfig opt;
  std::vector<std::string> backends = {"cpu", "ref"};
  if (!rtl_lanes().empty()) backends.push_back("rtl");
  std::vector<uint64_t> cycles;
  uint64_t hash = 0;
  for (const auto& b : backends) {
    opt.backend = b;
    Simulation sim(make_scene(spec), opt);
    uint64_t c = 0;
    for (int f = 0; f < 120; ++f) c += sim.step().device_cycles;
    cycles.push_back(c);
    if (b == "cpu") hash = sim.state_hash();
    EXPECT_EQ(sim.state_hash(), hash) << b;
    const ObjectType& t = *sim.scene().types[0];
    for (const Body& body : sim.scene().bodies) {
      const BodyBounds bb = body_bounds(t, body);
      // A bounce happens in the frame a body crosses a wall; a collision pushing it back out costs one more
      // frame's travel at most.
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(bb.centre[a] - bb.radius, -2 * bb.max_speed - 1e-9);
        EXPECT_LE(bb.centre[a] + bb.radius, 100 + 2 * bb.max_speed + 1e-9);
      }
    }
  }
  for (size_t i = 1; i < cycles.size(); ++i) EXPECT_EQ(cycles[i], cycles[0]) << backends[i];
  EXPECT_GT(cycles[0], 0u);
}

// Wide devices (16 lanes, reduced memories; dense, and sparse with shared banks and brick lanes) run the scene as the
// cpu backend models them: the same state hash and the same device cycles on ref and, with the models, on the RTL
// (every wide model the build has with reduced memories; without models, the configurations of VOXCD_RTL_WIDE_MODELS).
std::vector<DeviceConfig> small_wide_devices() {
  std::vector<DeviceConfig> out;
  for (const DeviceConfig& c : rtl_wide_configs())
    if (c.MAW <= 12) out.push_back(c);  // the full-size ones of VOXCD_RTL_WIDE: the same RTL, a slower model
  if (!out.empty()) return out;
  DeviceConfig dense;
  dense.LANES = 16, dense.SAW = 12, dense.MAW = 12;
  DeviceConfig brick = dense;
  brick.BANKS = 4, brick.BL = 3, brick.TX = 1;
  return {dense, brick};
}

TEST(Simulate, WideDevicesRunTheSceneAsTheCpuBackendModelsThem) {
  RunConfig spec;
  spec.types[0].count = 32;
  spec.density = 0.05;
  spec.speed = 0.5;
  spec.types[0].voxel = 1.5;
  std::vector<std::string> backends = {"cpu", "ref"};
  if (!rtl_wide_configs().empty()) backends.push_back("rtl");
  for (const DeviceConfig& cfg : small_wide_devices()) {
    RunConfig opt;
    opt.device = cfg;
    opt.lanes = cfg.LANES;
    opt.storage = cfg.sparse() ? ObjectStorage::kSparse : ObjectStorage::kDense;
    std::vector<uint64_t> cycles, hashes;
    for (const std::string& b : backends) {
      opt.backend = b;
      Simulation sim(make_scene(spec), opt);
      uint64_t c = 0;
      for (int f = 0; f < 60; ++f) c += sim.step().device_cycles;
      cycles.push_back(c);
      hashes.push_back(sim.state_hash());
    }
    for (size_t i = 1; i < backends.size(); ++i) {
      EXPECT_EQ(hashes[i], hashes[0]) << cfg.to_string() << " on " << backends[i];
      EXPECT_EQ(cycles[i], cycles[0]) << cfg.to_string() << " on " << backends[i];
    }
    EXPECT_GT(cycles[0], 0u) << cfg.to_string();
  }
}

}  // namespace
}  // namespace voxcd
