#include "voxcd/host/pairs/pose_text.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace voxcd {

namespace {

constexpr const char* kForms =
    "give 3 (tx,ty,tz), 6 (tx,ty,tz,rx,ry,rz in degrees), 7 (tx,ty,tz,qw,qx,qy,qz), 12 (a 3x4 matrix [R|t], "
    "row-major) or 16 (a 4x4 matrix, row-major)";

bool known_count(size_t n) { return n == 3 || n == 6 || n == 7 || n == 12 || n == 16; }

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.17g", v);
  return b;
}

// The rotation of a unit quaternion given as w, x, y, z: kept exactly when its norm is 1 to 1e-12 (a pose the tool
// printed), normalised when within 1e-3 (digits typed by hand), else an error.
Eigen::Quaterniond unit_quaternion(const double* q) {
  const Eigen::Quaterniond r(q[0], q[1], q[2], q[3]);
  const double norm = r.norm();
  if (std::fabs(norm - 1) <= 1e-12) return r;
  if (std::fabs(norm - 1) <= 1e-3) return r.normalized();
  throw std::invalid_argument("the quaternion (" + number(q[0]) + ", " + number(q[1]) + ", " + number(q[2]) + ", " +
                              number(q[3]) + ") has norm " + number(norm) + ", not 1");
}

// The rotation of the 3 x 3 part of a row-major matrix of `cols` columns: an error when it is not a rotation to 1e-6.
Eigen::Quaterniond matrix_rotation(const double* m, int cols) {
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R(i, j) = m[cols * i + j];
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(off < 1e-6) || !(R.determinant() > 0))
    throw std::invalid_argument("the matrix's upper left 3x3 is not a rotation (R^T R differs from I by " +
                                number(off) + ", det " + number(R.determinant()) + ")");
  return Eigen::Quaterniond(R).normalized();
}

}  // namespace

RigidPose euler_pose(const Eigen::Vector3d& translation, const Eigen::Vector3d& degrees) {
  RigidPose p;
  p.translation = translation;
  const double k = M_PI / 180.0;
  p.rotation = Eigen::AngleAxisd(degrees[2] * k, Eigen::Vector3d::UnitZ()) *
               Eigen::AngleAxisd(degrees[1] * k, Eigen::Vector3d::UnitY()) *
               Eigen::AngleAxisd(degrees[0] * k, Eigen::Vector3d::UnitX());
  return p;
}

Eigen::Vector3d euler_degrees(const Eigen::Quaterniond& q) {
  // R = Rz(c) Ry(b) Rx(a): R20 = -sin b, R21 / R22 = tan a, R10 / R00 = tan c while cos b is not 0; at b = +-90 degrees
  // only a -+ c is defined, and c is taken as 0.
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  const double s = std::clamp(-R(2, 0), -1.0, 1.0);
  double a, b = std::asin(s), c = 0;
  if (std::fabs(s) < 1 - 1e-12) {
    a = std::atan2(R(2, 1), R(2, 2));
    c = std::atan2(R(1, 0), R(0, 0));
  } else {
    a = std::atan2(s > 0 ? R(0, 1) : -R(0, 1), R(1, 1));
  }
  return Eigen::Vector3d(a, b, c) * (180.0 / M_PI);
}

RigidPose pose_from_numbers(const double* v, size_t n) {
  if (!known_count(n)) throw std::invalid_argument(std::to_string(n) + " numbers; " + kForms);
  for (size_t i = 0; i < n; ++i)
    if (!std::isfinite(v[i]))
      throw std::invalid_argument("number " + std::to_string(i + 1) + " of " + std::to_string(n) + " (" +
                                  number(v[i]) + ") is not finite");
  if (n == 3 || n == 6)
    return n == 6 ? euler_pose({v[0], v[1], v[2]}, {v[3], v[4], v[5]}) : euler_pose({v[0], v[1], v[2]});
  RigidPose p;
  if (n == 7) {
    p.translation = Eigen::Vector3d(v[0], v[1], v[2]);
    p.rotation = unit_quaternion(v + 3);
    return p;
  }
  if (n == 16 && !(v[12] == 0 && v[13] == 0 && v[14] == 0 && v[15] == 1))
    throw std::invalid_argument("the 4x4 matrix's last row is (" + number(v[12]) + ", " + number(v[13]) + ", " +
                                number(v[14]) + ", " + number(v[15]) + "), not (0, 0, 0, 1)");
  p.rotation = matrix_rotation(v, 4);
  p.translation = Eigen::Vector3d(v[3], v[7], v[11]);
  return p;
}

