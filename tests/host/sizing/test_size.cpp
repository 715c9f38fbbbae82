// Scene files and `voxcd size`: errors that name the key, scene files that build the scenes they describe, the
// derived configurations of the example scenes (tests/scenes/configs.txt must stay what voxcd size derives), each
// of them minimal and meeting its accuracy against exact arithmetic on random poses, and requests that cannot be met.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

const std::string kScenes = VOXCD_SCENES_DIR;

std::string error_of(const std::string& text) {
  try {
    parse_scene_file(text, "s.json");
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RunConfig, ErrorsNameTheFileAndTheKey) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"types": [{"shape": "cube"}], "colour": 1})", "s.json: colour: unknown key"},
      {R"({"types": [{"shape": "cube", "voxel": "big"}]})", "s.json: types[0].voxel: must be a number, not string"},
      {R"({"types": [{"shape": "cube", "voxel": -1}]})", "s.json: types[0].voxel: -1 is outside (0,"},
      {R"({"types": [{"shape": "cube", "count": 0}]})", "s.json: types[0].count: 0 is outside [1,"},
      {R"({"types": [{"shape": "cube", "count": 1.5}]})", "s.json: types[0].count: must be an integer"},
      {R"({"types": [{"shape": "cube"}, {"shape": "nope"}]})", "s.json: types[1].shape: 'nope' is not one of"},
      {R"({"types": [{"shape": "cube", "mesh": "a.obj"}]})", "s.json: types[0]: needs exactly one of"},
      {R"({"types": [{"shape": "cube", "size": 2, "scale": 3}]})", "s.json: types[0]: give \"size\" or \"scale\""},
      {R"({"types": [{"shape": "cube", "sise": 2}]})", "s.json: types[0].sise: unknown key"},
      {R"({"types": [{"shape": "cube"}], "environment": {"density": 0.5}})",
       "s.json: environment.density: 0.5 is outside (0, 0.3]"},
      {R"({"types": [{"shape": "cube", "size": 3}], "environment": {"density": 0.1}})",
       "s.json: environment.density: sizes only the types"},
      {R"({"types": [{"shape": "cube"}], "environment": {"seed": -1}})", "s.json: environment.seed: -1 is outside"},
      {R"({"types": [{"shape": "cube"}], "environment": 3})", "s.json: environment: must be an object"},
      {R"({"types": []})", "s.json: types: is empty"},
      {R"({"types": {"shape": "cube"}})", "s.json: types: must be an array"},
      {R"({"environment": {}})", "s.json: types: missing"},
      {R"({"types": [{"shape": "cube"}], "backend": "gpu"})", "s.json: backend: 'gpu' is not one of"},
      {R"({"types": [{"shape": "cube"}], "rate": 0})", "s.json: rate: 0 is outside (0,"},
      {R"({"types": [{"shape": "cube"}], "both_directions": 1})", "s.json: both_directions: must be true or false"},
      {R"({"types": [{"shape": "cube"}])", "s.json: not valid JSON: parse error at line 1, column"},
      {R"([1, 2])", "s.json: (top level): must be an object, not array"},
      {"", "s.json: not valid JSON"},
      {R"({"types": [{"shape": "cube", "voxel": 1e999}]})", "s.json: not valid JSON: number overflow parsing '1e999'"},
      // A key given twice in one object is refused wherever it is (the JSON reader would keep the last).
      {R"({"types": [{"shape": "cube"}], "types": []})", "s.json: types: appears twice in one object"},
      {R"({"types": [{"shape": "cube"}, {"shape": "torus", "count": [1, 2], "voxel": 1, "shape": "cube"}]})",
       "s.json: types[1].shape: appears twice in one object"},
      {R"({"types": [[{"a": 1}], {"count": 2, "count": 3}]})", "s.json: types[1].count: appears twice in one object"},
      {R"({"types": [{"shape": "cube"}], "environment": {"side": 50, "seed": 2, "side": 60}})",
       "s.json: environment.side: appears twice in one object"},
      {R"({"types": [{"shape": "cube"}], "storage": "thin"})",
       "s.json: storage: 'thin' is not one of auto, dense, sparse"},
      {R"({"types": [{"shape": "cube"}], "storage": 3})", "s.json: storage: must be a string"},
  };
  for (const auto& [text, want] : cases) {
    const std::string got = error_of(text);
    EXPECT_EQ(got.rfind(want, 0), 0u) << "scene " << text << "\n got: " << got << "\n want a message starting: " << want;
  }
}

