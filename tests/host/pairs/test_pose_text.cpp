// The one parser of "tx,ty,tz[,rx,ry,rz]" (host/pairs/pose.h) that `voxcd pair --pose` and `voxcd view --pose` share:
// three or six numbers, and errors that quote the word and the text.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/pairs/pose.h"

namespace voxcd {
namespace {

std::string error_of(const std::string& text, bool finite) {
  try {
    parse_pose_numbers(text, finite);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(PoseText, ThreeOrSixNumbers) {
  EXPECT_EQ(parse_pose_numbers("1,-2.5,3e2", true), (std::vector<double>{1, -2.5, 300}));
  EXPECT_EQ(parse_pose_numbers("0,0,0,90,0,-45", false), (std::vector<double>{0, 0, 0, 90, 0, -45}));
}

TEST(PoseText, ErrorsQuoteTheWordAndTheText) {
  EXPECT_EQ(error_of("1,x,3", false), "'x' in '1,x,3' is not a number");
  EXPECT_EQ(error_of("1,x,3", true), "'x' in '1,x,3' is not a finite number");
  EXPECT_EQ(error_of("1,,3", false), "'' in '1,,3' is not a number");
  EXPECT_EQ(error_of("1,2", false), "'1,2' has 2 numbers; give tx,ty,tz or tx,ty,tz,rx,ry,rz");
  EXPECT_EQ(error_of("1,2,3,4", true), "'1,2,3,4' has 4 numbers; give tx,ty,tz or tx,ty,tz,rx,ry,rz");
}

TEST(PoseText, NonFiniteNumbersOnlyWhereAllowed) {
  EXPECT_EQ(error_of("nan,0,0", false), "");  // voxcd pair refuses the pose later, naming the pair
  EXPECT_EQ(error_of("0,inf,0", true), "'inf' in '0,inf,0' is not a finite number");
}

}  // namespace
}  // namespace voxcd
