// Scenes of any object count: the default voxel that follows the objects' size (and keeps the paper's scene as it
// was), --resolution beside --voxel, and placement at every density that fits (at random where it succeeds, with
// the draws of before; else on a lattice), with a clear error where no placement can exist.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "tests/error_text.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

using test::error_text;

// Every pair of bodies: bounding spheres apart (touching allowed to rounding), every sphere inside the cube.
void expect_apart_and_inside(const Scene& sc) {
  std::vector<BodyBounds> b;
  for (const Body& body : sc.bodies) b.push_back(body_bounds(*sc.types[body.type], body));
  for (size_t i = 0; i < b.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      ASSERT_GE(b[i].centre[a] - b[i].radius, -1e-9) << "body " << i;
      ASSERT_LE(b[i].centre[a] + b[i].radius, sc.side + 1e-9) << "body " << i;
    }
    for (size_t j = i + 1; j < b.size(); ++j)
      ASSERT_GE((b[i].centre - b[j].centre).norm(), b[i].radius + b[j].radius - 1e-9) << i << " " << j;
  }
}

bool same_bodies(const Scene& a, const Scene& b) {
  if (a.bodies.size() != b.bodies.size()) return false;
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const Body &x = a.bodies[i], &y = b.bodies[i];
    if (x.type != y.type || x.pose.translation != y.pose.translation ||
        x.pose.rotation.coeffs() != y.pose.rotation.coeffs() || x.velocity != y.velocity || x.spin != y.spin)
      return false;
  }
  return true;
}

uint64_t run(const RunConfig& spec, int frames) {
  Simulation sim(make_scene(spec), RunConfig{});
  for (int f = 0; f < frames; ++f) sim.step();
  return sim.state_hash();
}

// The paper's scene runs exactly as before the default voxel followed the objects' size (voxel 1 at 64 objects
// and 2.5%), and so does any scene given voxel 1: the hashes of the build before this change.
TEST(SceneScale, ThePapersSceneKeepsItsRun) {
  EXPECT_EQ(make_scene(RunConfig{}).types[0]->voxmap().voxel(), 1.0);
  EXPECT_EQ(run(RunConfig{}, 300), 0xe535ccc7878ddda4ull);
  RunConfig s;
  s.types[0].count = 256;
  s.types[0].voxel = 1;
  EXPECT_EQ(run(s, 300), 0xc3bd11b3a4e9d449ull);
}

// The default voxel scales with the object: (64/N)^(1/3) for the polytope at 2.5%, the same voxmap at every N.
TEST(SceneScale, DefaultVoxelFollowsTheObjectsSize) {
  const Scene paper = make_scene(RunConfig{});
  for (size_t n : {2u, 512u, 3000u, 65536u}) {
    RunConfig s;
    s.types[0].count = n;
    const Scene sc = make_scene(s);
    EXPECT_NEAR(sc.types[0]->voxmap().voxel(), std::cbrt(64.0 / double(n)), 1e-12) << n;
    EXPECT_EQ(sc.types[0]->voxmap().dims(), paper.types[0]->voxmap().dims()) << n;
    EXPECT_EQ(sc.bodies.size(), n);
  }
  // And with the density and the cube: the object's volume sets it.
  RunConfig s;
  s.density = 0.05;
  s.side = 200;
  EXPECT_NEAR(make_scene(s).types[0]->voxmap().voxel(), std::cbrt(0.05 * 200 * 200 * 200 / 64 / kPaperObjectVolume),
              1e-12);
  // Thin or flat objects: between 4 and 64 voxels along the longest side whatever their volume.
  EXPECT_EQ(default_voxel(kPaperObjectVolume, 20), 1.0);
  EXPECT_EQ(default_voxel(0, 64), 1.0);
  EXPECT_EQ(default_voxel(1e-9, 32), 0.5);
  EXPECT_EQ(default_voxel(1e9, 8), 2.0);
  // A scene file's type without voxel or resolution: the same rule, so one type is the built-in scene.
  const RunConfig f = parse_scene_file(R"({"types": [{"shape": "polytope36", "count": 300}]})", "one.json");
  RunConfig b;
  b.types[0].count = 300;
  EXPECT_TRUE(same_bodies(make_scene(f), make_scene(b)));
  EXPECT_EQ(make_scene(f).types[0]->voxmap().voxel(), make_scene(b).types[0]->voxmap().voxel());
}

