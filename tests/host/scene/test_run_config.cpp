// One run configuration (host/scene/run_config.h): every limit and allowed-value list refused by the one check with
// a message naming the field and where it was given (a scene file's key, an option, a value set in code), the limits
// themselves accepted, options applied over the scene file (file < options), and a round trip scene file ->
// RunConfig -> summary (the summary reports the configuration the run used).
#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/error_text.h"
#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd {
namespace {

using test::error_text;

// A scene file of one cube type with `extra` top-level keys (", \"frames\": 3") and `type` keys.
std::string scene(const std::string& extra = "", const std::string& type = "") {
  return R"({"types": [{"shape": "cube")" + type + "}]" + extra + "}";
}

std::string file_error(const std::string& text) {
  return error_text<SceneFileError>([&] { parse_scene_file(text, "s.json"); });
}

// The option error of `options` over the built-in scene: "<options>: <message>".
std::string option_error(const RunConfig& options) {
  try {
    run_config(options);
  } catch (const OptionError& e) {
    std::string names;
    for (const auto& o : e.options) names += (names.empty() ? "" : ", ") + o;
    EXPECT_EQ(std::string(e.what()), names + ": " + e.message);
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an option error: " << e.what();
  }
  return "(no error)";
}

RunConfig given(RunConfig o, const std::string& field, const std::string& name) {
  o.given[field] = SettingSource{"", name};
  return o;
}

TEST(RunConfig, EachLimitOfAFileNamesTheFileAndTheKey) {
  const std::string res = std::to_string(kMaxVoxelsAcross + 1), objs = std::to_string(kMaxObjects + 1);
  EXPECT_EQ(file_error(scene("", R"(, "resolution": 3)")), "s.json: types[0].resolution: 3 is outside [4, 1020]");
  EXPECT_EQ(file_error(scene("", ", \"resolution\": " + res)),
            "s.json: types[0].resolution: " + res + " is outside [4, " + std::to_string(kMaxVoxelsAcross) + "]");
  EXPECT_EQ(file_error(scene("", R"(, "count": 0)")), "s.json: types[0].count: 0 is outside [1, 1048576]");
  EXPECT_EQ(file_error(scene("", ", \"count\": " + objs)),
            "s.json: types[0].count: " + objs + " is outside [1, 1048576]");
  EXPECT_EQ(file_error(scene("", R"(, "voxel": -1)")), "s.json: types[0].voxel: -1 is outside (0, 1e+12]");
  EXPECT_EQ(file_error(scene("", R"(, "voxel": 1, "resolution": 8)")),
            "s.json: types[0]: give \"voxel\" (world units) or \"resolution\" (voxels along the longest side), "
            "not both");
  EXPECT_EQ(file_error(scene(R"(, "environment": {"density": 0.31})")),
            "s.json: environment.density: 0.31 is outside (0, 0.3]");
  EXPECT_EQ(file_error(scene(R"(, "frames": 0)")), "s.json: frames: 0 is outside [1, 1000000]");
  EXPECT_EQ(file_error(scene(R"(, "frames": 1000001)")), "s.json: frames: 1000001 is outside [1, 1000000]");
  for (int bits : {0, 2, 5, 12, 32})
    EXPECT_EQ(file_error(scene(", \"distance_bits\": " + std::to_string(bits))),
              "s.json: distance_bits: " + std::to_string(bits) + " is not 4, 8 or 16");
  EXPECT_EQ(file_error(scene(R"(, "band": 2)")),
            "s.json: band: is the band of distance fields: it needs \"distance_bits\"");
  EXPECT_EQ(file_error(scene(R"(, "ccd": true)")),
            "s.json: ccd: continuous collision bounds each step by the distance fields: it needs \"distance_bits\"");
  EXPECT_EQ(file_error(scene(R"(, "mode": "SOME")")), "s.json: mode: 'SOME' is not one of ALL, FIRST, COUNT");
  std::string names;
  for (const auto& b : broadphase_names()) names += (names.empty() ? "" : ", ") + b;
  EXPECT_EQ(file_error(scene(R"(, "broadphase": "nope")")), "s.json: broadphase: 'nope' is not one of " + names);
  EXPECT_EQ(file_error(scene(R"(, "clock": 0)")), "s.json: clock: 0 is outside (0, 1000000]");
}

TEST(RunConfig, TheLimitsThemselvesAreAccepted) {
  EXPECT_NO_THROW(parse_scene_file(scene("", ", \"resolution\": " + std::to_string(kMinVoxelsAcross)), "s.json"));
  EXPECT_NO_THROW(parse_scene_file(scene("", ", \"resolution\": " + std::to_string(kMaxVoxelsAcross)), "s.json"));
  EXPECT_NO_THROW(parse_scene_file(scene("", ", \"count\": " + std::to_string(kMaxObjects)), "s.json"));
  EXPECT_NO_THROW(parse_scene_file(scene(R"(, "environment": {"density": 0.3}, "frames": 1000000)"), "s.json"));
  for (int bits : kDistanceBits) {
    const RunConfig c = parse_scene_file(scene(", \"distance_bits\": " + std::to_string(bits)), "s.json");
    EXPECT_EQ(c.distance_bits, bits);
    RunConfig o;
    o.distance_bits = bits;
    EXPECT_NO_THROW(check(o)) << bits;
  }
}

TEST(RunConfig, EachLimitOfAnOptionNamesTheOption) {
  RunConfig o;
  o.types[0].resolution = kMaxVoxelsAcross + 1;
  EXPECT_EQ(option_error(given(o, "types[0].resolution", "resolution")),
            "resolution: " + std::to_string(kMaxVoxelsAcross + 1) + " is outside [4, 1020]");
  o = RunConfig{};
  o.types[0].count = 0;
  EXPECT_EQ(option_error(given(o, "types[0].count", "objects")), "objects: 0 is outside [1, 1048576]");
  o = RunConfig{};
  o.types[0].voxel = -2;
  EXPECT_EQ(option_error(given(o, "types[0].voxel", "voxel")), "voxel: must be a positive number of world units");
  o.types[0].resolution = 8;
  EXPECT_EQ(option_error(given(given(o, "types[0].voxel", "voxel"), "types[0].resolution", "resolution")),
            "voxel, resolution: give the voxel size in world units (--voxel) or the voxels along an object's longest "
            "side (--resolution), not both");
  o = RunConfig{};
  o.distance_bits = 5;
  EXPECT_EQ(option_error(given(o, "distance_bits", "distance_bits")), "distance_bits: 5 is not 4, 8 or 16");
  o.distance_bits = 0;  // an option may ask for no distance voxmaps
  EXPECT_NO_THROW(run_config(given(o, "distance_bits", "distance_bits")));
  o = RunConfig{};
  o.density = 0.5;
  EXPECT_EQ(option_error(given(o, "density", "density")), "density: 0.5 is outside (0, 0.3]");
  o = RunConfig{};
  o.band = -1;
  EXPECT_EQ(option_error(given(o, "band", "band")), "band: must be a positive number of voxels");
  o = RunConfig{};
  o.frames = 0;
  EXPECT_EQ(option_error(given(o, "frames", "frames")), "frames: 0 is outside [1, 1000000]");
  o = RunConfig{};
  o.ccd = true;
  EXPECT_EQ(option_error(given(o, "ccd", "ccd")),
            "ccd: continuous collision bounds each step by the distance fields: it needs distance voxmaps "
            "(--distance-bits 4, 8 or 16)");
  EXPECT_EQ(error_text<OptionError>([] { mode_option("SOME"); }), "mode: 'SOME' is not ALL, FIRST or COUNT");
}

TEST(RunConfig, AValueSetInCodeNamesTheField) {
  RunConfig c;
  c.types[0].resolution = 2;
  EXPECT_EQ(error_text<OptionError>([&] { check(c); }), "types[0].resolution: 2 is outside [4, 1020]");
  c = RunConfig{};
  c.distance_bits = 7;
  EXPECT_EQ(error_text<OptionError>([&] { check(c); }), "distance_bits: 7 is not 4, 8 or 16");
  c = RunConfig{};
  c.margin = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_text<OptionError>([&] { check(c); }), "margin: must be a finite number");
}

