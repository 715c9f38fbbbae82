// The sparse voxmap: conversions both ways keep every state, the canonical form (a brick exactly where a cell is not
// uniform), counts and bytes, and the device image read back through ref/'s sparse lookup (table, then brick) on
// devices of every BL and word width.
#include <gtest/gtest.h>

#include <random>

#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/sparse_voxmap.h"
#include "voxcd/ref/pipeline.h"
#include "tests/error_text.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

// Every voxel of `sm` against `vm`, the counts, and that every brick is canonical.
void expect_same(const SparseVoxmap& sm, const Voxmap& vm, const std::string& what) {
  ASSERT_EQ(sm.dims(), vm.dims()) << what;
  const auto& d = vm.dims();
  uint64_t wrong = 0;
  for (uint32_t z = 0; z < d[2]; ++z)
    for (uint32_t y = 0; y < d[1]; ++y)
      for (uint32_t x = 0; x < d[0]; ++x) wrong += sm.at(x, y, z) != vm.at(x, y, z);
  EXPECT_EQ(wrong, 0u) << what;
  EXPECT_EQ(sm.counts(), vm.counts()) << what;
  const auto cc = sm.code_counts();
  EXPECT_EQ(cc[0] + cc[1] + cc[2] + cc[3], sm.cells()) << what;
  EXPECT_EQ(cc[kCodeBrick], sm.bricks()) << what;
  for (uint64_t t = 0; t < sm.cells(); ++t)
    if (sm.code(t) == kCodeBrick) {
      const char* p = sm.brick_problem(t, sm.brick(sm.brick_index(t)));
      ASSERT_EQ(p, nullptr) << what << ": cell " << t << ": " << p;
    }
}

TEST(SparseVoxmap, DenseRoundTripEveryShapeAndBrickSize) {
  for (const auto& name : shape_names())
    for (double s : {0.25, 0.05})
      for (int bl : {2, 3, 4}) {
        VoxelizeOptions o;
        o.voxel = s;
        const Voxmap vm = voxelize(make_shape(name), o);
        const SparseVoxmap sm = SparseVoxmap::from_dense(vm, bl);
        const std::string what = name + " voxel " + std::to_string(s) + " BL " + std::to_string(bl);
        expect_same(sm, vm, what);
        EXPECT_EQ(sm.to_dense().words(), vm.words()) << what;
        EXPECT_EQ(SparseVoxmap::from_dense(sm.to_dense(), bl), sm) << what;
      }
}

// A small map whose cells are known: uniform interior, uniform surface, a brick, a far-face cell.
TEST(SparseVoxmap, CodesOfKnownCells) {
  GridPlacement g;
  g.dims = {12, 8, 8};  // 2 x 1 x 1 cells of 8^3; the second holds voxels x = 8..11 only
  Voxmap vm(g);
  for (uint32_t z = 0; z < 8; ++z)
    for (uint32_t y = 0; y < 8; ++y)
      for (uint32_t x = 0; x < 8; ++x) vm.set(vm.index(x, y, z), kInterior);
  SparseVoxmap sm = SparseVoxmap::from_dense(vm, 3);
  EXPECT_EQ(sm.code(0), kInterior);
  EXPECT_EQ(sm.code(1), kEmpty);
  EXPECT_EQ(sm.bricks(), 0u);
  // The far-face cell all surface within the grid: a brick (its voxels beyond the grid are empty).
  for (uint32_t z = 0; z < 8; ++z)
    for (uint32_t y = 0; y < 8; ++y)
      for (uint32_t x = 8; x < 12; ++x) vm.set(vm.index(x, y, z), kSurface);
  sm = SparseVoxmap::from_dense(vm, 3);
  EXPECT_EQ(sm.code(1), kCodeBrick);
  EXPECT_EQ(sm.bricks(), 1u);
  EXPECT_EQ(sm.at(11, 7, 7), kSurface);
  // One voxel of the first cell changed: a brick; every voxel surface: uniform surface.
  vm.set(vm.index(3, 4, 5), kSurface);
  sm = SparseVoxmap::from_dense(vm, 3);
  EXPECT_EQ(sm.code(0), kCodeBrick);
  EXPECT_EQ(sm.brick_index(1), 1u);
  EXPECT_EQ(sm.at(3, 4, 5), kSurface);
  EXPECT_EQ(sm.at(3, 4, 6), kInterior);
  for (uint32_t z = 0; z < 8; ++z)
    for (uint32_t y = 0; y < 8; ++y)
      for (uint32_t x = 0; x < 8; ++x) vm.set(vm.index(x, y, z), kSurface);
  sm = SparseVoxmap::from_dense(vm, 3);
  EXPECT_EQ(sm.code(0), kSurface);
  EXPECT_EQ(sm.bricks(), 1u);
  expect_same(sm, vm, "known cells");
  // Bytes with MEMW 64: one table word (16 codes), one brick of 512 2-bit states.
  EXPECT_EQ(sm.table_bytes(), 8u);
  EXPECT_EQ(sm.brick_bytes(), 128u);
  // A brick that is not canonical, and a state beyond the grid.
  std::vector<uint64_t> w(sm.brick_words(), 0x5555555555555555ull);
  EXPECT_NE(sm.brick_problem(0, w.data()), nullptr);
  w.assign(sm.brick_words(), 0);
  w[0] = 1;
  EXPECT_EQ(sm.brick_problem(0, w.data()), nullptr);
  w[15] = uint64_t{1} << 62;  // voxel (7, 7, 7) of cell 1 lies beyond x = 11
  EXPECT_NE(std::string(sm.brick_problem(1, w.data())).find("beyond the grid"), std::string::npos);
}

