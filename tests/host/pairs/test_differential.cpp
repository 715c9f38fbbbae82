// The differential check against exact geometry (tests/differential.h) on a sample of the corpus that
// bench/bench_differential.cpp runs in full: no collision missed deeper than the documented depth and no contact at
// a pose farther apart than the documented separation, in 2-bit and distance mode (both directions, margin 0); and
// the non-manifold solids of the corpus voxelise with the interior of their union in both modes.
#include <gtest/gtest.h>

#include "tests/differential.h"
#include "tests/host/test_util.h"
#include "voxcd/host/object/distance_field.h"

namespace voxcd {
namespace {

using test::diff::Model;

std::vector<Model> sample_corpus() {
  using namespace test;
  std::vector<Model> v = {diff::robot(), diff::from_defect(face_sharing_boxes()), diff::from_defect(wedge_union()),
                          diff::from_defect(box_with_internal_face()), diff::from_defect(pinwheel()),
                          diff::thin_plate(0.012), diff::open_tube(), diff::open_square()};
  for (Model& m : diff::real_models({"STL/Spider_binary.stl"})) v.push_back(std::move(m));
  for (Model& m : v) m = diff::normalized(std::move(m));
  return v;
}

void run_pairs(const std::vector<std::pair<Model, Model>>& pairs, uint32_t resolution, size_t poses) {
  test::diff::Tally t[2];
  for (size_t p = 0; p < pairs.size(); ++p) {
    test::diff::PairCheck check(pairs[p].first, pairs[p].second, resolution);
    const uint64_t seed = test::seed() + 977 * p;
    for (const RigidPose& pose : check.poses(poses, seed)) {
      const test::diff::Outcome o = check.check(pose);
      char where[512];
      std::snprintf(where, sizeof where, "%s against %s, B at (%.9g, %.9g, %.9g) q (%.9g, %.9g, %.9g, %.9g) (seed %llu)",
                    pairs[p].first.name.c_str(), pairs[p].second.name.c_str(), pose.translation.x(),
                    pose.translation.y(), pose.translation.z(), pose.rotation.w(), pose.rotation.x(),
                    pose.rotation.y(), pose.rotation.z(), (unsigned long long)seed);
      for (int k = 0; k < 2; ++k) {
        test::diff::tally(t[k], k, o, where);
        const double limit = k == 0 ? test::diff::kMissDepth2Bit : test::diff::kMissDepthDistance;
        if (o.truth && !o.voxcd[k]) {
          EXPECT_LE(o.depth, limit) << (k ? "distance" : "2-bit") << " mode missed a collision " << o.depth
                                    << " voxels deep: " << where;
        }
        if (!o.truth && o.voxcd[k]) {
          EXPECT_LE(o.separation, test::diff::kFalseSeparation)
              << (k ? "distance" : "2-bit") << " mode reported a contact " << o.separation << " voxels apart: " << where;
        }
      }
    }
  }
  for (int k = 0; k < 2; ++k)
    std::printf("%s: collisions found %llu, missed %llu (deepest %.3f voxels), separated %llu, false contacts %llu "
                "(farthest %.3f voxels)\n",
                k ? "distance" : "2-bit", (unsigned long long)t[k].tp, (unsigned long long)t[k].fn,
                t[k].worst_missed_depth, (unsigned long long)t[k].tn, (unsigned long long)t[k].fp,
                t[k].worst_false_separation);
  // The poses must exercise both sides of the question.
  EXPECT_GT(t[0].tp, 0u);
  EXPECT_GT(t[0].tn + t[0].fp, 0u);
}

// Each model of the sample against the next, and the robot in the room.
TEST(Differential, SampleAgainstFcl) {
  const std::vector<Model> corpus = sample_corpus();
  std::vector<std::pair<Model, Model>> pairs;
  for (size_t i = 0; i < corpus.size(); ++i) pairs.emplace_back(corpus[i], corpus[(i + 1) % corpus.size()]);
  run_pairs(pairs, 24, 24);
}

TEST(Differential, RobotInTheRoom) {
  run_pairs({{test::diff::room(), test::diff::robot()}}, 64, 40);
}

// Closed solids glued along faces and edges, and a closed mesh with an internal face: the interior of their union in
// the voxmap (the volume between the interior and interior + surface counts) and a field negative wherever a node
// lies inside by more than a voxel.
TEST(Differential, NonManifoldSolidsHaveTheirInterior) {
  for (const test::Defect& d :
       {test::face_sharing_boxes(), test::box_with_internal_face(), test::wedge_union(), test::pinwheel(), test::box_with_fin(),
        test::overlapping_boxes_sharing_an_edge()}) {
    Mesh m = d.mesh;
    MeshReport rep = repair(m);
    EXPECT_FALSE(rep.surface_only) << d.name;
    EXPECT_EQ(rep.nonmanifold_parts, 1u) << d.name;
    ObjectOptions o;
    o.resolution = 40;
    o.distance_bits = 8;
    const ObjectFile obj = make_object(m, d.name, 0, o, &rep);
    const auto c = obj.voxmap.counts();
    const double v3 = std::pow(obj.voxmap.voxel(), 3);
    EXPECT_GT(c[kInterior], 0u) << d.name;
    EXPECT_LE(double(c[kInterior]) * v3, d.volume) << d.name;
    EXPECT_GE(double(c[kInterior] + c[kSurface]) * v3, d.volume) << d.name;
    test::diff::Model model = test::diff::from_defect(d);
    const test::diff::Inside inside(model);
    const DistanceField& f = obj.distance;
    uint64_t deep = 0, wrong = 0;
    for (uint32_t z = 0; z <= f.dims[2]; ++z)
      for (uint32_t y = 0; y <= f.dims[1]; ++y)
        for (uint32_t x = 0; x <= f.dims[0]; ++x) {
          const Eigen::Vector3d p = obj.voxmap.origin() + obj.voxmap.voxel() * Eigen::Vector3d(x, y, z);
          if (inside.depth(p) <= obj.voxmap.voxel()) continue;
          ++deep;
          wrong += f.at(x, y, z) >= 0;
        }
    EXPECT_GT(deep, 0u) << d.name;
    EXPECT_EQ(wrong, 0u) << d.name << ": nodes more than a voxel inside with a distance >= 0";
  }
}

}  // namespace
}  // namespace voxcd