TEST(RunConfig, MissingMeshNamesTheKeyAndTheFile) {
  const RunConfig f = parse_scene_file(R"({"types": [{"shape": "cube"}, {"mesh": "meshes/gone.obj", "size": 4}]})",
                                       "/tmp/voxcd-scenes/s.json");
  EXPECT_EQ(f.types[1].mesh, "/tmp/voxcd-scenes/meshes/gone.obj");  // relative to the scene file
  try {
    make_scene(f);
    FAIL() << "no error";
  } catch (const SceneFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/tmp/voxcd-scenes/s.json: types[1].mesh: '/tmp/voxcd-scenes/meshes/gone.obj'"),
              std::string::npos)
        << e.what();
  }
}

TEST(RunConfig, OneTypeIsTheBuiltInScene) {
  // The built-in scene's parameters as a scene file: the same bodies, so the same simulation.
  const RunConfig f = parse_scene_file(
      R"({"types": [{"shape": "polytope36", "count": 40}], "environment": {"seed": 5, "density": 0.03}})", "one.json");
  RunConfig spec;
  spec.types[0].count = 40;
  spec.seed = 5;
  spec.density = 0.03;
  Simulation a(make_scene(f), RunConfig{}), b(make_scene(spec), RunConfig{});
  EXPECT_EQ(a.state_hash(), b.state_hash());
  for (int k = 0; k < 30; ++k) {
    const FrameStats sa = a.step(), sb = b.step();
    ASSERT_EQ(sa.hits, sb.hits) << "frame " << k;
  }
  EXPECT_EQ(a.state_hash(), b.state_hash());
}

TEST(RunConfig, MixedSceneHasEveryTypeSizedAsAsked) {
  const RunConfig f = read_scene_file(kScenes + "/mixed.json");
  const Scene s = make_scene(f);
  ASSERT_EQ(s.types.size(), 3u);
  std::vector<uint64_t> count(3, 0);
  for (const Body& b : s.bodies) ++count.at(b.type);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(count[i], f.types[i].count);
    // Every shell is fine enough for the smallest voxmap of the scene (0.5): spacing 0.5 / sqrt(2).
    EXPECT_NEAR(s.types[i]->shell().frame().voxel, 0.5 / std::sqrt(2.0), 1e-12) << f.types[i].name;
    EXPECT_EQ(s.types[i]->voxmap().voxel(), f.types[i].voxel);
  }
  // "size" is the largest extent of the object's box (the voxmap spans it, to within a voxel each side).
  const auto& d = s.types[2]->voxmap().dims();
  const double extent = *std::max_element(d.begin(), d.end()) * f.types[2].voxel;
  EXPECT_GE(extent, f.types[2].size);
  EXPECT_LE(extent, f.types[2].size + 4 * f.types[2].voxel);
  // Bounding spheres do not overlap at the start.
  for (size_t i = 0; i < s.bodies.size(); ++i)
    for (size_t j = i + 1; j < s.bodies.size(); ++j) {
      const BodyBounds bi = body_bounds(*s.types[s.bodies[i].type], s.bodies[i]);
      const BodyBounds bj = body_bounds(*s.types[s.bodies[j].type], s.bodies[j]);
      EXPECT_GE((bi.centre - bj.centre).norm(), bi.radius + bj.radius - 1e-9);
    }
}

struct Listed {
  std::string scene, config;
};

std::vector<Listed> listed_configs() {
  std::ifstream in(kScenes + "/configs.txt");
  std::vector<Listed> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto sp = line.find(' ');
    out.push_back({line.substr(0, sp), line.substr(sp + 1)});
  }
  return out;
}

TEST(Size, ListedConfigurationsAreWhatSizeDerives) {
  const auto listed = listed_configs();
  ASSERT_GE(listed.size(), 3u);
  for (const auto& l : listed) {
    const RunConfig f = read_scene_file(kScenes + "/" + l.scene);
    const SizeReport r = derive_size(f, make_scene(f), {});
    EXPECT_EQ(r.config.to_string(), l.config) << l.scene << ": tests/scenes/configs.txt is stale";
  }
}