TEST(RunConfig, OptionsOverrideTheFileInOrder) {
  const std::string text = scene(R"(, "environment": {"seed": 5}, "frames": 20, "broadphase": "sap", "mode": "FIRST")",
                                 R"(, "resolution": 8, "count": 3)");
  RunConfig o;
  o.where = "s.json";
  o.seed = 7;
  o.types[0].voxel = 0.5;
  o = given(given(o, "seed", "seed"), "types[0].voxel", "voxel");
  const RunConfig c = run_config(o, text);
  EXPECT_EQ(c.where, "s.json");
  EXPECT_EQ(c.seed, 7u);                       // the option
  EXPECT_EQ(c.frames, 20u);                    // the file's
  EXPECT_EQ(c.broadphase, "sap");              // the file's
  EXPECT_EQ(c.mode, Mode::First);              // the file's
  EXPECT_EQ(c.types[0].count, 3u);             // the file's
  EXPECT_EQ(c.types[0].voxel, 0.5);            // the option, in place of the file's resolution
  EXPECT_EQ(c.types[0].resolution, 0u);
  EXPECT_EQ(c.given.at("seed").file, "");      // given by the option now
  EXPECT_EQ(c.given.at("frames").file, "s.json");
  EXPECT_EQ(c.given.at("frames").name, "frames");
  EXPECT_EQ(c.given.count("types[0].resolution"), 0u);
  // Without options: the file's values, and a file's default frames (100), not the built-in scene's (1000).
  RunConfig none;
  none.where = "s.json";
  EXPECT_EQ(run_config(none, scene()).frames, 100u);
  EXPECT_EQ(run_config(RunConfig{}).frames, 1000u);
  // The options of the one type refuse a file of two.
  o = given(RunConfig{}, "types[0].count", "objects");
  o.where = "two.json";
  EXPECT_EQ(error_text<OptionError>(
                [&] { run_config(o, R"({"types": [{"shape": "cube"}, {"shape": "sphere"}]})"); }),
            "objects, shape, voxel, resolution: apply only to a scene file with one object type; two.json has 2");
  // An option turns the file's distance fields off, its band with them.
  RunConfig off;
  off.where = "d.json";
  off = given(off, "distance_bits", "distance_bits");
  const RunConfig two_bit = run_config(off, scene(R"(, "distance_bits": 8, "band": 3)"));
  EXPECT_EQ(two_bit.distance_bits, 0);
  EXPECT_EQ(two_bit.device_distance_bits(), 0);
  // A whole distance configuration brings its SB; lanes overrides its LANES.
  RunConfig d;
  d.device = DeviceConfig{};
  d.device->SB = 8;
  d.device->WB = 4;
  d.lanes = 2;
  d = given(given(d, "device", "config"), "lanes", "lanes");
  const RunConfig dc = run_config(d);
  EXPECT_EQ(dc.distance_bits, 8);
  EXPECT_EQ(dc.device->LANES, 2);
  EXPECT_EQ(dc.lanes, 2);
}

