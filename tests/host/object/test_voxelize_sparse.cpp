// The sparse voxeliser gives voxelize()'s states voxel for voxel (and its report) on every built-in shape, the
// defective meshes of tests/defects.h (holes, flipped patches, sheets, point clouds, non-manifold parts), real models
// (FCL's room and robot, the panda arm's links, Debian's assimp test models) at several resolutions, grid shifts and
// brick sizes, whatever the thread count.
#include <gtest/gtest.h>

#include <random>

#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize_sparse.h"
#include "tests/defects.h"
#include "tests/host/test_util.h"

#ifndef VOXCD_TEST_DATA
#error "VOXCD_TEST_DATA: the folder of the decompressed real models (env.obj, rob.obj) and the panda meshes"
#endif

namespace voxcd {
namespace {

// The dense voxmap's voxels that the sparse one gives another state (the count, for the failure's message).
uint64_t differing(const SparseVoxmap& sm, const Voxmap& vm) {
  uint64_t n = 0;
  for (uint32_t z = 0; z < vm.dims()[2]; ++z)
    for (uint32_t y = 0; y < vm.dims()[1]; ++y)
      for (uint32_t x = 0; x < vm.dims()[0]; ++x) n += sm.at(x, y, z) != vm.at(x, y, z);
  return n;
}

VoxelizeReport expect_equal(const Mesh& m, const VoxelizeOptions& o, int bl, const std::string& what) {
  VoxelizeReport rd, rs;
  const Voxmap vm = voxelize(m, o, &rd);
  const SparseVoxmap sm = voxelize_sparse(m, o, &rs, bl);
  const SparseVoxmap want = SparseVoxmap::from_dense(vm, bl);
  EXPECT_TRUE(sm == want) << what << ": " << differing(sm, vm) << " voxels differ of " << vm.size();
  EXPECT_EQ(rs.evaluated, rd.evaluated) << what;
  EXPECT_EQ(rs.uncertain, rd.uncertain) << what;
  return rs;
}

std::string shift_text(const Eigen::Vector3d& s) {
  return "shift (" + std::to_string(s.x()) + ", " + std::to_string(s.y()) + ", " + std::to_string(s.z()) + ")";
}

TEST(VoxelizeSparse, EveryShapeAtSeveralSizesShiftsAndBricks) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.01, 1.0);
  for (const auto& name : shape_names()) {
    const Mesh m = make_shape(name);
    for (double s : {0.25, 0.07, 0.021})
      for (int bl : {2, 3, 4}) {
        VoxelizeOptions o;
        o.voxel = s;
        o.shift = Eigen::Vector3d(u(rng), u(rng), u(rng));
        expect_equal(m, o, bl, name + " voxel " + std::to_string(s) + " BL " + std::to_string(bl) + " " +
                                   shift_text(o.shift) + " seed " + std::to_string(seed));
      }
  }
}

TEST(VoxelizeSparse, NeverDependsOnTheThreadCount) {
  VoxelizeOptions o;
  o.voxel = 0.015;
  const Mesh m = make_shape("stellated");
  o.threads = 1;
  const SparseVoxmap one = voxelize_sparse(m, o);
  o.threads = 3;
  EXPECT_TRUE(voxelize_sparse(m, o) == one);
}

// Holes (one large: the near-hole refinement across layers), flips, duplicates, cracks, non-manifold unions, hollow
// spheres, sheets, a terrain and a point cloud, repaired as voxcd repairs them.
TEST(VoxelizeSparse, EveryDefectiveMesh) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.01, 1.0);
  for (const test::Defect& d : test::all_defects(4, seed)) {
    Mesh m = d.mesh;
    repair(m);
    for (uint32_t res : {24u, 61u}) {
      VoxelizeOptions o;
      o.resolution = res;
      o.shift = Eigen::Vector3d(u(rng), u(rng), u(rng));
      expect_equal(m, o, 3, d.name + " at " + std::to_string(res) + " " + shift_text(o.shift));
    }
  }
}

// A hole deep enough that the refinement reaches voxels many layers from the rim.
TEST(VoxelizeSparse, OneLargeHoleAtHigherResolution) {
  const test::Defect d = test::punched(test::icosphere(5), 600, test::seed(), true);
  Mesh m = d.mesh;
  repair(m);
  VoxelizeOptions o;
  o.resolution = 150;
  EXPECT_GT(expect_equal(m, o, 3, d.name).evaluated, 1000u) << "the refinement near the hole was not exercised";
}

// Real models: FCL's room (large thin walls across many layers) and robot, the panda arm's links, and Debian's assimp
// test models of the differential corpus (an open sphere among them).
TEST(VoxelizeSparse, RealModels) {
  const std::string dir = VOXCD_TEST_DATA;
  std::vector<std::string> files = {dir + "/env.obj", dir + "/rob.obj"};
  for (const char* l : {"link0", "link1", "link3", "link5", "hand", "finger"})
    files.push_back(dir + "/panda/" + l + ".stl");
  for (const char* a : {"STL/Spider_binary.stl", "STL/Wuson.stl", "STL/sphereWithHole.stl", "OBJ/spider.obj"})
    files.push_back(std::string("/usr/share/assimp/models/") + a);
  std::mt19937_64 rng(test::seed());
  std::uniform_real_distribution<double> u(0.01, 1.0);
  for (const auto& f : files) {
    const Mesh m = load_mesh(f);  // repaired as voxcd voxelize repairs it
    for (uint32_t res : {40u, 173u}) {
      VoxelizeOptions o;
      o.resolution = res;
      o.shift = Eigen::Vector3d(u(rng), u(rng), u(rng));
      expect_equal(m, o, 3, f + " at " + std::to_string(res) + " " + shift_text(o.shift));
    }
  }
}

TEST(VoxelizeSparse, ErrorsAsVoxelize) {
  const Mesh m = make_shape("cube");
  VoxelizeOptions o;
  o.voxel = 0.001;  // 2000 voxels across, more than max_dim
  std::string dense, sparse;
  try {
    voxelize(m, o);
  } catch (const MeshError& e) {
    dense = e.what();
  }
  try {
    voxelize_sparse(m, o);
  } catch (const MeshError& e) {
    sparse = e.what();
  }
  EXPECT_NE(dense, "");
  EXPECT_EQ(sparse, dense);
  o.voxel = 0.1;
  EXPECT_THROW(voxelize_sparse(m, o, nullptr, 5), std::invalid_argument);
}

}  // namespace
}  // namespace voxcd
