// voxcd sweep's library side (host/sizing/sweep*.h): the Pareto flags on hand-checked tables, the points' order,
// sweep files and their errors, rows through the results file, and on a small sweep of a scene file the measured
// contact error within the predicted bound on every row.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "voxcd/host/sizing/sweep/sweep.h"
#include "voxcd/host/sizing/sweep/sweep_results.h"
#include "voxcd/host/sizing/sweep/sweep_table.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {
namespace {

const std::string kScenes = VOXCD_SCENES_DIR;

TEST(SweepPareto, HandCheckedTable) {
  // (contact error, cycles, memory)
  const std::vector<std::array<double, 3>> pts = {
      {1.0, 100, 50},  // 0: front (smallest cycles among error 1)
      {1.0, 200, 50},  // 1: dominated by 0
      {0.5, 300, 80},  // 2: front (smallest error)
      {0.5, 300, 90},  // 3: dominated by 2 (more memory)
      {2.0, 100, 10},  // 4: front (smallest memory)
      {2.0, 100, 10},  // 5: equal to 4: on the front as well
      {2.0, 150, 10},  // 6: dominated by 4
      {0.4, 900, 95},  // 7: front (smallest error)
  };
  const std::vector<bool> want = {true, false, true, false, true, true, false, true};
  EXPECT_EQ(pareto_front(pts), want);
  EXPECT_TRUE(pareto_front({}).empty());
  EXPECT_EQ(pareto_front({{3, 3, 3}}), std::vector<bool>{true});
}

TEST(SweepPareto, TableMarksOnlyFeasibleRowsInPointOrder) {
  SweepTable t;
  auto row = [](uint64_t i, double err, uint64_t cycles, uint64_t bits, bool ok = true) {
    SweepRow r;
    r.point.index = i;
    r.contact_bound = err, r.max_cycles = cycles, r.shell_bits = bits;
    if (!ok) r.status = "infeasible: accuracy: too fine";
    return r;
  };
  t.rows = {row(2, 0.1, 10, 10, false), row(0, 1.0, 100, 100), row(1, 2.0, 200, 200), row(3, 0.5, 300, 100)};
  finish_table(t);
  ASSERT_EQ(t.rows.size(), 4u);
  for (size_t i = 0; i < 4; ++i) EXPECT_EQ(t.rows[i].point.index, i);
  EXPECT_TRUE(t.rows[0].pareto);
  EXPECT_FALSE(t.rows[1].pareto);  // point 0 is better in all three
  EXPECT_FALSE(t.rows[2].pareto);  // infeasible: never on the front, though it would dominate everything
  EXPECT_TRUE(t.rows[3].pareto);
}

SweepSpec spec4() {
  SweepSpec s;
  s.scene = kScenes + "/small.json";
  s.lanes = {1, 2};
  s.voxel_scales = {1, 0.5};
  s.distance_bits = {0, 8};
  s.accuracies = {0.02, 0.005};
  s.frames = 20;
  s.clock = 100;
  s.clock_source = "--clock";
  return s;
}

TEST(SweepPoints, CrossProductLanesOutermostAccuracyInnermost) {
  const SweepSpec s = spec4();
  ASSERT_EQ(s.points(), 16u);
  const SweepPoint p0 = point_at(s, 0), p1 = point_at(s, 1), p2 = point_at(s, 2), p15 = point_at(s, 15);
  EXPECT_EQ(p0.text(), "lanes 1, depth 0, voxel x1, distance bits 0, accuracy 0.02");
  EXPECT_EQ(p1.text(), "lanes 1, depth 0, voxel x1, distance bits 0, accuracy 0.005");
  EXPECT_EQ(p2.text(), "lanes 1, depth 0, voxel x1, distance bits 8, accuracy 0.02");
  EXPECT_EQ(p15.text(), "lanes 2, depth 0, voxel x0.5, distance bits 8, accuracy 0.005");
  EXPECT_THROW(point_at(s, 16), std::out_of_range);
}

TEST(SweepPoints, DepthIsTheSecondAxis) {
  SweepSpec s = spec4();
  s.depths = {0, 3};  // the order of the points, whether or not the device offers depth 3
  ASSERT_EQ(s.points(), 32u);
  EXPECT_EQ(point_at(s, 0).text(), "lanes 1, depth 0, voxel x1, distance bits 0, accuracy 0.02");
  EXPECT_EQ(point_at(s, 7).text(), "lanes 1, depth 0, voxel x0.5, distance bits 8, accuracy 0.005");
  EXPECT_EQ(point_at(s, 8).text(), "lanes 1, depth 3, voxel x1, distance bits 0, accuracy 0.02");
  EXPECT_EQ(point_at(s, 16).text(), "lanes 2, depth 0, voxel x1, distance bits 0, accuracy 0.02");
  EXPECT_EQ(point_at(s, 31).text(), "lanes 2, depth 3, voxel x0.5, distance bits 8, accuracy 0.005");
  // The sweep file's key, and through the results file's JSON; a file written before depths has depth 0.
  const SweepSpec f = parse_sweep_file(R"({"depth": [0]})", "s.json", spec4());
  EXPECT_EQ(f.depths, std::vector<int>{0});
  EXPECT_EQ(sweep_from_json(sweep_json(s), "x").depths, (std::vector<int>{0, 3}));
  std::string old = sweep_json(spec4());
  const size_t at = old.find("\"depth\":[0],");
  ASSERT_NE(at, std::string::npos) << old;
  old.erase(at, std::string("\"depth\":[0],").size());
  EXPECT_EQ(sweep_from_json(old, "old").depths, std::vector<int>{0});
  SweepRow r;
  r.point = point_at(s, 8);
  r.latency = 11;
  const SweepRow back = parse_sweep_row(sweep_row_line(r), "x");
  EXPECT_EQ(back.point.depth, 3);
  EXPECT_EQ(back.latency, 11);
  std::string line = sweep_row_line(r);
  line.erase(line.find("\"depth\":3,"), std::string("\"depth\":3,").size());
  EXPECT_EQ(parse_sweep_row(line, "old").point.depth, 0) << "a row written before depths";
}

TEST(SweepRows, CostReadsBackAndOlderRowsTakeTheirDefaults) {
  SweepRow r;
  r.point.index = 3;
  r.point.lanes = 2;
  r.contacts_conservative = 7;
  r.latency = 9;
  r.cost = YosysCost{};
  r.cost->luts = 1234;
  r.cost->ffs = 56;
  r.cost->dsps = 7;
  r.cost->brams = 1.5;
  const SweepRow back = parse_sweep_row(sweep_row_line(r), "x");
  ASSERT_TRUE(back.cost.has_value());
  EXPECT_EQ(back.cost->luts, 1234u);
  EXPECT_EQ(back.cost->ffs, 56u);
  EXPECT_EQ(back.cost->dsps, 7u);
  EXPECT_EQ(back.cost->brams, 1.5);
  EXPECT_EQ(back.contacts_conservative, 7u);
  EXPECT_EQ(sweep_row_line(back), sweep_row_line(r)) << "a row reads back to the same line";
  r.cost.reset();
  const std::string line = sweep_row_line(r);
  EXPECT_NE(line.find("\"cost\":null"), std::string::npos) << line;
  EXPECT_FALSE(parse_sweep_row(line, "x").cost.has_value());
  // A row written before conservative cells and latency: those keys absent, read as 0.
  std::string old = line;
  for (const char* key : {"\"contacts_conservative\":7,", "\"latency\":9,"}) old.erase(old.find(key), std::strlen(key));
  const SweepRow o = parse_sweep_row(old, "old");
  EXPECT_EQ(o.contacts_conservative, 0u);
  EXPECT_EQ(o.latency, 0);
  // A key every row has: its absence is an error naming the file and the key.
  std::string broken = line;
  broken.erase(broken.find("\"status\":\"ok\","), std::strlen("\"status\":\"ok\","));
  try {
    parse_sweep_row(broken, "results.jsonl:2");
    ADD_FAILURE() << "a row without status was read";
  } catch (const SweepError& e) {
    EXPECT_NE(std::string(e.what()).find("results.jsonl:2: not a sweep row"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("status"), std::string::npos) << e.what();
  }
}

TEST(SweepPoints, ADepthTheDeviceDoesNotOfferIsRefusedNamingIt) {
  for (int bad : {-1, 1000}) {
    SweepSpec s = spec4();
    s.depths = {0, bad};
    try {
      check_sweep(s, "s.json");
      ADD_FAILURE() << "depth " << bad << " was taken";
    } catch (const SweepError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("s.json: depth[1]: ", 0), 0u) << e.what();
    }
  }
  SweepSpec s = spec4();
  s.depths = {};
  EXPECT_THROW(check_sweep(s, "s.json"), SweepError);
}

std::string error_of(const std::string& text) {
  try {
    check_sweep(parse_sweep_file(text, "s.json", spec4()), "s.json");
  } catch (const SweepError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepFile, KeysOverrideAndBadFilesNameTheKey) {
  const SweepSpec s = parse_sweep_file(
      R"({"lanes": [4, 8], "voxel_scale": 0.75, "distance_bits": [4], "accuracy": [0.1], "frames": 30,
          "sample_frames": 3, "clock": 250, "cost": true})", "s.json", spec4());
  EXPECT_EQ(s.lanes, (std::vector<int>{4, 8}));
  EXPECT_EQ(s.voxel_scales, std::vector<double>{0.75});
  EXPECT_EQ(s.distance_bits, std::vector<int>{4});
  EXPECT_EQ(s.frames, 30u);
  EXPECT_EQ(s.sample_frames, 3u);
  EXPECT_EQ(s.clock, 250);
  EXPECT_EQ(s.clock_source, "given by s.json's \"clock\"");
  EXPECT_TRUE(s.cost);
  const std::pair<const char*, const char*> bad[] = {
      {"[1, 2]", "s.json: expected a JSON object"},
      {"{\"lanes\": [1, 2", "s.json: not JSON"},
      {"{\"lane\": [1]}", "s.json: lane: unknown key"},
      {"{\"lanes\": [3]}", "s.json: lanes[0]: 3 is not a power of two from 1 to 64"},
      {"{\"lanes\": [128]}", "s.json: lanes[0]: 128 is not a power of two"},
      {"{\"lanes\": []}", "s.json: lanes: is empty"},
      {"{\"lanes\": [1.5]}", "s.json: lanes[0]: 1.5 is not a whole number"},
      {"{\"lanes\": \"1,2\"}", "s.json: lanes: expected a list of numbers"},
      {"{\"distance_bits\": [0, 5]}", "s.json: distance_bits[1]: 5 is not 0 (2-bit states), 4, 8 or 16"},
      {"{\"accuracy\": [0.01, -1]}", "s.json: accuracy[1]: -1 is not a positive number"},
      {"{\"voxel_scale\": [0]}", "s.json: voxel_scale[0]: 0 is not a positive number"},
      {"{\"frames\": -3}", "s.json: frames: expected a whole number"},
      {"{\"sample_frames\": 50}", "s.json: sample_frames: 50 is more than the 20 frames"},
      {"{\"clock\": 0}", "s.json: clock: expected a positive number of MHz"},
      {"{\"cost\": 1}", "s.json: cost: expected true or false"},
  };
  for (const auto& [text, want] : bad) {
    const std::string got = error_of(text);
    EXPECT_NE(got.find(want), std::string::npos) << text << "\n  got: " << got << "\n  want: " << want;
  }
  EXPECT_EQ(error_of("{}"), "");
  EXPECT_THROW(parse_number_list("1,,2", "--lanes"), SweepError);
  EXPECT_THROW(parse_number_list("1,x", "--lanes"), SweepError);
  EXPECT_THROW(parse_number_list("1,", "--lanes"), SweepError);
  EXPECT_EQ(parse_number_list("1,0.5", "--voxel-scale"), (std::vector<double>{1, 0.5}));
}

TEST(SweepResults, RowsRoundTripAndAnotherSweepIsRefused) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "voxcd_test_sweep_results";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "r.jsonl").string();
  const SweepSpec s = spec4();
  SweepRow r;
  r.point = point_at(s, 5);
  r.config = "PW 8";
  r.error_bound = 0.1 / 3, r.contact_bound = 1.7320508075688772, r.contact_measured = 0.123456789;
  r.contacts_checked = 17, r.max_cycles = 12345, r.mean_cycles = 1000.0 / 7, r.rate = 8100.0 / 3;
  r.shell_bits = 1 << 20, r.map_bits = 1 << 12, r.rank = 2, r.seconds = 1.5;
  {
    SweepResults f(path, s);
    EXPECT_TRUE(f.finished().empty());
    f.append(r);
    f.append(r);  // twice: counts once
  }
  {
    SweepResults f(path, s);
    ASSERT_EQ(f.finished().size(), 1u);
    EXPECT_EQ(sweep_row_line(f.finished()[0]), sweep_row_line(r));
  }
  SweepSpec other = s;
  other.accuracies = {0.01};
  try {
    SweepResults f(path, other);
    ADD_FAILURE() << "another sweep's results file was accepted";
  } catch (const SweepError& e) {
    EXPECT_NE(std::string(e.what()).find("holds the results of another sweep"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

// A scene file without "clock" (every scene of tests/scenes gives one), written to a directory of its own.
std::string scene_without_clock() {
  const auto dir = std::filesystem::temp_directory_path() / "voxcd_test_sweep_clock";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "cubes.json").string();
  std::ofstream(path) << R"({"types": [{"shape": "cube", "count": 8, "size": 3, "voxel": 0.25}],
 "environment": {"side": 12, "seed": 2}, "accuracy": 0.02, "rate": 1000, "frames": 3})";
  return path;
}

