// The sparse map's layout on a 2-bit device (docs/contract.md, "The table", "2-bit bricks"): a brick takes one unit
// of UW words, so a table word's rank counts its bricks, and a cell's brick starts at brick_base + UW * (the bricks
// before it).
#include <gtest/gtest.h>

#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {
namespace {

TEST(SparseLayout, TwoBitBricksTakeOneUnitEach) {
  for (int bl : {2, 3, 4}) {
    DeviceConfig cfg;
    cfg.BL = bl;
    EXPECT_EQ(code_units(cfg, kCodeBrick), 1u) << bl;
    EXPECT_EQ(unit_words(cfg), 2 * (uint64_t{1} << (3 * bl)) / 64) << bl;
    for (uint8_t c : {kEmpty, kSurface, kInterior}) EXPECT_EQ(code_units(cfg, c), 0u);
  }
  // 20 cells: bricks at 1, 2, 17 and 19; 16 cells a 64-bit word, the second word's rank is 2.
  DeviceConfig cfg;
  cfg.BL = 3;
  std::vector<uint8_t> codes(20, kEmpty);
  for (size_t t : {1, 2, 17, 19}) codes[t] = kCodeBrick;
  codes[5] = kInterior;
  const std::vector<uint64_t> table = table_image(cfg, codes);
  ASSERT_EQ(table.size(), 2u);
  EXPECT_EQ(table[0] >> 32, 0u);
  EXPECT_EQ(table[1] >> 32, 2u);
  EXPECT_EQ(table_units(cfg, codes), 4u);
  Job job;
  job.nx = 8 * 20;
  job.sparse = kSparseMap;
  job.brick_base = 100;
  job.brick_units = 4;
  const uint64_t firsts[4] = {100, 116, 132, 148};
  size_t k = 0;
  for (size_t t : {1, 2, 17, 19}) {
    Located l{};
    l.index[0] = int64_t(8 * t);
    l.inside = true;
    const Cell c = read_cell(cfg, table, job, table_ref(cfg, job, l));
    EXPECT_EQ(c.code, kCodeBrick) << t;
    EXPECT_EQ(c.first, firsts[k++]) << t;
  }
  // One unit fewer: the last brick's reference lies past the job's bricks and reads as code 0.
  job.brick_units = 3;
  Located l{};
  l.index[0] = 8 * 19;
  l.inside = true;
  EXPECT_EQ(read_cell(cfg, table, job, table_ref(cfg, job, l)).code, kEmpty);
}

}  // namespace
}  // namespace voxcd
