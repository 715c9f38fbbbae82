// The vector file format: a round trip, every kind of malformed file (an error with file and line, never a
// crash), and random mutations of a valid file.
#include <gtest/gtest.h>

#include <random>
#include <sstream>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/vectors.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

const char* kGood =
    "voxcd-vectors 1\n"
    "# a comment line\n"
    "config PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4\n"
    "shell 3\n"
    "128 128 128   # (0.5, 0.5, 0.5)\n"
    "-64 0 0\n"
    "384 128 128\n"
    "map 1\n"
    "0000000000000004\n"
    "job 9 ALL 6 0 3 0 2 1 1 65536 0 0 0 65536 0 0 0 65536 0 0 0\n"
    "hit 9 2 1 0 0 1\n"
    "done 9 1\n";

VectorFile parse(const std::string& s) { return parse_vectors(s, "t.vec"); }

TEST(Vectors, ParsesAndRunsTheDocumentedExample) {
  const VectorFile f = parse(kGood);
  ASSERT_EQ(f.memory.shell.size(), 3u);
  EXPECT_EQ(f.memory.shell[1].x, -64);
  ASSERT_EQ(f.memory.map.size(), 1u);
  EXPECT_EQ(f.memory.map[0], 4u);
  ASSERT_EQ(f.jobs.size(), 1u);
  EXPECT_EQ(f.job_lines[0], 10);
  EXPECT_TRUE(f.has_lanes);
  const auto got = run_stream(f.config, f.memory, f.jobs);
  EXPECT_EQ(compare_streams(f, got, false), "");
}

TEST(Vectors, RoundTripOfGeneratedVectors) {
  GenerateOptions g;
  g.seed = 11;
  g.jobs = 120;
  const GeneratedVectors v = generate_vectors(g);
  const auto recs = run_stream(v.config, v.memory, v.jobs);
  std::ostringstream os;
  write_vectors(os, v.config, true, v.memory, v.jobs, recs);
  const VectorFile f = parse(os.str());
  EXPECT_TRUE(f.config == v.config);
  ASSERT_EQ(f.memory.shell.size(), v.memory.shell.size());
  for (size_t k = 0; k < f.memory.shell.size(); ++k) EXPECT_TRUE(f.memory.shell[k] == v.memory.shell[k]);
  EXPECT_EQ(f.memory.map, v.memory.map);
  ASSERT_EQ(f.jobs.size(), v.jobs.size());
  for (size_t k = 0; k < f.jobs.size(); ++k) EXPECT_EQ(job_line(f.jobs[k]), job_line(v.jobs[k]));
  EXPECT_EQ(compare_streams(f, recs, true), "");
}

TEST(Vectors, GeneratedVectorsFitASmallShellMemory) {
  // A derived configuration's small shell memory (SAW 10: 1024 words, less than the directed blocks in full): the
  // directed blocks shrink beside the cloud and every job still runs; a cloud larger than the memory is an error.
  GenerateOptions g;
  g.seed = 3;
  g.jobs = 100;
  g.cloud_points = 256;
  g.config = parse_config_pairs("PW 7 PF 1 MW 12 MF 11 TW 21 DW 4 MEMW 64 LANES 1 SAW 10 MAW 6 TAGW 16", "test");
  const GeneratedVectors v = generate_vectors(g);
  EXPECT_LE(v.memory.shell.size(), g.config.shell_depth());
  EXPECT_GT(v.memory.shell.size(), g.cloud_points + 4);
  EXPECT_EQ(v.jobs.size(), g.jobs);
  EXPECT_FALSE(run_stream(v.config, v.memory, v.jobs).empty());
  g.cloud_points = 5000;
  EXPECT_THROW(generate_vectors(g), std::invalid_argument);
  // The default configuration's vectors are those of before (the blocks in full): the same shell size.
  GenerateOptions d;
  EXPECT_EQ(generate_vectors(d).memory.shell.size(), d.cloud_points + 400 + 64 + 800);
}

