// The RTL built for configurations `voxcd size` derives (rtl/CMakeLists.txt, VOXCD_RTL_CONFIGS): each model is
// the configuration tests/scenes/configs.txt lists for its scene; conformance vectors generated for that
// configuration pass on it, cycle for cycle; and its scene simulates on it exactly as on the cpu backend.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {
namespace {

const std::string kScenes = VOXCD_SCENES_DIR;

// The scene tests/scenes/configs.txt lists for cfg ("" when none).
std::string scene_of(const DeviceConfig& cfg) {
  std::ifstream in(kScenes + "/configs.txt");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const auto sp = line.find(' ');
    if (parse_config_pairs(line.substr(sp + 1), "configs.txt") == cfg) return line.substr(0, sp);
  }
  return "";
}

TEST(SizeRtl, ModelsAreListedDerivedConfigurations) {
  if (!VOXCD_HAS_MODELS) {
    // A build without the device models (-DVOXCD_DEVICE_MODELS=OFF) has none, and the rtl backend says so.
    EXPECT_TRUE(rtl_configs().empty());
    try {
      make_device("rtl", DeviceConfig{});
      FAIL() << "an rtl device in a build without models";
    } catch (const DeviceError& e) {
      EXPECT_NE(std::string(e.what()).find("VOXCD_DEVICE_MODELS=OFF"), std::string::npos) << e.what();
    }
    return;
  }
  ASSERT_FALSE(rtl_configs().empty()) << "the build has no models of derived configurations (VOXCD_RTL_CONFIGS)";
  for (const DeviceConfig& cfg : rtl_configs()) {
    EXPECT_NE(scene_of(cfg), "") << cfg.to_string();
    EXPECT_FALSE(cfg.same_widths(DeviceConfig{})) << "a derived configuration with the default widths";
    EXPECT_EQ(make_device("rtl", cfg)->config(), cfg);
  }
  // A configuration without a model is refused, naming the ones there are.
  DeviceConfig other = rtl_configs()[0];
  other.TW += 1;
  try {
    make_device("rtl", other);
    FAIL() << "no error";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find(rtl_configs()[0].to_string()), std::string::npos) << e.what();
  }
}

TEST(SizeRtl, ConformanceVectorsOfTheConfigurationPass) {
  for (const DeviceConfig& cfg : rtl_configs()) {
    SCOPED_TRACE(cfg.to_string());
    for (uint64_t seed : {1, 2, 3}) {
      GenerateOptions g;
      g.seed = seed;
      g.jobs = 300;
      g.config = cfg;
      // A quarter of a small derived shell memory for the cloud (the directed blocks shrink to the rest).
      g.cloud_points = std::min<size_t>(g.cloud_points, cfg.shell_depth() / 4);
      const GeneratedVectors v = generate_vectors(g);
      ASSERT_EQ(v.config, cfg);
      std::vector<Record> want = run_stream(cfg, v.memory, v.jobs);
      annotate_cycles(cfg, v.jobs, want);
      auto dev = make_device("rtl", cfg);
      dev->load(v.memory);
      const std::vector<Record> got = dev->run(v.jobs);
      ASSERT_EQ(got.size(), want.size()) << "seed " << seed;
      size_t hits = 0;
      for (size_t k = 0; k < got.size(); ++k) {
        ASSERT_TRUE(got[k].same_as(want[k], true)) << "seed " << seed << ", record " << k;
        hits += got[k].kind == Record::Hit;
      }
      EXPECT_GT(hits, 100u) << "seed " << seed;
    }
  }
}

TEST(SizeRtl, SceneSimulatesOnItsDerivedModelAsOnCpu) {
  for (const DeviceConfig& cfg : rtl_configs()) {
    const std::string scene = scene_of(cfg);
    SCOPED_TRACE(scene + ": " + cfg.to_string());
    RunConfig f = read_scene_file(kScenes + "/" + scene);
    // A sparse device was derived for the types stored sparse (docs/size.md, "Sparse or dense"), or as the file says.
    if (cfg.sparse() && f.storage == ObjectStorage::kDense) f.storage = ObjectStorage::kSparse;
    RunConfig opt;
    opt.broadphase = f.broadphase;
    opt.device = cfg;
    opt.lanes = cfg.LANES;
    opt.backend = "cpu";
    Simulation cpu(make_scene(f), opt);
    opt.backend = "rtl";
    Simulation rtl(make_scene(f), opt);
    ASSERT_EQ(rtl.device_config(), cfg);
    uint64_t hits = 0;
    for (int k = 0; k < 40; ++k) {
      const FrameStats a = cpu.step(), b = rtl.step();
      ASSERT_EQ(a.hits, b.hits) << "frame " << k;
      ASSERT_EQ(a.contacts, b.contacts) << "frame " << k;
      ASSERT_EQ(a.device_cycles, b.device_cycles) << "frame " << k;
      hits += a.hits;
    }
    EXPECT_EQ(cpu.state_hash(), rtl.state_hash());
    EXPECT_GT(hits, 0u);
  }
}

}  // namespace
}  // namespace voxcd