TEST(RunConfig, ASceneFileRunsAndItsSummaryReportsItsConfiguration) {
  const std::string text = scene(
      R"(, "environment": {"seed": 9, "density": 0.05}, "frames": 4, "broadphase": "sap", "both_directions": true,)"
      R"( "distance_bits": 8, "band": 3, "clock": 120)",
      R"(, "count": 12, "resolution": 10)");
  RunConfig o;
  o.where = "round.json";
  o.margin = 0.25;
  o = given(o, "margin", "margin");
  const RunConfig c = run_config(o, text);
  const SimulationSummary s = simulate(c);
  EXPECT_EQ(s.file(), "round.json");
  EXPECT_EQ(s.config.objects(), 12u);
  EXPECT_EQ(s.config.seed, 9u);
  EXPECT_EQ(s.config.frames, 4u);
  EXPECT_EQ(s.config.broadphase, "sap");
  EXPECT_TRUE(s.config.both_directions);
  EXPECT_EQ(s.distance_bits(), 8);
  EXPECT_EQ(s.device.SB, 8);
  EXPECT_EQ(s.config.band, 3.0);
  EXPECT_EQ(s.config.margin, 0.25);
  ASSERT_TRUE(s.config.clock.has_value());
  EXPECT_EQ(s.config.clock->mhz, 120.0);
  EXPECT_EQ(s.clock.text(), "120 MHz (given by round.json's \"clock\")") << "a given clock is never replaced";
  EXPECT_EQ(s.shape(), "cube");
  EXPECT_EQ(s.types.size(), 1u);
  // What a recording says of the run comes from the same value.
  const nlohmann::json j = nlohmann::json::parse(record_settings(s));
  EXPECT_EQ(j["scene"], "round.json");
  EXPECT_EQ(j["objects"], 12);
  EXPECT_EQ(j["seed"], 9);
  EXPECT_EQ(j["frames"], 4);
  EXPECT_EQ(j["broadphase"], "sap");
  EXPECT_EQ(j["pruning"], "sap") << "the deprecated spelling, kept for one release";
  EXPECT_EQ(j["mode"], "ALL");
  EXPECT_EQ(j["distance_bits"], 8);
  EXPECT_EQ(j["margin"], 0.25);
  EXPECT_EQ(j["clock_mhz"], 120.0);
  EXPECT_EQ(j["clock_estimate"], false);
  // The same configuration runs the same: equal state hashes.
  EXPECT_EQ(simulate(c).state_hash, s.state_hash);
}

