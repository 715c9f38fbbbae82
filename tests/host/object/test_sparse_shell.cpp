// The sparse shell: the same points as point_shell (every voxel centre of the shell grid's surface voxels), each with
// the same triangle's normal, as shell bricks whose device words ref's shell_points turns into exactly those points in
// the host's point order; chains with few origin words; normals within 1e-4 radian of their encoding.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "voxcd/host/object/detail/octahedral.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/sparse_shell.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "tests/defects.h"
#include "tests/error_text.h"
#include "tests/host/test_util.h"

#ifndef VOXCD_TEST_DATA
#error "VOXCD_TEST_DATA: the folder of the decompressed real models (env.obj, rob.obj) and the panda meshes"
#endif

namespace voxcd {
namespace {

// The sparse shell against the dense one: the same points, each normal the encoding of the dense normal.
void expect_same_shell(const SparseShell& sp, const PointShell& dense, const std::string& what) {
  ASSERT_EQ(sp.size(), dense.size()) << what;
  const PointShell back = sp.to_point_shell();
  EXPECT_EQ(back.cells, dense.cells) << what;
  EXPECT_EQ(back.points, dense.points) << what;
  const uint64_t nx = dense.grid.dims[0], ny = dense.grid.dims[1];
  auto lin = [&](const std::array<uint32_t, 3>& c) { return c[0] + nx * (c[1] + ny * uint64_t(c[2])); };
  std::vector<uint64_t> dense_lin(dense.size());
  for (size_t k = 0; k < dense.size(); ++k) dense_lin[k] = lin(dense.cells[k]);
  const auto cells = sp.cells();
  uint64_t wrong = 0;
  for (size_t k = 0; k < cells.size(); ++k) {
    const size_t i = size_t(std::lower_bound(dense_lin.begin(), dense_lin.end(), lin(cells[k])) - dense_lin.begin());
    wrong += sp.normals[k] != detail::encode_normal(dense.normals[i]);
  }
  EXPECT_EQ(wrong, 0u) << what << ": normals not the dense point's";
  uint64_t bricks_with_points = 0;
  for (uint64_t m : sp.masks) bricks_with_points += m != 0;
  EXPECT_EQ(bricks_with_points, sp.bricks.size()) << what;
}

// ref's shell_points of the device words are the points' centres, in point order, as the dense words give them.
void expect_device_points(const SparseShell& sp, const DeviceConfig& cfg, const std::string& what) {
  const std::vector<ShellWord> words = sp.device_words(cfg);
  ASSERT_EQ(words.size(), sp.words()) << what;
  Job job;
  job.sparse = kSparseShell;
  job.shell_count = uint32_t(words.size());
  const std::vector<ShellWord> pts = shell_points(cfg, words, job);
  PointShell cells;
  cells.grid = sp.grid;
  cells.cells = sp.cells();
  EXPECT_EQ(pts, cells.words(cfg)) << what;
  uint64_t origins = 0;
  for (const ShellWord& w : words) origins += is_origin_word(cfg, w);
  EXPECT_EQ(origins, sp.origin_words()) << what;
}

TEST(SparseShell, EveryShapeAsPointShellAtSeveralSizesAndShifts) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.01, 1.0);
  DeviceConfig cfg;
  cfg.BL = 3;
  for (const auto& name : shape_names())
    for (double s : {0.25, 0.07, 0.03}) {
      ShellOptions o;
      o.target_voxel = s;
      o.shift = Eigen::Vector3d(u(rng), u(rng), u(rng));
      const Mesh m = make_shape(name);
      const std::string what = name + " voxel " + std::to_string(s) + " seed " + std::to_string(seed);
      const SparseShell sp = sparse_point_shell(m, o);
      const PointShell dense = point_shell(m, o);
      expect_same_shell(sp, dense, what);
      expect_device_points(sp, cfg, what);
      const SparseShell again = SparseShell::from_point_shell(dense);
      EXPECT_EQ(again.bricks, sp.bricks) << what;
      EXPECT_EQ(again.masks, sp.masks) << what;
      EXPECT_EQ(again.normals, sp.normals) << what;
    }
}

TEST(SparseShell, DefectiveMeshesSheetsAndPointClouds) {
  const uint64_t seed = test::seed();
  for (const test::Defect& d : test::all_defects(3, seed)) {
    Mesh m = d.mesh;
    repair(m);
    ShellOptions o;
    o.target_voxel = voxel_for_resolution(m, 40);
    expect_same_shell(sparse_point_shell(m, o), point_shell(m, o), d.name);
  }
}

TEST(SparseShell, RealModels) {
  const std::string dir = VOXCD_TEST_DATA;
  DeviceConfig cfg;
  cfg.BL = 3;
  for (const std::string& f : {dir + "/env.obj", dir + "/rob.obj", dir + "/panda/link3.stl", dir + "/panda/hand.stl"}) {
    const Mesh m = load_mesh(f);
    ShellOptions o;
    o.target_voxel = voxel_for_resolution(m, 120);
    const SparseShell sp = sparse_point_shell(m, o);
    expect_same_shell(sp, point_shell(m, o), f);
    expect_device_points(sp, cfg, f);
  }
}

// The chains: on a closed curved surface almost every brick follows the one before it by a step.
TEST(SparseShell, FewOriginWords) {
  ShellOptions o;
  o.target_voxel = 0.01;
  for (const char* name : {"torus", "sphere", "stellated"}) {
    const SparseShell sp = sparse_point_shell(make_shape(name), o);
    ASSERT_GT(sp.bricks.size(), 1000u) << name;
    EXPECT_LT(double(sp.origin_words()), 0.02 * double(sp.bricks.size())) << name << ": " << sp.origin_words()
                                                                            << " origin words for " << sp.bricks.size()
                                                                            << " bricks";
    // More than 10 points a word: the words are the device's memory.
    EXPECT_GT(double(sp.size()) / double(sp.words()), 10.0) << name;
  }
}

TEST(SparseShell, NormalsKeepTheirDirection) {
  std::mt19937_64 rng(test::seed());
  std::normal_distribution<double> g;
  double worst = 0;
  for (int k = 0; k < 200000; ++k) {
    Eigen::Vector3d n(g(rng), g(rng), g(rng));
    if (k < 6) n = Eigen::Vector3d::Unit(k % 3) * (k < 3 ? 1 : -1);
    n.normalize();
    const Eigen::Vector3d d = detail::decode_normal(detail::encode_normal(n));
    worst = std::max(worst, std::acos(std::min(1.0, d.dot(n))));
    EXPECT_NEAR(d.norm(), 1.0, 1e-12);
  }
  EXPECT_LT(worst, 1e-4);
  std::printf("largest angle between a normal and its encoding: %.3g radian\n", worst);
}

TEST(SparseShell, ErrorsNameWhatIsWrong) {
  ShellOptions o;
  o.target_voxel = 0.1;
  o.on_surface = true;
  const Mesh m = make_shape("cube");
  EXPECT_NE(test::error_text<std::invalid_argument>([&] { sparse_point_shell(m, o); }).find("no sparse form"),
            std::string::npos);
  o.on_surface = false;
  const SparseShell sp = sparse_point_shell(m, o);
  DeviceConfig narrow;
  narrow.PW = 20;
  narrow.PF = 4;
  EXPECT_NE(test::error_text<std::invalid_argument>([&] { sp.device_words(narrow); }).find("3 PW >= 72"),
            std::string::npos);
  o.target_voxel = 0;
  EXPECT_THROW(sparse_point_shell(m, o), MeshError);
}

}  // namespace
}  // namespace voxcd