TEST(Vectors, ComparisonNamesJobPointExpectedAndGot) {
  const VectorFile f = parse(kGood);
  std::vector<Record> got = run_stream(f.config, f.memory, f.jobs);
  got[0].z = 3;
  const std::string d = compare_streams(f, got, false);
  EXPECT_NE(d.find("job tag 9 (job 0, line 10)"), std::string::npos) << d;
  EXPECT_NE(d.find("point 2: expected 'hit 9 2 1 0 0 1', got 'hit 9 2 1 0 3 1'"), std::string::npos) << d;
  got.pop_back();
  got[0].z = 0;
  EXPECT_NE(compare_streams(f, got, false).find("got 'end of stream'"), std::string::npos);
  got = run_stream(f.config, f.memory, f.jobs);
  got.push_back(Record::done(9, 0));
  EXPECT_NE(compare_streams(f, got, false).find("expected 'end of stream'"), std::string::npos);
  // Cycles are compared only when asked.
  VectorFile fc = parse(std::string(kGood).replace(std::string(kGood).find("done 9 1"), 8, "done 9 1 17"));
  got = run_stream(f.config, f.memory, f.jobs);
  got.back().cycles = 18;
  EXPECT_EQ(compare_streams(fc, got, false), "");
  EXPECT_NE(compare_streams(fc, got, true).find("cycles differ"), std::string::npos);
  got.back().cycles = 17;
  EXPECT_EQ(compare_streams(fc, got, true), "");
}

struct Bad {
  const char* name;
  std::string text;
  int line;
  const char* needle;
};

std::string good_with(const std::string& from, const std::string& to) {
  std::string s = kGood;
  const size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

TEST(Vectors, MalformedFilesGiveFileLineAndReason) {
  const std::string g = kGood;
  const std::vector<Bad> bad = {
      {"empty", "", 0, "empty file"},
      {"no header", "config PW 24\n", 1, "must start with 'voxcd-vectors 1'"},
      {"version", "voxcd-vectors 4\n", 1, "unsupported vector format version '4' (this reads 1, 2 and 3)"},
      {"truncated shell", g.substr(0, g.find("-64 0 0")), 5, "truncated: the shell section at line 4 declares 3"},
      {"truncated map", g.substr(0, g.find("0000000000000004")), 8, "truncated: the map section at line 8"},
      {"shell count larger than its lines", good_with("shell 3", "shell 4"), 8,
       "shell word 3 needs 3 fields 'x y z', found 2"},
      {"map count larger than its lines", good_with("map 1", "map 2"), 10, "map word 1 needs one hex field"},
      {"shell value too wide", good_with("-64 0 0", "-64 8388608 0"), 6, "shell y 8388608 does not fit PW = 24"},
      {"shell not a number", good_with("-64 0 0", "-64 0x1 0"), 6, "shell y '0x1' is not a decimal integer"},
      {"map word too wide", good_with("0000000000000004", "10000000000000004"), 9, "wider than MEMW = 64"},
      {"map word not hex", good_with("0000000000000004", "000000000000000g"), 9, "is not a hex number"},
      {"matrix too wide", good_with("65536 0 0 0 65536", "131072 0 0 0 65536"), 10, "M00 131072 does not fit MW = 18"},
      {"translation too wide", good_with("65536 0 0 0\n", "65536 140737488355328 0 0\n"), 10, "T0 140737488355328 does not fit TW = 48"},
      {"job field count", good_with("65536 0 0 0\nhit", "65536 0 0\nhit"), 10, "'job' takes 21 fields, found 20"},
      {"unknown mode", good_with("job 9 ALL", "job 9 SOME"), 10, "MODE 'SOME' is not ALL, FIRST or COUNT"},
      {"mask too wide", good_with("job 9 ALL 6", "job 9 ALL 16"), 10, "MASK 16 is outside 0..15"},
      {"tag too wide", good_with("job 9 ALL", "job 65536 ALL"), 10, "TAG 65536 does not fit 16 bits"},
      {"job past loaded shell", good_with("job 9 ALL 6 0 3", "job 9 ALL 6 1 3"), 10, "go past the 3 loaded shell words"},
      {"job past loaded map", good_with("0 3 0 2 1 1", "0 3 0 40 1 1"), 10, "go past the 1 loaded voxmap words"},
      {"dimension zero", good_with("0 3 0 2 1 1", "0 3 0 2 0 1"), 10, "ny = 0 is outside"},
      {"unknown record", good_with("done 9 1", "finish 9 1"), 12, "unknown record 'finish'"},
      {"hit field count", good_with("hit 9 2 1 0 0 1", "hit 9 2 1 0 0"), 11, "'hit' takes 6 fields, found 5"},
      {"hit state too wide", good_with("hit 9 2 1 0 0 1", "hit 9 2 1 0 0 4"), 11, "STATE 4 does not fit 2 bits"},
      {"done too many fields", good_with("done 9 1", "done 9 1 2 3"), 12, "'done' takes TAG HITS [CYCLES]"},
      {"negative cycles", good_with("done 9 1", "done 9 1 -5"), 12, "CYCLES '-5' is not an unsigned"},
      {"unknown config key", good_with("LANES 4", "LANES 4 FOO 3"), 3, "unknown config parameter 'FOO'"},
      {"config twice", good_with("shell 3", "config PW 24\nshell 3"), 4, "a second config line"},
      {"bad config value", good_with("MEMW 64", "MEMW 48"), 3, "MEMW = 48 is not a power of two"},
      {"duplicate config key", good_with("LANES 4", "LANES 4 PW 20"), 3, "config parameter PW given twice"},
      {"second shell section", good_with("map 1", "shell 0\nmap 1"), 8, "a second shell section"},
      {"shell deeper than memory", good_with("shell 3", "shell 65537"), 4, "exceeds the memory depth 2^SAW = 65536"},
      {"count not a number", good_with("shell 3", "shell three"), 4, "shell count 'three' is not an unsigned"},
  };
  for (const Bad& b : bad) {
    try {
      parse(b.text);
      ADD_FAILURE() << b.name << ": accepted";
    } catch (const VectorError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("t.vec:" + std::to_string(b.line) + ": ", 0), 0u) << b.name << ": " << m;
      EXPECT_NE(m.find(b.needle), std::string::npos) << b.name << ": " << m;
    }
  }
}