// Copies against shared banks: with more than one lane the same frames are measured again with one voxmap in LANES
// banks; the voxmap memory is one copy, the cycles are those of the banked device's timing model (never fewer).
TEST(Size, CopiesAreWeighedAgainstBanks) {
  for (const auto& l : listed_configs()) {
    SCOPED_TRACE(l.scene);
    const RunConfig f = read_scene_file(kScenes + "/" + l.scene);
    const SizeReport r = derive_size(f, make_scene(f), {});
    const Scene& scene = r.scene;  // the types stored as sized (sparse on a sparse device)
    const std::string json = size_json(r);
    if (r.config.LANES == 1) {
      EXPECT_FALSE(r.banked.has_value());
      EXPECT_NE(json.find("\"banked\": null"), std::string::npos);
      continue;
    }
    ASSERT_TRUE(r.banked.has_value());
    const SizeReport::Banked& b = *r.banked;
    EXPECT_EQ(b.config.BANKS, r.config.LANES);
    EXPECT_TRUE(b.config.same_widths(r.config));
    EXPECT_EQ(b.map_bits() * uint64_t(r.config.LANES), r.map_bits());
    EXPECT_GE(b.measure.max_cycles, r.chosen().max_cycles);
    EXPECT_GE(b.measure.mean_cycles, r.chosen().mean_cycles);
    const LaneMeasure again = measure_frames(scene, f, b.config, r.frames);
    EXPECT_EQ(again.max_cycles, b.measure.max_cycles);
    EXPECT_GT(b.measure.mean_cycles, r.chosen().mean_cycles) << "the scene's lanes must meet in a bank sometimes";
    EXPECT_NE(size_text(r).find("banks           BANKS " + std::to_string(r.config.LANES)), std::string::npos);
    EXPECT_NE(json.find("\"voxmap_bits_saved\": " + std::to_string(r.map_bits() - b.map_bits())), std::string::npos);
  }
}

// cfg with one field changed; true when that device cannot run the scene at the accuracy and rate: a width that
// does not validate, a shell or voxmap that does not load, a pose entry that does not fit, a bound above the
// accuracy, or a largest frame over the cycle budget.
TEST(Size, DerivedConfigurationsFitAndAreMinimal) {
  for (const auto& l : listed_configs()) {
    SCOPED_TRACE(l.scene);
    const RunConfig f = read_scene_file(kScenes + "/" + l.scene);
    const SizeReport r = derive_size(f, make_scene(f), {});
    const Scene& scene = r.scene;  // the types stored as sized (sparse on a sparse device)
    const DeviceConfig cfg = r.config;
    // It fits: every type loads, the bound meets the accuracy, the largest frame meets the budget.
    {
      DeviceImage image(cfg);
      for (const auto& t : scene.types) EXPECT_NO_THROW(image.add(*t, shell_order(cfg, *t)));
    }
    EXPECT_LE(size_error_bound(cfg, r.extents), r.accuracy);
    EXPECT_LE(r.chosen().max_cycles, r.budget);
    auto loads = [&](const DeviceConfig& c) {
      try {
        c.validate();
        DeviceImage image(c);
        for (const auto& t : scene.types) image.add(*t, shell_order(c, *t));
        return true;
      } catch (const std::exception&) {
        return false;
      }
    };
    EXPECT_TRUE(loads(cfg));
    DeviceConfig c = cfg;
    c.PF -= 1;  // half-integer shell coordinates are no longer exact: the point term of the bound is back
    EXPECT_TRUE(!loads(c) || size_error_bound(c, r.extents) > r.accuracy) << "PF " << c.PF;
    c = cfg;
    c.PW -= 1;
    EXPECT_FALSE(loads(c)) << "PW " << c.PW;
    c = cfg;
    c.DW -= 1;
    EXPECT_FALSE(loads(c)) << "DW " << c.DW;
    if ((1 << (cfg.SAW - 1)) >= cfg.LANES) {
      c = cfg;
      c.SAW -= 1;
      EXPECT_FALSE(loads(c)) << "SAW " << c.SAW;
    }
    c = cfg;
    c.MAW -= 1;
    EXPECT_FALSE(loads(c)) << "MAW " << c.MAW;
    c = cfg;
    c.MF -= 1;
    EXPECT_GT(size_error_bound(c, r.extents), r.accuracy) << "MF " << c.MF;
    // MW - 1: the largest matrix entry (a rotation entry of exactly 1 times the largest spacing ratio) no longer
    // fits. Half a turn about z gives -1, a quarter turn +1.
    c = cfg;
    c.MW -= 1;
    {
      FloatPose p;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) p.M[i][j] = i == j ? r.extents.max_ratio : 0;
      Job job;
      bool refused = false;
      try {
        c.validate();
        quantize_pose(c, p, job);
      } catch (const std::exception&) {
        refused = true;
      }
      EXPECT_TRUE(refused) << "MW " << c.MW;
      EXPECT_NO_THROW(quantize_pose(cfg, p, job));
    }
    // TW - 1: the translation bound no longer fits (or the accumulator no longer holds the index range).
    c = cfg;
    c.TW -= 1;
    {
      int64_t raw;
      bool refused = false;
      try {
        c.validate();
        refused = !try_quantize(r.extents.max_translation, FixedFormat{c.TW, c.TF()}, &raw);
      } catch (const ConfigError&) {
        refused = true;
      }
      EXPECT_TRUE(refused) << "TW " << c.TW;
      EXPECT_TRUE(try_quantize(r.extents.max_translation, FixedFormat{cfg.TW, cfg.TF()}, &raw));
    }
    // Two bodies at opposite corners of the cube grown by a radius, turned: their pose fits at TW.
    {
      double rmax = 0;
      for (const auto& t : scene.types) rmax = std::max(rmax, t->radius);
      std::mt19937_64 rng(test::seed(3));
      std::normal_distribution<double> n(0, 1);
      for (const auto& p : r.extents.pairs) {
        RigidPose pa, pb;
        pa.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
        pb.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
        pa.translation = Eigen::Vector3d::Constant(-rmax) - pa.rotation * scene.types[p.a]->centre;
        pb.translation = Eigen::Vector3d::Constant(scene.side + rmax) - pb.rotation * scene.types[p.b]->centre;
        Job job;
        EXPECT_NO_THROW(pose_job(cfg, pa, scene.types[p.a]->shell().frame(), pb,
                                 scene.types[p.b]->voxmap().grid().frame(), job));
      }
    }
    // Half the lanes miss the rate.
    if (cfg.LANES > 1) {
      ASSERT_GE(r.lanes.size(), 2u);
      EXPECT_EQ(r.lanes[r.lanes.size() - 2].lanes, cfg.LANES / 2);
      EXPECT_GT(r.lanes[r.lanes.size() - 2].max_cycles, r.budget);
    }
  }
}

