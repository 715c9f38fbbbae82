// Relative pose of A's shell grid in B's voxmap grid agrees with going through the world, and bad poses are
// errors, not garbage.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "voxcd/host/pairs/pose.h"
#include "voxcd/ref/fixed.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

Eigen::Quaterniond random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized();
}

TEST(Pose, RelativePoseMatchesTheWorldPath) {
  std::mt19937_64 rng(test::seed(3));
  std::uniform_real_distribution<double> u(-50, 50);
  for (int k = 0; k < 1000; ++k) {
    RigidPose a{random_rotation(rng), {u(rng), u(rng), u(rng)}}, b{random_rotation(rng), {u(rng), u(rng), u(rng)}};
    GridFrame sa{{u(rng), u(rng), u(rng)}, 0.1 + std::fabs(u(rng)) / 50}, mb{{u(rng), u(rng), u(rng)}, 0.2};
    const FloatPose p = relative_pose(a, sa, b, mb);
    const Eigen::Vector3d g(u(rng), u(rng), u(rng));
    const Eigen::Vector3d world = a.rotation * (sa.origin + sa.voxel * g) + a.translation;
    const Eigen::Vector3d want = (b.rotation.inverse() * (world - b.translation) - mb.origin) / mb.voxel;
    for (int i = 0; i < 3; ++i) {
      const double got = p.M[i][0] * g(0) + p.M[i][1] * g(1) + p.M[i][2] * g(2) + p.t[i];
      EXPECT_NEAR(got, want(i), 1e-9 * (1 + std::fabs(want(i))));
    }
  }
}

TEST(Pose, NonFiniteOrNonUnitPosesAreErrors) {
  RigidPose a, b;
  GridFrame f;
  a.translation.x() = std::nan("");
  EXPECT_THROW(relative_pose(a, f, b, f), RangeError);
  a = RigidPose{};
  b.rotation.coeffs() << 0, 0, std::numeric_limits<double>::infinity(), 1;
  EXPECT_THROW(relative_pose(a, f, b, f), RangeError);
  b = RigidPose{};
  b.rotation.coeffs() << 0, 0, 0, 2;  // not a unit quaternion
  try {
    relative_pose(a, f, b, f);
    ADD_FAILURE();
  } catch (const RangeError& e) {
    EXPECT_NE(std::string(e.what()).find("pose of B has a rotation quaternion of norm 2"), std::string::npos);
  }
}

TEST(Pose, QuantisedJobFailsCleanlyWhenFarOrScaledTooMuch) {
  DeviceConfig cfg;
  Job j;
  j.t[0] = 123;
  RigidPose a, b;
  GridFrame sa, mb;
  b.translation.x() = 1e7;  // 10^7 voxels away: does not fit TW = 48
  EXPECT_THROW(pose_job(cfg, a, sa, b, mb, j), RangeError);
  EXPECT_EQ(j.t[0], 123);
  b = RigidPose{};
  sa.voxel = 2.5;  // scale 2.5 does not fit MW = 18, MF = 16 ([-2, 2))
  EXPECT_THROW(pose_job(cfg, a, sa, b, mb, j), RangeError);
  sa.voxel = 1.0;
  EXPECT_NO_THROW(pose_job(cfg, a, sa, b, mb, j));
  EXPECT_EQ(j.M[0][0], 65536);
  EXPECT_EQ(j.t[0], 0);
}

}  // namespace
}  // namespace voxcd