TEST(Vectors, MissingFileIsAnError) {
  EXPECT_THROW(read_vectors("/nonexistent/voxcd.vec"), VectorError);
}

TEST(Vectors, RandomMutationsNeverCrash) {
  // Truncations, deleted and duplicated lines and flipped characters: each parses or throws VectorError.
  GenerateOptions g;
  g.seed = 5;
  g.jobs = 30;
  g.cloud_points = 50;
  const GeneratedVectors v = generate_vectors(g);
  std::ostringstream os;
  write_vectors(os, v.config, true, v.memory, v.jobs, run_stream(v.config, v.memory, v.jobs));
  const std::string text = os.str();
  std::mt19937_64 rng(test::seed(99));
  size_t errors = 0, parsed = 0;
  for (int k = 0; k < 3000; ++k) {
    std::string s = text;
    switch (k % 4) {
      case 0: s.resize(rng() % s.size()); break;
      case 1: s[rng() % s.size()] = "0123456789 -\nabcxyz#"[rng() % 20]; break;
      case 2: {
        const size_t a = rng() % s.size(), b = s.find('\n', a);
        if (b != std::string::npos) s.erase(a, b - a + 1);
        break;
      }
      default: {
        const size_t a = s.rfind('\n', rng() % s.size());
        const size_t b = s.find('\n', a + 1);
        if (a != std::string::npos && b != std::string::npos) s.insert(b, s.substr(a, b - a));
        break;
      }
    }
    try {
      const VectorFile f = parse(s);
      run_stream(f.config, f.memory, f.jobs);  // a file that parses is runnable
      ++parsed;
    } catch (const VectorError& e) {
      ++errors;
      EXPECT_EQ(std::string(e.what()).rfind("t.vec:", 0), 0u);
    }
  }
  EXPECT_GT(errors, 500u);
  EXPECT_GT(parsed, 50u);
}

}  // namespace
}  // namespace voxcd