// Fixed-point voxel indices against floor of the exact (double) transform on random poses of every pair of types:
// where they differ, the exact point lies within the accuracy (world units) of a voxel boundary. Returns the
// largest such distance seen and counts lookups and disagreements.
struct Agreement {
  uint64_t lookups = 0, differ = 0;
  double worst = 0;  // world units from a voxel boundary, over the points that differ
};

Agreement check_against_exact(const DeviceConfig& cfg, const Scene& scene, uint64_t seed, int poses) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> u(-1, 1);
  Agreement g;
  DeviceImage image(cfg);
  for (const auto& t : scene.types) image.add(*t, shell_order(cfg, *t));
  for (int k = 0; k < poses; ++k) {
    const uint32_t a = uint32_t(rng() % scene.types.size()), b = uint32_t(rng() % scene.types.size());
    const ObjectType &ta = *scene.types[a], &tb = *scene.types[b];
    RigidPose pa, pb;
    pa.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    pb.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    // Centres within the sum of the radii, anywhere in the cube.
    const Eigen::Vector3d cb(scene.side * (0.5 + 0.5 * u(rng)), scene.side * (0.5 + 0.5 * u(rng)),
                             scene.side * (0.5 + 0.5 * u(rng)));
    const Eigen::Vector3d ca = cb + Eigen::Vector3d(u(rng), u(rng), u(rng)) * (ta.radius + tb.radius) / std::sqrt(3.0);
    pa.translation = ca - pa.rotation * ta.centre;
    pb.translation = cb - pb.rotation * tb.centre;
    const GridFrame fa = ta.shell().frame(), fb = tb.voxmap().grid().frame();
    Job job;
    job.nx = tb.voxmap().dims()[0], job.ny = tb.voxmap().dims()[1], job.nz = tb.voxmap().dims()[2];
    pose_job(cfg, pa, fa, pb, fb, job);
    const FloatPose fp = relative_pose(pa, fa, pb, fb);
    const std::vector<ShellWord> words = ta.shell().words(cfg);
    for (size_t q = 0; q < words.size(); ++q) {
      const Located loc = locate(cfg, job, transform(cfg, job, words[q]));
      const Eigen::Vector3d gp = ta.shell().grid_point(q);
      const double p[3] = {gp.x(), gp.y(), gp.z()};
      double y[3];
      float_transform(fp, p, y);
      ++g.lookups;
      for (int i = 0; i < 3; ++i) {
        if (loc.index[i] == int64_t(std::floor(y[i]))) continue;
        ++g.differ;
        const double d = std::abs(y[i] - std::round(y[i])) * fb.voxel;
        g.worst = std::max(g.worst, d);
      }
    }
  }
  return g;
}

