// The directed cases against their hand-derived expectations, and the pipeline stages one by one.
#include <gtest/gtest.h>

#include "voxcd/ref/pipeline.h"
#include "tests/ref/directed_cases.h"

namespace voxcd {
namespace {

class Directed : public ::testing::TestWithParam<size_t> {};

TEST_P(Directed, RefMatchesHandDerivedStream) {
  const testing::DirectedCase& c = testing::directed_cases()[GetParam()];
  const std::vector<Record> got = run_stream(c.config, c.memory, c.jobs);
  ASSERT_EQ(got.size(), c.expected.size()) << c.name;
  for (size_t i = 0; i < got.size(); ++i)
    EXPECT_TRUE(got[i].same_as(c.expected[i], false))
        << c.name << " record " << i << ": expected '" << c.expected[i].to_string() << "', got '"
        << got[i].to_string() << "'";
}

INSTANTIATE_TEST_SUITE_P(Cases, Directed, ::testing::Range<size_t>(0, testing::directed_cases().size()),
                         [](const ::testing::TestParamInfo<size_t>& i) {
                           return "case" + testing::directed_cases()[i.param].name;
                         });

TEST(Stages, FullRangeAccumulatorDoesNotOverflow) {
  DeviceConfig cfg;
  Job j;
  for (auto& row : j.M)
    for (auto& e : row) e = -(int64_t{1} << 17);
  for (auto& e : j.t) e = (int64_t{1} << 47) - 1;
  const int64_t pmin = -(int64_t{1} << 23);
  const Transformed t = transform(cfg, j, ShellWord{pmin, pmin, pmin});
  // 3 * 2^40 + 2^47 - 1 = 131 * 2^40 - 1: index floor(/2^24) = 131 * 2^16 - 1.
  const Acc expect = Acc(131) * (Acc(1) << 40) - 1;
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(t.acc[i] == expect);
  j.nx = j.ny = j.nz = 1024;
  const Located l = locate(cfg, j, t);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(l.index[i], 131 * 65536 - 1);
  EXPECT_FALSE(l.inside);
}

TEST(Stages, FloorNotTruncation) {
  DeviceConfig cfg;
  Job j;
  j.nx = j.ny = j.nz = 4;
  Transformed t;
  t.acc[0] = -1;                        // -2^-24 voxel
  t.acc[1] = -(Acc(1) << 24);           // exactly -1
  t.acc[2] = -(Acc(1) << 24) - 1;       // just below -1
  const Located l = locate(cfg, j, t);
  EXPECT_EQ(l.index[0], -1);
  EXPECT_EQ(l.index[1], -1);
  EXPECT_EQ(l.index[2], -2);
  EXPECT_FALSE(l.inside);
}

TEST(Stages, LinearAddressWordAndSlot) {
  DeviceConfig cfg;
  cfg.MEMW = 16;  // 8 states per word
  Job j;
  j.nx = 37;
  j.ny = 5;
  j.nz = 3;
  j.map_base = 100;
  Transformed t;
  const int64_t xyz[3] = {36, 4, 2};
  for (int i = 0; i < 3; ++i) t.acc[i] = Acc(xyz[i]) << 24;
  const Located l = locate(cfg, j, t);
  ASSERT_TRUE(l.inside);
  EXPECT_EQ(l.linear, 554u);
  EXPECT_EQ(l.word, 100u + 554 / 8);
  EXPECT_EQ(l.slot, 554u % 8);
  std::vector<uint64_t> map(200, 0);
  map[l.word] = uint64_t(3) << (2 * l.slot);
  EXPECT_EQ(fetch_state(cfg, map, l), 3);
  map[l.word] = ~(uint64_t(3) << (2 * l.slot)) & 0xFFFF;
  EXPECT_EQ(fetch_state(cfg, map, l), 0);
}

TEST(Stages, HitTestUsesTheMaskBitOfTheState) {
  for (unsigned mask = 0; mask < 16; ++mask)
    for (uint8_t s = 0; s < 4; ++s) {
      EXPECT_EQ(hit_test(uint8_t(mask), true, s), bool(mask & (1u << s)));
      EXPECT_FALSE(hit_test(uint8_t(mask), false, s));
    }
}

TEST(Validate, JobErrorsNameTheTagAndField) {
  DeviceConfig cfg;
  auto expect_error = [&](Job j, uint64_t shell, uint64_t map, const char* needle) {
    try {
      validate_job(cfg, j, shell, map);
      ADD_FAILURE() << "accepted job for " << needle;
    } catch (const JobError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("job tag 5"), std::string::npos) << e.what();
    }
  };
  Job j;
  j.tag = 5;
  j.shell_count = 10;
  j.nx = j.ny = j.nz = 4;
  EXPECT_NO_THROW(validate_job(cfg, j, 10, 2));
  expect_error(j, 9, 2, "go past the 9 loaded shell words");
  expect_error(j, 10, 1, "go past the 1 loaded voxmap words");
  Job k = j;
  k.nx = 0;
  expect_error(k, 10, 2, "nx = 0 is outside");
  k = j;
  k.nz = 1025;
  expect_error(k, 10, 2000, "nz = 1025 is outside 1..2^DW = 1024");
  k = j;
  k.M[1][2] = int64_t{1} << 17;
  expect_error(k, 10, 2, "M12 = 131072 does not fit MW = 18");
  k = j;
  k.t[2] = int64_t{1} << 47;
  expect_error(k, 10, 2, "T2 = ");
  k = j;
  k.hit_mask = 16;
  expect_error(k, 10, 2, "hit mask 16");
  k = j;
  k.tag = 70000;
  try {
    validate_job(cfg, k, 10, 2);
    ADD_FAILURE();
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("TAGW"), std::string::npos);
  }
}

TEST(Validate, MemoryThatDoesNotFitTheDevice) {
  DeviceConfig cfg;
  cfg.SAW = 4;
  DeviceMemory m;
  m.shell.resize(17);
  EXPECT_THROW(validate_memory(cfg, m), JobError);
  m.shell.resize(16);
  m.shell[3].y = int64_t{1} << 23;
  try {
    validate_memory(cfg, m);
    ADD_FAILURE();
  } catch (const JobError& e) {
    EXPECT_NE(std::string(e.what()).find("shell word 3 coordinate 1"), std::string::npos) << e.what();
  }
  m.shell[3].y = 0;
  cfg.MEMW = 32;
  m.map = {uint64_t{1} << 32};
  EXPECT_THROW(validate_memory(cfg, m), JobError);
}

}  // namespace
}  // namespace voxcd