TEST(SceneScale, ResolutionIsVoxelsAlongTheLongestSide) {
  RunConfig s;
  s.types[0].count = 100;
  s.types[0].resolution = 20;
  const Scene sc = make_scene(s);
  Mesh m = make_shape("polytope36");
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  const double each = 0.025 * 100 * 100 * 100 / 100.0;
  const double extent = (hi - lo).maxCoeff() * std::cbrt(each / m.volume());
  EXPECT_NEAR(sc.types[0]->voxmap().voxel(), extent / 20, 1e-12 * extent);
  // In a scene file, beside explicit voxels; the shells follow the smallest voxmap.
  const Scene f = make_scene(parse_scene_file(
      R"({"types": [{"shape": "cube", "count": 8, "size": 4, "resolution": 16},
                    {"shape": "sphere", "count": 4, "size": 6, "voxel": 0.5}], "environment": {"side": 40}})",
      "r.json"));
  EXPECT_NEAR(f.types[0]->voxmap().voxel(), 0.25, 1e-12);
  EXPECT_EQ(f.types[1]->voxmap().voxel(), 0.5);
  EXPECT_NEAR(f.types[1]->shell().frame().voxel, 0.25 / std::sqrt(2.0), 1e-12);
}

TEST(SceneScale, VoxelAndResolutionAreExclusiveAndResolutionIsAtLeastFour) {
  RunConfig s;
  s.types[0].voxel = 1;
  s.types[0].resolution = 10;
  EXPECT_EQ(error_text<OptionError>([&] { make_scene(s); }),
            "types[0]: give \"voxel\" (world units) or \"resolution\" (voxels along the longest side), not both");
  s = RunConfig{};
  s.types[0].resolution = 3;
  EXPECT_EQ(error_text<OptionError>([&] { make_scene(s); }),
            "types[0].resolution: 3 is outside [4, 1020]");
  s.types[0].resolution = 1021;
  EXPECT_EQ(error_text<OptionError>([&] { make_scene(s); }),
            "types[0].resolution: 1021 is outside [4, 1020]");
  // A voxel of fewer than 4 across (but more than 2) names the size that gives 4.
  s = RunConfig{};
  s.types[0].voxel = 4;
  EXPECT_NE(error_text<std::invalid_argument>([&] { make_scene(s); })
                .find("scene: voxel 4.000000 leaves 3.06419 voxels along the object's longest side (12.2568); at "
                      "least 4 are needed: a voxel of at most 3.06419, or a resolution"),
            std::string::npos);
  auto file_error = [](const char* text) {
    return error_text<SceneFileError>([&] { make_scene(parse_scene_file(text, "s.json")); });
  };
  EXPECT_EQ(file_error(R"({"types": [{"shape": "cube", "voxel": 1, "resolution": 8}]})"),
            "s.json: types[0]: give \"voxel\" (world units) or \"resolution\" (voxels along the longest side), not "
            "both");
  EXPECT_EQ(file_error(R"({"types": [{"shape": "cube", "resolution": 3}]})"),
            "s.json: types[0].resolution: 3 is outside [4, 1020]");
  EXPECT_EQ(file_error(R"({"types": [{"shape": "cube", "resolution": 8.5}]})"),
            "s.json: types[0].resolution: must be an integer, not 8.5");
  EXPECT_EQ(file_error(R"({"types": [{"shape": "cube", "resolution": "fine"}]})"),
            "s.json: types[0].resolution: must be an integer, not string");
}

// The random placement (up to 10,000 uniform tries a body against every body placed so far) as it was before the
// spatial grid and the lattice: place_bodies must give exactly its bodies wherever it succeeds.
std::vector<Body> place_as_before(const Scene& scene, const std::vector<uint64_t>& counts, double speed, double spin,
                                  uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
  std::vector<Body> out;
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
      if (!placed) return {};
      centres.push_back(c);
      radii.push_back(r);
      b.pose.translation = c - b.pose.rotation * type.centre;
      b.velocity = scene_direction(rng) * (speed * r * u(rng));
      b.spin = scene_direction(rng) * (spin * u(rng));
      out.push_back(b);
    }
  }
  return out;
}

TEST(ScenePlacement, RandomPlacementIsAsBeforeWhereItSucceeds) {
  // Two types of different radii, crowded enough that the last bodies need many tries.
  const Scene two = make_scene(parse_scene_file(
      R"({"types": [{"shape": "polytope36", "count": 1, "size": 6}, {"shape": "torus", "count": 1, "size": 3}]})",
      "two.json"));
  const uint64_t first = test::seed(1);
  for (uint64_t seed : {first, first + 1, first + 2}) {
    Scene sc;
    sc.side = 55;
    sc.types = two.types;
    const std::vector<uint64_t> counts = {150, 400};
    place_bodies(sc, counts, 0.1, 0.02, seed);
    Scene want = sc;
    want.bodies = place_as_before(sc, counts, 0.1, 0.02, seed);
    ASSERT_EQ(want.bodies.size(), 550u) << "the old placement must succeed here for the comparison to mean something";
    EXPECT_TRUE(same_bodies(sc, want)) << "seed " << seed;
  }
}