// "pruning", "broadphase"'s spelling before one vocabulary: the same setting with a note naming the file, and an
// error naming the file and the key when both are given and differ.
TEST(RunConfig, PruningIsBroadphasesDeprecatedSpelling) {
  const RunConfig now = parse_scene_file(scene(R"(, "broadphase": "sap")"), "s.json");
  const RunConfig old = parse_scene_file(scene(R"(, "pruning": "sap")"), "s.json");
  EXPECT_EQ(old.broadphase, "sap");
  EXPECT_TRUE(now.notes.empty());
  ASSERT_EQ(old.notes.size(), 1u);
  EXPECT_EQ(old.notes[0], "s.json: pruning is deprecated: use \"broadphase\" (the same key; docs/scenes.md, "
                          "\"Deprecated spellings\")");
  // Both, agreeing: one setting; differing: an error naming the file and the key.
  EXPECT_EQ(parse_scene_file(scene(R"(, "pruning": "sap", "broadphase": "sap")"), "s.json").broadphase, "sap");
  EXPECT_EQ(file_error(scene(R"(, "pruning": "sap", "broadphase": "tree")")),
            "s.json: pruning: is \"broadphase\"'s deprecated spelling, and names 'sap' where \"broadphase\" names "
            "'tree'");
  EXPECT_EQ(file_error(scene(R"(, "pruning": "nope")")).rfind("s.json: pruning: 'nope' is not one of ", 0), 0u);
  // The same run, and the note carried to the run's configuration (the tool prints it, Python warns).
  RunConfig o;
  o.where = "s.json";
  const RunConfig a = run_config(o, scene(R"(, "broadphase": "sap", "frames": 3)"));
  const RunConfig b = run_config(o, scene(R"(, "pruning": "sap", "frames": 3)"));
  EXPECT_EQ(simulate(a).state_hash, simulate(b).state_hash);
  EXPECT_EQ(b.notes, old.notes);
}

// A scene file without "both_directions" tests both directions (a World's default); the built-in scene one (the
// paper's); the key and the option say otherwise.
TEST(RunConfig, BothDirectionsDefaults) {
  EXPECT_FALSE(RunConfig{}.both_directions);
  EXPECT_FALSE(run_config(RunConfig{}).both_directions);
  EXPECT_TRUE(parse_scene_file(scene(), "s.json").both_directions);
  EXPECT_FALSE(parse_scene_file(scene(R"(, "both_directions": false)"), "s.json").both_directions);
  RunConfig o;
  o.where = "s.json";
  o.both_directions = false;
  o = given(o, "both_directions", "both");
  EXPECT_FALSE(run_config(o, scene()).both_directions);
  RunConfig builtin;
  builtin.both_directions = true;
  EXPECT_TRUE(run_config(given(builtin, "both_directions", "both")).both_directions);
}

}  // namespace
}  // namespace voxcd