// ref/'s lookup of a sparse map (table_ref, read_cell, sparse_state) gives the dense state of every voxel.
void expect_device_reads(const SparseVoxmap& sm, const Voxmap& vm, const DeviceConfig& cfg) {
  const SparseVoxmap::DeviceImage im = sm.device_image(cfg);
  std::vector<uint64_t> mem = im.table;
  Job job;
  job.nx = vm.dims()[0];
  job.ny = vm.dims()[1];
  job.nz = vm.dims()[2];
  job.sparse = kSparseMap;
  job.brick_base = uint32_t(mem.size());
  job.brick_units = uint32_t(im.brick_units);
  mem.insert(mem.end(), im.bricks.begin(), im.bricks.end());
  ASSERT_EQ(im.table.size(), table_words(cfg, job));
  ASSERT_EQ(im.bricks.size(), brick_words(cfg, job));
  uint64_t wrong = 0;
  for (uint32_t z = 0; z < job.nz; ++z)
    for (uint32_t y = 0; y < job.ny; ++y)
      for (uint32_t x = 0; x < job.nx; ++x) {
        Located l{};
        l.index[0] = x;
        l.index[1] = y;
        l.index[2] = z;
        l.inside = true;
        const Cell c = read_cell(cfg, mem, job, table_ref(cfg, job, l));
        wrong += sparse_state(cfg, mem, c, l) != vm.at(x, y, z);
      }
  EXPECT_EQ(wrong, 0u) << cfg.to_string();
}

TEST(SparseVoxmap, DeviceImageReadsBackThroughRef) {
  // MEMW 16 keeps 8-bit ranks: the coarse torus has fewer bricks than that.
  for (int memw : {16, 32, 64}) {
    VoxelizeOptions o;
    o.voxel = memw == 16 ? 0.25 : 0.08;
    const Voxmap vm = voxelize(make_shape("torus"), o);
    for (int bl : {2, 3, 4}) {
      DeviceConfig cfg;
      cfg.BL = bl;
      cfg.MEMW = memw;
      if (2 * (uint64_t{1} << (3 * bl)) < uint64_t(memw)) continue;
      expect_device_reads(SparseVoxmap::from_dense(vm, bl), vm, cfg);
    }
  }
  // A rank the device's table word cannot hold is ref's error, not a wrapped rank.
  VoxelizeOptions o;
  o.voxel = 0.03;
  DeviceConfig cfg;
  cfg.BL = 2;
  cfg.MEMW = 16;
  const SparseVoxmap sm = SparseVoxmap::from_dense(voxelize(make_shape("torus"), o), 2);
  EXPECT_NE(test::error_text<std::invalid_argument>([&] { sm.device_image(cfg); }).find("does not fit MEMW/2 = 8 bits"),
            std::string::npos);
}

TEST(SparseVoxmap, ErrorsNameWhatIsWrong) {
  GridPlacement g;
  g.dims = {9, 9, 9};
  for (int bl : {1, 5})
    EXPECT_NE(test::error_text<std::invalid_argument>([&] { SparseVoxmap s(g, bl); }).find("BL = " + std::to_string(bl)),
              std::string::npos);
  const SparseVoxmap sm(g, 3);
  EXPECT_NE(test::error_text<std::invalid_argument>([&] { sm.device_image(DeviceConfig{}); })
                .find("not a 2-bit sparse device of BL 3"),
            std::string::npos);
  DeviceConfig other;
  other.BL = 2;
  EXPECT_NE(test::error_text<std::invalid_argument>([&] { sm.device_image(other); }).find("BL 3"), std::string::npos);
  SparseVoxmap full(g, 3);
  for (uint64_t t = 0; t < full.cells(); ++t) full.append(kEmpty);
  EXPECT_NE(test::error_text<std::logic_error>([&] { full.append(kEmpty); }).find("more cells"), std::string::npos);
}

}  // namespace
}  // namespace voxcd