TEST(Size, DerivedConfigurationsMeetTheirAccuracyOnRandomPoses) {
  const uint64_t seed = test::seed(9);
  for (const auto& l : listed_configs()) {
    SCOPED_TRACE(l.scene + ", seed " + std::to_string(seed));
    const RunConfig f = read_scene_file(kScenes + "/" + l.scene);
    const SizeReport r = derive_size(f, make_scene(f), {});
    const Scene& scene = r.scene;
    const Agreement g = check_against_exact(r.config, scene, seed, 300);
    EXPECT_LE(g.worst, r.accuracy + 1e-9) << g.differ << " of " << g.lookups << " coordinates differ";
    EXPECT_GT(g.lookups, 100000u);
    // The check can fail: five fraction bits fewer put disagreements beyond the accuracy.
    DeviceConfig coarse = r.config;
    coarse.MF -= 5;
    coarse.MW -= 5;
    const Agreement gc = check_against_exact(coarse, scene, seed, 300);
    EXPECT_GT(gc.worst, r.accuracy) << gc.differ << " of " << gc.lookups << " coordinates differ";
    std::cout << l.scene << ": " << g.lookups << " lookups, " << g.differ << " coordinates differ, farthest "
              << g.worst << " from a boundary (accuracy " << r.accuracy << "); MF - 5: " << gc.differ
              << " differ, farthest " << gc.worst << "\n";
  }
}

SizeError size_error(const std::string& scene, SizeRequest req) {
  const RunConfig f = read_scene_file(kScenes + "/" + scene);
  try {
    derive_size(f, make_scene(f), req);
  } catch (const SizeError& e) {
    return e;
  }
  return SizeError("none", 0, "no error");
}