// Without a clock, each row's rate is at its own configuration's clock, which says whether it was measured for it;
// a clock given is every row's.
TEST(SweepRows, EachRowAtItsOwnConfigurationsClockUnlessOneIsGiven) {
  SweepSpec s;
  s.scene = scene_without_clock();
  s.lanes = {1, 4};
  s.voxel_scales = {1};
  s.distance_bits = {0};
  s.accuracies = {0.02};
  s.frames = 3;
  s.sample_frames = 1;
  check_sweep(s, "test");
  SweepTable t;
  t.spec = s;
  t.frames = s.frames;
  SweepRunner runner(s);
  for (uint64_t i = 0; i < s.points(); ++i) t.rows.push_back(runner.run(i));
  finish_table(t);
  ASSERT_TRUE(t.rows[0].ok() && t.rows[1].ok()) << t.rows[0].status << t.rows[1].status;
  for (const SweepRow& r : t.rows) {
    const DeviceClock want = clock_for(parse_config_pairs(r.config, "row"));
    EXPECT_EQ(r.clock_mhz, want.mhz) << r.config;
    EXPECT_EQ(r.clock_source, want.source) << r.config;
    EXPECT_EQ(r.clock_estimate, want.estimate) << r.config;
    EXPECT_DOUBLE_EQ(r.rate, want.rate(double(r.max_cycles)));
    EXPECT_EQ(parse_sweep_row(sweep_row_line(r), "x").clock_source, r.clock_source) << "the results file keeps it";
  }
  // The sized widths are not the measured configuration's: each row an estimate naming its own lanes.
  EXPECT_TRUE(t.rows[0].clock_estimate);
  EXPECT_NE(t.rows[0].clock_source.find("not measured for LANES 1 "), std::string::npos) << t.rows[0].clock_source;
  EXPECT_EQ(t.rows[1].clock_source.find("LANES 1"), std::string::npos) << t.rows[1].clock_source;
  const std::string text = sweep_text(t);
  EXPECT_NE(text.find("frames/s at each point's own clock"), std::string::npos) << text;
  EXPECT_NE(text.find("; clock 100.4 MHz (estimate: the clock of LANES 4 DEPTH 0"), std::string::npos) << text;
  const std::string csv = sweep_csv(t);
  EXPECT_NE(csv.find(",pareto,clock_mhz,clock_source,clock_estimate\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",1\n"), std::string::npos) << csv;
  // A clock given: every row's, as given.
  s.clock = 75;
  s.clock_source = "given by --clock";
  const SweepRow given = SweepRunner(s).run(0);
  EXPECT_EQ(given.clock_mhz, 75);
  EXPECT_EQ(given.clock_source, "given by --clock");
  EXPECT_FALSE(given.clock_estimate);
}

// Every feasible row of a small sweep: contacts were checked, and the farthest lies within the predicted bound.
TEST(SweepRows, MeasuredContactErrorWithinTheBoundOnEveryRow) {
  SweepSpec s;
  s.scene = kScenes + "/small.json";
  s.lanes = {1};
  s.voxel_scales = {1, 2};
  s.distance_bits = {0, 4, 8};
  s.accuracies = {0.05};
  s.frames = 200;
  s.sample_frames = 6;
  s.clock = 100;
  s.clock_source = "--clock";
  check_sweep(s, "test");
  SweepRunner runner(s);
  uint64_t checked = 0;
  for (uint64_t i = 0; i < s.points(); ++i) {
    const SweepRow r = runner.run(i);
    ASSERT_TRUE(r.ok()) << r.point.text() << ": " << r.status;
    std::printf("%s: contact bound %.4g, measured %.4g over %llu contacts, %llu cycles\n", r.point.text().c_str(),
                r.contact_bound, r.contact_measured, (unsigned long long)r.contacts_checked,
                (unsigned long long)r.max_cycles);
    EXPECT_GT(r.contacts_checked + r.contacts_conservative, 0u) << r.point.text();
    EXPECT_LE(r.contact_measured, r.contact_bound) << r.point.text();
    // Next to conservative cells of a distance voxmap, the 2-bit bound.
    EXPECT_LE(r.contact_measured_conservative, r.contact_bound_conservative) << r.point.text();
    if (r.point.distance_bits == 0) {
      EXPECT_EQ(r.contacts_conservative, 0u);
    }
    EXPECT_GT(r.max_cycles, 0u);
    EXPECT_LE(r.mean_cycles, double(r.max_cycles));
    checked += r.contacts_checked + r.contacts_conservative;
  }
  EXPECT_GT(checked, 100u);
}

}  // namespace
}  // namespace voxcd
