#include "voxcd/host/pairs/pose.h"

#include <cmath>

#include "voxcd/ref/fixed.h"

namespace voxcd {

namespace {
void require_finite(const RigidPose& p, const char* which) {
  const Eigen::Vector4d q = p.rotation.coeffs();
  // Finite when every entry is: x - x is 0 for a finite x and NaN otherwise, so one sum of them tells.
  const double probe = (q - q).sum() + (p.translation - p.translation).sum();
  if (probe != 0)
    throw RangeError(std::string("pose of ") + which + " is not finite (NaN or infinite rotation or translation)");
  // |n - 1| <= 1e-6 whenever |n^2 - 1| < 1.9e-6 (n^2 - 1 = (n - 1)(n + 1)): the square root only near the limit.
  if (std::fabs(q.squaredNorm() - 1.0) >= 1.9e-6 && std::fabs(q.norm() - 1.0) > 1e-6)
    throw RangeError(std::string("pose of ") + which + " has a rotation quaternion of norm " +
                     std::to_string(q.norm()) + ", not 1");
}
}  // namespace

FloatPose relative_pose(const RigidPose& a, const GridFrame& shell_a, const RigidPose& b, const GridFrame& map_b) {
  require_finite(a, "A");
  require_finite(b, "B");
  const Eigen::Matrix3d Ra = a.rotation.toRotationMatrix(), Rb = b.rotation.toRotationMatrix();
  const Eigen::Matrix3d R = Rb.transpose() * Ra;
  const Eigen::Matrix3d M = R * (shell_a.voxel / map_b.voxel);
  const Eigen::Vector3d t =
      (Rb.transpose() * (Ra * shell_a.origin + a.translation - b.translation) - map_b.origin) / map_b.voxel;
  FloatPose p;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) p.M[i][j] = M(i, j);
    p.t[i] = t(i);
  }
  return p;
}

void pose_job(const DeviceConfig& cfg, const RigidPose& a, const GridFrame& shell_a, const RigidPose& b,
              const GridFrame& map_b, Job& job) {
  quantize_pose(cfg, relative_pose(a, shell_a, b, map_b), job);
}

int64_t distance_threshold(const DeviceConfig& cfg, double margin, double voxel, double step) {
  const double unit = voxel * step / std::ldexp(1.0, 3 * cfg.WB);  // world units per unit of D
  const double lim = std::ldexp(1.0, cfg.IW() - 1);
  const double v = std::floor(margin / unit);
  if (!std::isfinite(margin) || !(v >= -lim && v < lim)) {
    throw RangeError("margin = " + std::to_string(margin) + " does not fit a distance job's threshold (signed " +
                     std::to_string(cfg.IW()) + "-bit in units of " + std::to_string(unit) +
                     " world units): it must lie in [" + std::to_string(-lim * unit) + ", " +
                     std::to_string((lim - 1) * unit) + "]");
  }
  return int64_t(v);
}

}  // namespace voxcd
