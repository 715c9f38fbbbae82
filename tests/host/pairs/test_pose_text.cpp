// The one pose parser (host/pairs/pose_text.h) that `voxcd pair --pose`, `voxcd view --pose` and the Python module
// share: its five forms of numbers and its JSON, a printed pose read back bit for bit, and errors that quote the word
// and the text.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/pairs/pose_text.h"

namespace voxcd {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_pose(text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string error_of(const std::vector<double>& v) {
  try {
    pose_from_numbers(v.data(), v.size());
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// Equal bit for bit (a quaternion and its negation are the same rotation, but not the same pose text).
bool same(const RigidPose& a, const RigidPose& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}

// The same rigid motion to `tol`: translations, and rotations as matrices.
bool close(const RigidPose& a, const RigidPose& b, double tol) {
  return (a.translation - b.translation).cwiseAbs().maxCoeff() <= tol &&
         (a.rotation.toRotationMatrix() - b.rotation.toRotationMatrix()).cwiseAbs().maxCoeff() <= tol;
}

// The 12 and 16 numbers of a pose's matrix, row-major.
std::vector<double> matrix_numbers(const RigidPose& p, bool homogeneous) {
  const Eigen::Matrix3d R = p.rotation.toRotationMatrix();
  std::vector<double> v;
  for (int i = 0; i < 3; ++i) v.insert(v.end(), {R(i, 0), R(i, 1), R(i, 2), p.translation[i]});
  if (homogeneous) v.insert(v.end(), {0, 0, 0, 1});
  return v;
}

std::string joined(const std::vector<double>& v) {
  std::string s;
  for (double x : v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.17g", x);
    s += (s.empty() ? "" : ",") + std::string(b);
  }
  return s;
}

TEST(PoseText, ThreeAndSixNumbersAreATranslationAndDegreesAsBefore) {
  EXPECT_TRUE(same(parse_pose("1,-2.5,3e2"), euler_pose({1, -2.5, 300})));
  EXPECT_TRUE(same(parse_pose("0,0,0,90,0,-45"), euler_pose({0, 0, 0}, {90, 0, -45})));
  const RigidPose p = parse_pose("0,0,0,0,0,90");  // 90 degrees about z takes x to y
  EXPECT_LT((p.rotation * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-15);
}

TEST(PoseText, SevenNumbersAreATranslationAndAQuaternionWxyz) {
  const RigidPose p = parse_pose("1,2,3,0.70710678118654757,0,0,0.70710678118654757");
  EXPECT_EQ(p.translation, Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(close(p, euler_pose({1, 2, 3}, {0, 0, 90}), 1e-15));
  // Digits typed by hand: normalised when the norm is within 1e-3 of 1.
  EXPECT_TRUE(close(parse_pose("0,0,0,0.7071,0,0,0.7071"), euler_pose({0, 0, 0}, {0, 0, 90}), 1e-12));
}

TEST(PoseText, TwelveAndSixteenNumbersAreRowMajorMatrices) {
  const RigidPose want = euler_pose({0.5, -1, 2}, {10, -20, 30});
  for (bool homogeneous : {false, true}) {
    const std::vector<double> v = matrix_numbers(want, homogeneous);
    EXPECT_TRUE(close(pose_from_numbers(v.data(), v.size()), want, 1e-14)) << v.size();
    EXPECT_TRUE(close(parse_pose(joined(v)), want, 1e-14)) << v.size();
  }
}

TEST(PoseText, JsonAsTheToolPrintsIt) {
  const RigidPose want = euler_pose({1.2, 0, 0}, {0, 0, 30});
  const std::string printed = "{\"translation\": [1.2, 0, 0], \"rotation_wxyz\": [" +
                              joined({want.rotation.w(), want.rotation.x(), want.rotation.y(), want.rotation.z()}) +
                              "]}";
  EXPECT_TRUE(same(parse_pose(printed), want)) << printed;
  EXPECT_TRUE(same(parse_pose("{\"translation\": [1, 2, 3]}"), euler_pose({1, 2, 3})));
  EXPECT_TRUE(same(parse_pose("[0, 0, 0, 90, 0, -45]"), euler_pose({0, 0, 0}, {90, 0, -45})));
}

// Every form, printed by pose_text, reads back as the same pose, bit for bit.
TEST(PoseText, PrintedPosesReadBackExactly) {
  const RigidPose e = euler_pose({0.1, -7.25, 1e-3}, {33, -71, 190});
  std::vector<std::string> texts = {"1,2,3", "0.1,-7.25,0.001,33,-71,190", "1,2,3,0.5,0.5,0.5,0.5",
                                    joined(matrix_numbers(e, false)), joined(matrix_numbers(e, true)),
                                    "-0,0,0,-1,0,0,0"};
  for (const std::string& text : texts) {
    const RigidPose p = parse_pose(text);
    const std::string printed = pose_text(p);
    EXPECT_TRUE(same(parse_pose(printed), p)) << text << " -> " << printed;
    EXPECT_EQ(pose_text(parse_pose(printed)), printed);
  }
  EXPECT_EQ(pose_text(RigidPose{}), "0,0,0,1,0,0,0");
}

TEST(PoseText, EulerDegreesGiveTheRotationBack) {
  for (const Eigen::Vector3d& d : {Eigen::Vector3d(10, -20, 30), Eigen::Vector3d(-170, 89, 5),
                                  Eigen::Vector3d(45, 90, 0), Eigen::Vector3d(0, -90, 60),
                                  Eigen::Vector3d(0, 0, 0)}) {
    const RigidPose p = euler_pose({0, 0, 0}, d);
    EXPECT_TRUE(close(euler_pose({0, 0, 0}, euler_degrees(p.rotation)), p, 1e-12)) << d.transpose();
  }
}

TEST(PoseText, ErrorsQuoteTheWordAndTheText) {
  const std::string forms =
      "give 3 (tx,ty,tz), 6 (tx,ty,tz,rx,ry,rz in degrees), 7 (tx,ty,tz,qw,qx,qy,qz), 12 (a 3x4 matrix [R|t], "
      "row-major) or 16 (a 4x4 matrix, row-major)";
  EXPECT_EQ(error_of("1,x,3"), "'x' in '1,x,3' is not a number");
  EXPECT_EQ(error_of("1,,3"), "'' in '1,,3' is not a number");
  EXPECT_EQ(error_of("1,2,3,"), "'' in '1,2,3,' is not a number");
  EXPECT_EQ(error_of("1,2"), "'1,2' has 2 numbers; " + forms);
  EXPECT_EQ(error_of("1,2,3,4"), "'1,2,3,4' has 4 numbers; " + forms);
  EXPECT_EQ(error_of("[1]"), "'[1]' has 1 number; " + forms);
  EXPECT_EQ(error_of(std::vector<double>{1, 2}), "2 numbers; " + forms);
  EXPECT_EQ(error_of("0,0,0,2,0,0,0"), "'0,0,0,2,0,0,0': the quaternion (2, 0, 0, 0) has norm 2, not 1");
  EXPECT_EQ(error_of("1,0,0,0,1,0,0,0,1,0,0,0,0,0,0,2"),
            "'1,0,0,0,1,0,0,0,1,0,0,0,0,0,0,2': the 4x4 matrix's last row is (0, 0, 0, 2), not (0, 0, 0, 1)");
  EXPECT_EQ(error_of("2,0,0,0,0,1,0,0,0,0,1,0"),
            "'2,0,0,0,0,1,0,0,0,0,1,0': the matrix's upper left 3x3 is not a rotation (R^T R differs from I by 3, "
            "det 2)");
  EXPECT_NE(error_of("-1,0,0,0,0,1,0,0,0,0,1,0").find("is not a rotation"), std::string::npos);  // a reflection
  EXPECT_EQ(error_of("{\"translation\": [1, 2]}"),
            "'{\"translation\": [1, 2]}': translation must be an array of 3 numbers");
  EXPECT_EQ(error_of("{\"t\": [1, 2, 3]}"), "'{\"t\": [1, 2, 3]}': t: unknown key (known: translation, rotation_wxyz)");
  EXPECT_EQ(error_of("[1, 2").rfind("'[1, 2' is not valid JSON: ", 0), 0u);
}

TEST(PoseText, NonFiniteNumbersAreRefusedNamingTheNumber) {
  EXPECT_EQ(error_of("nan,0,0"), "'nan' in 'nan,0,0' is not a finite number");
  EXPECT_EQ(error_of("0,inf,0"), "'inf' in '0,inf,0' is not a finite number");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of(std::vector<double>{0, 0, 0, nan, 0, 0}), "number 4 of 6 (nan) is not finite");
  EXPECT_EQ(error_of(std::vector<double>{0, 0, 0, 1, 0, 0, std::numeric_limits<double>::infinity()}),
            "number 7 of 7 (inf) is not finite");
}

}  // namespace
}  // namespace voxcd
