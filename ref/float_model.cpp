#include "voxcd/ref/float_model.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace voxcd {

FixedFormat matrix_format(const DeviceConfig& cfg) { return {cfg.MW, cfg.MF}; }
FixedFormat translation_format(const DeviceConfig& cfg) { return {cfg.TW, cfg.TF()}; }
FixedFormat point_format(const DeviceConfig& cfg) { return {cfg.PW, cfg.PF}; }

void quantize_pose(const DeviceConfig& cfg, const FloatPose& pose, Job& job) {
  int64_t M[3][3];
  int64_t t[3];
  const FixedFormat mf = matrix_format(cfg), tf = translation_format(cfg);
  for (int i = 0; i < 3; ++i) {
    // The message is built only for an entry that fails.
    for (int j = 0; j < 3; ++j)
      if (!try_quantize(pose.M[i][j], mf, &M[i][j]))
        M[i][j] = quantize(pose.M[i][j], mf, "M" + std::to_string(i) + std::to_string(j));
    if (!try_quantize(pose.t[i], tf, &t[i])) t[i] = quantize(pose.t[i], tf, "T" + std::to_string(i));
  }
  // Only a pose that fits entirely is written: a failure leaves the job as it was.
  std::copy(&M[0][0], &M[0][0] + 9, &job.M[0][0]);
  std::copy(t, t + 3, job.t);
}

ShellWord quantize_point(const DeviceConfig& cfg, const double p[3], const std::string& what) {
  const FixedFormat f = point_format(cfg);
  return ShellWord{quantize(p[0], f, what + ".x"), quantize(p[1], f, what + ".y"), quantize(p[2], f, what + ".z")};
}

void point_value(const DeviceConfig& cfg, const ShellWord& w, double p[3]) {
  for (int i = 0; i < 3; ++i) p[i] = to_double(w[i], cfg.PF);
}

void float_transform(const FloatPose& pose, const double p[3], double out[3]) {
  for (int i = 0; i < 3; ++i)
    out[i] = pose.M[i][0] * p[0] + pose.M[i][1] * p[1] + pose.M[i][2] * p[2] + pose.t[i];
}

namespace {
double row_l1(const DeviceConfig& cfg, const Job& job, int i) {
  double s = 0;
  for (int j = 0; j < 3; ++j) s += std::fabs(to_double(job.M[i][j], cfg.MF));
  return s;
}
}  // namespace

double error_bound(const DeviceConfig& cfg, const Job& job, int axis, const double p[3], bool point_quantised) {
  const double p1 = std::fabs(p[0]) + std::fabs(p[1]) + std::fabs(p[2]);
  double b = std::ldexp(p1, -(cfg.MF + 1)) + std::ldexp(1.0, -(cfg.TF() + 1));
  if (!point_quantised) b += std::ldexp(row_l1(cfg, job, axis), -(cfg.PF + 1));
  return b;
}

double error_bound_max(const DeviceConfig& cfg, const Job& job, double max_abs_p) {
  double worst = 0;
  for (int i = 0; i < 3; ++i) {
    const double b = 3 * std::ldexp(max_abs_p, -(cfg.MF + 1)) + std::ldexp(row_l1(cfg, job, i), -(cfg.PF + 1)) +
                     std::ldexp(1.0, -(cfg.TF() + 1));
    worst = std::max(worst, b);
  }
  return worst;
}

}  // namespace voxcd