TEST(Size, ImpossibleRequestsNameTheConstraintAndTheAmount) {
  SizeRequest req;
  req.accuracy = 1e-12;
  SizeError e = size_error("paper.json", req);
  EXPECT_EQ(e.constraint, "accuracy");
  EXPECT_GT(e.factor, 1);
  EXPECT_NE(std::string(e.what()).find("times finer"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("MF 31"), std::string::npos) << e.what();

  req = {};
  req.rate = 1e9;
  req.frames = 20;
  e = size_error("paper.json", req);
  EXPECT_EQ(e.constraint, "rate");
  EXPECT_GT(e.factor, 1);
  EXPECT_NE(std::string(e.what()).find("64 lanes take"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("times faster"), std::string::npos) << e.what();
  // Neither storage meets it: the dense device's reason, then the sparse one's.
  EXPECT_NE(std::string(e.what()).find("; stored sparse on a sparse device: rate: 64 lanes take"), std::string::npos)
      << e.what();

  // The rate 64 lanes reach, asked for exactly, is met; a little more is not.
  req.rate = 0.999e9 / e.factor;
  SizeReport r = derive_size(read_scene_file(kScenes + "/paper.json"),
                             make_scene(read_scene_file(kScenes + "/paper.json")), req);
  EXPECT_EQ(r.config.LANES, 64);

  // Memory: types that need more shell words than the largest shell memory holds.
  const RunConfig f = read_scene_file(kScenes + "/small.json");
  Scene huge = make_scene(f);
  const uint64_t points = huge.types[0]->shell().size();
  DeviceConfig narrow;
  huge.types.resize(1);
  while (huge.types.size() * points <= (uint64_t{1} << 24)) huge.types.push_back(huge.types[0]);
  try {
    derive_memory(narrow, huge);
    ADD_FAILURE() << "no error";
  } catch (const SizeError& x) {
    EXPECT_EQ(x.constraint, "memory");
    const uint64_t need = huge.types.size() * points;
    EXPECT_NEAR(x.factor, double(need) / double(1 << 24), 1e-12);
    EXPECT_NE(std::string(x.what()).find("need " + std::to_string(need) + " shell words"), std::string::npos)
        << x.what();
  }
}

// The scene file's types stored as `storage` (make_scene), whatever the file says.
Scene scene_stored(RunConfig f, ObjectStorage storage) {
  f.storage = storage;
  return make_scene(f);
}

// A scene of large objects (tests/scenes/large.json, tori and spheres about 90 voxels across): stored sparse, its
// device needs less memory (a shell word a brick of points instead of a point; bricks only near the surface), so
// voxcd size takes a sparse device (BL 3) for the types stored sparse and sizes it on that device's own frames.
TEST(SizeStorage, SparseWinsForLargeObjects) {
  const RunConfig f = read_scene_file(kScenes + "/large.json");
  const SizeReport r = derive_size(f, make_scene(f), {});
  const StorageChoice& s = r.storage;
  ASSERT_TRUE(s.dense.met()) << s.dense.failed;
  ASSERT_TRUE(s.sparse.met()) << s.sparse.failed;
  EXPECT_TRUE(s.chose_sparse);
  EXPECT_EQ(s.fixed_by, "");
  EXPECT_LT(s.sparse.memory_bits(), s.dense.memory_bits());
  EXPECT_EQ(s.sparse.storage, ObjectStorage::kSparse);
  EXPECT_EQ(r.config, s.sparse.config);
  EXPECT_EQ(r.config.BL, 3);
  EXPECT_EQ(r.config.PW, 24) << "a shell brick in a shell word, and no wider";
  EXPECT_EQ(s.dense.config.BL, 0);
  EXPECT_EQ(r.shell_bits() + r.map_bits(), s.sparse.memory_bits());
  EXPECT_EQ(s.why(), "the smaller device memory: " + std::to_string(s.sparse.memory_bytes()) +
                         " bytes of device memory against " + std::to_string(s.dense.memory_bytes()) +
                         " stored dense");
  for (const auto& t : r.scene.types) {
    EXPECT_TRUE(map_is_sparse(r.config, *t)) << t->name;
    EXPECT_TRUE(shell_is_sparse(r.config, *t)) << t->name;
  }
  // The lanes were chosen on the sparse device's cycles: its frames again give the same largest frame, which is not
  // the dense device's (a sparse shell's words take a slot per LANES points of a brick, and origin words a slot).
  const LaneMeasure again = measure_frames(r.scene, f, r.config, r.frames);
  EXPECT_GT(again.max_cycles, 0u);
  EXPECT_EQ(again.max_cycles, r.chosen().max_cycles);
  EXPECT_EQ(again.max_cycles, s.sparse.measure.max_cycles);
  EXPECT_NE(again.max_cycles, s.dense.measure.max_cycles);
  EXPECT_LE(again.max_cycles, r.budget);
  // Its memories hold the types only stored sparse (voxcd simulate --storage sparse): stored dense they do not load.
  const Scene dense = scene_stored(f, ObjectStorage::kDense);
  DeviceImage image(r.config);
  EXPECT_THROW(for (const auto& t : dense.types) image.add(*t, shell_order(r.config, *t)), CapacityError);
}

// Each layout's words are those of DeviceImage on its configuration: per type the placement's table, bricks (units
// of UW words) and shell words, type_map_words and type_shell_words, and in all the image's memory; the derived
// memories are the smallest that hold them.
void expect_words_of_the_image(const StorageLayout& l, const Scene& scene) {
  SCOPED_TRACE(l.config.to_string());
  ASSERT_EQ(l.words.types.size(), scene.types.size());
  DeviceImage image(l.config);
  for (size_t i = 0; i < scene.types.size(); ++i) {
    const ObjectType& t = *scene.types[i];
    const DeviceImage::Placement p = image.placement(image.add(t, shell_order(l.config, t)));
    const TypeWords& w = l.words.types[i];
    EXPECT_EQ(w.name, t.name);
    EXPECT_EQ(w.table, p.map_words) << t.name;
    EXPECT_EQ(w.bricks, uint64_t(p.brick_units) * unit_words(l.config)) << t.name;
    EXPECT_EQ(w.shell, p.shell_count) << t.name;
    EXPECT_EQ(w.map(), type_map_words(l.config, t)) << t.name;
    EXPECT_EQ(w.shell, type_shell_words(l.config, t)) << t.name;
    EXPECT_EQ(w.map_sparse, map_is_sparse(l.config, t)) << t.name;
    EXPECT_EQ(w.shell_sparse, shell_is_sparse(l.config, t)) << t.name;
  }
  EXPECT_EQ(l.words.map(), image.memory().map.size());
  EXPECT_EQ(l.words.shell, image.memory().shell.size());
  EXPECT_GT(2 * l.words.map(), l.config.map_depth()) << "MAW one smaller holds the words";
  EXPECT_GT(2 * l.words.shell, l.config.shell_depth()) << "SAW one smaller holds the words";
}

TEST(SizeStorage, FiguresAreTheDeviceImagesOfTheTypesStoredEachWay) {
  const RunConfig f = read_scene_file(kScenes + "/large.json");
  const SizeReport r = derive_size(f, make_scene(f), {});
  const Scene dense = scene_stored(f, ObjectStorage::kDense), sparse = scene_stored(f, ObjectStorage::kSparse);
  expect_words_of_the_image(r.storage.dense, dense);
  expect_words_of_the_image(r.storage.sparse, sparse);
  const LayoutWords &d = r.storage.dense.words, &p = r.storage.sparse.words;
  EXPECT_EQ(d.bricks, 0u);
  EXPECT_GT(p.bricks, 0u);
  EXPECT_LT(p.table + p.bricks, d.table) << "large objects' bricks and table take fewer words than their dense maps";
  EXPECT_LT(p.shell, d.shell);
  // The memories: as built, the block_rams of the configuration; split, a table and a brick memory that hold them.
  for (const StorageLayout* l : {&r.storage.dense, &r.storage.sparse}) {
    double ramb36 = 0, ebr = 0;
    for (const LayoutMemory& m : built_memories(l->config)) ramb36 += m.ramb36, ebr += m.ebr;
    EXPECT_EQ(ramb36, block_rams(l->config, "xilinx-7").count);
    EXPECT_EQ(ebr, block_rams(l->config, "ice40-hx8k").count);
    const std::vector<LayoutMemory> split = split_memories(l->config, l->words);
    ASSERT_EQ(split.size(), l->words.bricks ? 3u : 2u);
    EXPECT_EQ(split[1].what, "table memory");
    EXPECT_GE(split[1].shape.words, l->words.table);
    EXPECT_LT(split[1].shape.words, 2 * l->words.table);
    EXPECT_EQ(split[1].shape.read_ports, 1);
    if (l->words.bricks) {
      EXPECT_EQ(split[2].what, "brick memory");
      EXPECT_GE(split[2].shape.words, l->words.bricks);
      EXPECT_LT(split[2].shape.words, 2 * l->words.bricks);
    }
  }
  EXPECT_EQ(built_memories(r.storage.sparse.config).back().shape.read_ports, 2);
  EXPECT_EQ(built_memories(r.storage.dense.config).back().shape.read_ports, 1);
}

// The storage fixed: by the scene file's "storage" (small.json says dense although sparse takes less memory), by the
// request over the file, and "auto", which fixes nothing.
TEST(SizeStorage, TheFilesOrTheRequestsStorageFixesIt) {
  const RunConfig small = read_scene_file(kScenes + "/small.json");
  SizeReport r = derive_size(small, make_scene(small), {});
  EXPECT_FALSE(r.storage.chose_sparse);
  EXPECT_EQ(r.config.BL, 0);
  EXPECT_EQ(r.storage.fixed_by, kScenes + "/small.json's \"storage\"");
  ASSERT_TRUE(r.storage.sparse.met()) << "the other layout is sized too";
  EXPECT_LT(r.storage.sparse.memory_bits(), r.storage.dense.memory_bits());
  EXPECT_EQ(r.storage.why().rfind("fixed by " + r.storage.fixed_by + ": ", 0), 0u) << r.storage.why();
  for (const auto& t : r.scene.types) EXPECT_FALSE(t->object.voxmap_sparse()) << t->name;

  SizeRequest req;
  req.storage = ObjectStorage::kSparse;
  req.storage_source = "--storage";
  r = derive_size(small, make_scene(small), req);
  EXPECT_TRUE(r.storage.chose_sparse);
  EXPECT_EQ(r.config.BL, 3);
  EXPECT_EQ(r.storage.fixed_by, "--storage");

  const RunConfig large = read_scene_file(kScenes + "/large.json");
  req.storage = ObjectStorage::kDense;
  r = derive_size(large, make_scene(large), req);
  EXPECT_FALSE(r.storage.chose_sparse);
  EXPECT_EQ(r.config, r.storage.dense.config);
  EXPECT_EQ(r.config.BL, 0);
  EXPECT_GT(r.shell_bits() + r.map_bits(), r.storage.sparse.memory_bits());

  // "auto": the smaller memory chooses, the sparse layout's types each part in its smaller form.
  req.storage = ObjectStorage::kAuto;
  r = derive_size(small, make_scene(small), req);
  EXPECT_EQ(r.storage.fixed_by, "");
  EXPECT_EQ(r.storage.sparse.storage, ObjectStorage::kAuto);
  EXPECT_EQ(r.storage.chose_sparse, r.storage.sparse.memory_bits() < r.storage.dense.memory_bits());
}

// Dense wins where its memory is smaller: distance voxmaps of a small convex object (a sparse distance field's
// bricks are refined far beyond the dense field's nodes), and on a tie (the paper's scene: 3200 bytes either way).
TEST(SizeStorage, DenseWinsWhereItsMemoryIsNotLarger) {
  const RunConfig paper = read_scene_file(kScenes + "/paper.json");
  SizeRequest req;
  req.contact_accuracy = 1;
  req.frames = 20;
  SizeReport r = derive_size(paper, make_scene(paper), req);
  ASSERT_TRUE(r.kind.distance());
  ASSERT_TRUE(r.storage.sparse.met()) << r.storage.sparse.failed;
  EXPECT_FALSE(r.storage.chose_sparse);
  EXPECT_LT(r.storage.dense.memory_bits(), r.storage.sparse.memory_bits());
  EXPECT_EQ(r.config.BL, 0);
  EXPECT_GE(r.storage.sparse.config.TF(), r.storage.sparse.config.WB + 3) << "a sparse distance device's weights";
  EXPECT_EQ(r.storage.why().rfind("the smaller device memory: ", 0), 0u) << r.storage.why();

  r = derive_size(paper, make_scene(paper), {});
  EXPECT_EQ(r.storage.dense.memory_bits(), r.storage.sparse.memory_bits());
  EXPECT_FALSE(r.storage.chose_sparse);
  EXPECT_EQ(r.storage.why().rfind("equal memory, so the dense device", 0), 0u) << r.storage.why();
}

TEST(SizeStorage, JsonGivesBothLayoutsAndTheChoice) {
  const RunConfig f = read_scene_file(kScenes + "/large.json");
  const SizeReport r = derive_size(f, make_scene(f), {});
  const nlohmann::json j = nlohmann::json::parse(size_json(r));
  const nlohmann::json& s = j.at("storage");
  EXPECT_EQ(s.at("chosen"), "sparse");
  EXPECT_EQ(s.at("bl"), 3);
  EXPECT_EQ(j.at("config").at("BL"), 3);
  EXPECT_EQ(s.at("types_stored"), "sparse");
  EXPECT_TRUE(s.at("fixed_by").is_null());
  EXPECT_EQ(s.at("why"), r.storage.why());
  EXPECT_EQ(s.at("block_rams_estimate").get<std::string>().rfind("estimate: ", 0), 0u);
  for (const char* name : {"dense", "sparse"}) {
    SCOPED_TRACE(name);
    const StorageLayout& l = std::string(name) == "dense" ? r.storage.dense : r.storage.sparse;
    const nlohmann::json& x = s.at(name);
    EXPECT_EQ(x.at("met"), true);
    EXPECT_TRUE(x.at("failed").is_null());
    EXPECT_EQ(x.at("config_text"), l.config.to_string());
    EXPECT_EQ(x.at("memory_bytes"), l.memory_bytes());
    EXPECT_EQ(x.at("memory_bits").at("total"), l.memory_bits());
    EXPECT_EQ(x.at("max_cycles"), l.measure.max_cycles);
    EXPECT_EQ(x.at("words").at("table"), l.words.table);
    EXPECT_EQ(x.at("words").at("bricks"), l.words.bricks);
    EXPECT_EQ(x.at("words").at("shell"), l.words.shell);
    EXPECT_EQ(x.at("types").size(), r.scene.types.size());
    EXPECT_EQ(x.at("types")[0].at("table_words"), l.words.types[0].table);
    EXPECT_EQ(x.at("memories_split")[1].at("what"), "table memory");
    EXPECT_EQ(x.at("memories_built").back().at("read_ports"), l.config.sparse() ? 2 : 1);
    EXPECT_EQ(x.at("memories_built").back().at("ramb36"), built_memories(l.config).back().ramb36);
  }
  EXPECT_EQ(s.at("sparse").at("memories_split")[2].at("what"), "brick memory");
  EXPECT_EQ(s.at("dense").at("memories_split").size(), 2u);
  const std::string text = size_text(r);
  EXPECT_NE(text.find("\nstorage         sparse (BL 3), the types stored sparse (voxcd simulate --storage sparse): "),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("\n  sparse split  table memory "), std::string::npos) << text;
}

int run(const std::string& cmd) {
  const int rc = std::system((cmd + " >/tmp/voxcd-test-size.out 2>&1").c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}
std::string output() {
  std::ifstream in("/tmp/voxcd-test-size.out");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(SizeCli, SimulateAndSizeRunOnSceneFiles) {
  const std::string bin = VOXCD_BIN;
  ASSERT_EQ(run(bin + " simulate " + kScenes + "/mixed.json --frames 20 --json"), 0) << output();
  EXPECT_NE(output().find("\"types\": [{\"name\": \"rock\""), std::string::npos) << output();
  // An option overrides the file.
  ASSERT_EQ(run(bin + " simulate " + kScenes + "/mixed.json --frames 20 --broadphase sap"), 0) << output();
  EXPECT_NE(output().find("broadphase sap"), std::string::npos) << output();
  ASSERT_EQ(run(bin + " size " + kScenes + "/small.json --json"), 0) << output();
  EXPECT_NE(output().find(listed_configs().back().config), std::string::npos) << output();
  EXPECT_EQ(run(bin + " size " + kScenes + "/small.json --accuracy 1e-12"), 3);
  EXPECT_NE(output().find("cannot be met: accuracy:"), std::string::npos) << output();
  EXPECT_EQ(run(bin + " size " + kScenes + "/small.json --rate 1e9 --frames 10"), 3);
  EXPECT_NE(output().find("cannot be met: rate:"), std::string::npos) << output();
  std::ofstream(testing::TempDir() + "/bad.json") << R"({"types": [{"shape": "cube", "count": "many"}]})";
  EXPECT_NE(run(bin + " simulate " + testing::TempDir() + "/bad.json"), 0);
  EXPECT_NE(output().find("bad.json: types[0].count: must be an integer"), std::string::npos) << output();
}

}  // namespace
}  // namespace voxcd
