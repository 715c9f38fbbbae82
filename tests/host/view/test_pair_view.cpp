// The pair page's poses and default (host/view/pair_view.h, docs/view.md "A pair"): every form `voxcd pair --pose`
// takes becomes the page's six numbers, three or six as typed and the others as degrees of the same rotation; both
// directions are tested unless asked otherwise, as `voxcd pair` tests them.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "voxcd/host/pairs/pose_text.h"
#include "voxcd/host/view/pair_view.h"

namespace voxcd {
namespace {

TEST(PairView, EveryPoseFormBecomesThePagesSixNumbers) {
  EXPECT_EQ(view::parse_pair_pose("1,2,3"), (view::PairPose{1, 2, 3, 0, 0, 0}));
  EXPECT_EQ(view::parse_pair_pose("0.5,0,0,10,-20,30"), (view::PairPose{0.5, 0, 0, 10, -20, 30}));
  const RigidPose want = euler_pose({1.2, 0, 0}, {10, -20, 30});
  const Eigen::Quaterniond& q = want.rotation;
  const std::string json =
      nlohmann::json{{"translation", {1.2, 0, 0}}, {"rotation_wxyz", {q.w(), q.x(), q.y(), q.z()}}}.dump();
  for (const std::string& text : {pose_text(want), json}) {
    const view::PairPose p = view::parse_pair_pose(text);
    const RigidPose got = euler_pose({p[0], p[1], p[2]}, {p[3], p[4], p[5]});
    EXPECT_EQ(got.translation, want.translation) << text;
    EXPECT_LT((got.rotation.toRotationMatrix() - want.rotation.toRotationMatrix()).cwiseAbs().maxCoeff(), 1e-12)
        << text;
    EXPECT_NEAR(p[3], 10, 1e-9) << text;
    EXPECT_NEAR(p[4], -20, 1e-9) << text;
    EXPECT_NEAR(p[5], 30, 1e-9) << text;
  }
  EXPECT_THROW(view::parse_pair_pose("1,2"), std::invalid_argument);
  EXPECT_THROW(view::parse_pair_pose("nan,0,0"), std::invalid_argument);
}

TEST(PairView, BothDirectionsByDefault) {
  EXPECT_TRUE(view::PairViewOptions{}.both_directions);
  view::PairViewOptions opt;
  opt.resolution = 16;
  view::PairView both("torus", "cube", opt);
  opt.both_directions = false;
  view::PairView one("torus", "cube", opt);
  const view::PairPose pose{1.2, 0, 0, 0, 0, 30};
  const nlohmann::json b = nlohmann::json::parse(both.page_json(pose)), o = nlohmann::json::parse(one.page_json(pose));
  EXPECT_EQ(b["both_directions"], true);
  EXPECT_EQ(o["both_directions"], false);
  EXPECT_GT(b["result"]["hits"].get<int>(), o["result"]["hits"].get<int>());
}

}  // namespace
}  // namespace voxcd