TEST(ScenePlacement, LatticeCapacity) {
  // r = 9.99 in a cube of 100: centres in [9.99, 90.01]; simple cubic (5 a side, 125) beats face-centred cubic
  // (6^3 / 2). At r = 10 the spacing's hair above touching leaves simple cubic 4 a side: face-centred cubic wins.
  EXPECT_EQ(lattice_capacity(100, 9.99), 125u);
  EXPECT_EQ(lattice_capacity(100, 10), 108u);
  // Small spheres: face-centred cubic, 141 grid points a side, half of them.
  EXPECT_EQ(lattice_capacity(100, 0.5), (141ull * 141 * 141 + 1) / 2);
  EXPECT_EQ(lattice_capacity(100, 49), 1u);
  EXPECT_EQ(lattice_capacity(100, 50), 0u);
}

// Beyond what random placement reaches (bounding spheres filling 57% of the cube): the lattice places every body,
// apart and inside, the same for a seed and different for another.
TEST(ScenePlacement, HighDensityPlacesOnALatticeWithoutOverlap) {
  RunConfig s;
  s.types[0].count = 4096;
  s.density = 0.14;
  const Scene a = make_scene(s);
  ASSERT_EQ(a.bodies.size(), 4096u);
  expect_apart_and_inside(a);
  EXPECT_TRUE(same_bodies(a, make_scene(s)));
  s.seed = 2;
  const Scene b = make_scene(s);
  expect_apart_and_inside(b);
  EXPECT_FALSE(same_bodies(a, b));
  // A few objects, crowded: 30 at 10% (spheres of radius 14.8, 32 sites).
  s = RunConfig{};
  s.types[0].count = 30;
  s.density = 0.1;
  const Scene c = make_scene(s);
  expect_apart_and_inside(c);
  EXPECT_TRUE(place_as_before(c, {30}, s.speed, s.spin, s.seed).empty())
      << "random placement must fail here for the lattice to be tested";
}

TEST(ScenePlacement, MixedSizesOnTheLattice) {
  // Three sizes at a fill random placement does not reach (spheres fill half the cube): each body keeps its own
  // radius from the others.
  const RunConfig f = parse_scene_file(
      R"({"types": [{"shape": "polytope36", "count": 500, "size": 6}, {"shape": "polytope36", "count": 400, "size": 5.6},
                    {"shape": "icosahedron", "count": 100, "size": 4.5}], "environment": {"side": 70}})",
      "mixed.json");
  const Scene a = make_scene(f);
  ASSERT_EQ(a.bodies.size(), 1000u);
  expect_apart_and_inside(a);
  EXPECT_TRUE(same_bodies(a, make_scene(f)));
  EXPECT_TRUE(place_as_before(a, {500, 400, 100}, f.speed, f.spin, f.seed).empty())
      << "random placement must fail here for the lattice to be tested";
}

TEST(ScenePlacement, ImpossibleDensitySaysTheMostThatFits) {
  RunConfig s;
  s.density = 0.3;
  const std::string e = error_text<std::invalid_argument>([&] { make_scene(s); });
  EXPECT_EQ(e.rfind("scene: could not place object 27 of 64 without overlapping bounding spheres: at density 0.3 "
                    "each object's bounding sphere has radius 16.6",
                    0),
            0u)
      << e;
  const std::string most = "fit up to a density of about ";
  const size_t at = e.find(most);
  ASSERT_NE(at, std::string::npos) << e;
  const double d = std::stod(e.substr(at + most.size()));
  EXPECT_GT(d, 0.1);
  EXPECT_LT(d, 0.2);
  // Just below it, they fit.
  s.density = 0.97 * d;
  EXPECT_EQ(make_scene(s).bodies.size(), 64u);
  // In a scene file: the key, the counts and the most that fit.
  const std::string fe = error_text<SceneFileError>([&] {
    make_scene(parse_scene_file(R"({"types": [{"shape": "plate", "count": 64}]})", "plates.json"));
  });
  EXPECT_EQ(fe.rfind("plates.json: types[0].count: could not place instance 14 of 64 without overlapping another (the "
                     "cube is too full): even packed on a lattice, bounding spheres of radius ",
                     0),
            0u)
      << fe;
  EXPECT_NE(fe.find(" fit at most 14 of the 64 objects; lower environment.density (0.025) or the counts"),
            std::string::npos)
      << fe;
}

}  // namespace
}  // namespace voxcd