namespace {

// The numbers of a JSON pose: an array of numbers, or {"translation": [3], "rotation_wxyz": [4]} (the rotation
// optional).
std::vector<double> json_numbers(const std::string& text) {
  using nlohmann::json;
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    const std::string what = e.what();
    const auto p = what.find("] ");
    throw std::invalid_argument("'" + text + "' is not valid JSON: " +
                                (p == std::string::npos ? what : what.substr(p + 2)));
  }
  auto numbers = [&](const json& a, const char* key, size_t n, std::vector<double>& out) {
    if (!a.is_array() || a.size() != n || !std::all_of(a.begin(), a.end(), [](const json& x) { return x.is_number(); }))
      throw std::invalid_argument("'" + text + "': " + key + " must be an array of " + std::to_string(n) + " numbers");
    for (const json& x : a) out.push_back(x.get<double>());
  };
  std::vector<double> v;
  if (j.is_array()) {
    numbers(j, "the pose", j.size(), v);
    return v;
  }
  if (!j.is_object())
    throw std::invalid_argument("'" + text + "' is JSON " + j.type_name() +
                                "; give an array of numbers or {\"translation\": [...], \"rotation_wxyz\": [...]}");
  for (const auto& [key, value] : j.items())
    if (key != "translation" && key != "rotation_wxyz")
      throw std::invalid_argument("'" + text + "': " + key + ": unknown key (known: translation, rotation_wxyz)");
  if (!j.contains("translation")) throw std::invalid_argument("'" + text + "': translation: missing");
  numbers(j["translation"], "translation", 3, v);
  if (j.contains("rotation_wxyz")) numbers(j["rotation_wxyz"], "rotation_wxyz", 4, v);
  return v;
}

// The numbers of "a,b,c,...".
std::vector<double> comma_numbers(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    char* end = nullptr;
    const double d = std::strtod(item.c_str(), &end);
    if (item.empty() || end == item.c_str() || *end != '\0')
      throw std::invalid_argument("'" + item + "' in '" + text + "' is not a number");
    if (!std::isfinite(d)) throw std::invalid_argument("'" + item + "' in '" + text + "' is not a finite number");
    v.push_back(d);
  }
  if (!text.empty() && text.back() == ',') throw std::invalid_argument("'' in '" + text + "' is not a number");
  return v;
}

}  // namespace

RigidPose parse_pose(const std::string& text) {
  const size_t first = text.find_first_not_of(" \t\r\n");
  const bool json = first != std::string::npos && (text[first] == '[' || text[first] == '{');
  const std::vector<double> v = json ? json_numbers(text) : comma_numbers(text);
  if (!known_count(v.size()))
    throw std::invalid_argument("'" + text + "' has " + std::to_string(v.size()) + " number" +
                                (v.size() == 1 ? "" : "s") + "; " + kForms);
  try {
    return pose_from_numbers(v.data(), v.size());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("'" + text + "': " + e.what());
  }
}

std::string pose_text(const RigidPose& p) {
  const Eigen::Vector3d& t = p.translation;
  const Eigen::Quaterniond& q = p.rotation;
  std::string s;
  for (const double x : {t.x(), t.y(), t.z(), q.w(), q.x(), q.y(), q.z()}) s += (s.empty() ? "" : ",") + number(x);
  return s;
}

}  // namespace voxcd
