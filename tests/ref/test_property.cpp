// Random property test over 10^6 lookups on several configurations:
//  - the fixed-point index equals the exact rational result on the quantised inputs (floor of the exact sum,
//    computed here by division instead of the reference's shift);
//  - it equals the double-precision model's index except where the exact point lies within the documented
//    bound of a voxel boundary; and the fixed-point value itself is within that bound of the double model.
// Seed: printed at start; VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <random>

#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

uint64_t test_seed() { return test::seed(20261122); }

void random_rotation(std::mt19937_64& rng, double R[3][3]) {
  std::normal_distribution<double> n(0, 1);
  double q[4], len;
  do {
    len = 0;
    for (double& c : q) {
      c = n(rng);
      len += c * c;
    }
  } while (len < 1e-6);
  len = std::sqrt(len);
  for (double& c : q) c /= len;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                          {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                          {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = r[i][j];
}

// floor(a / 2^s) by division, not by shifting.
Acc floor_div(Acc a, int s) {
  const Acc d = Acc(1) << s;
  Acc q = a / d;
  if (a % d != 0 && a < 0) q -= 1;
  return q;
}

struct Stats {
  uint64_t lookups = 0, exact_mismatch = 0, disagreements = 0, violations = 0, value_violations = 0;
  double worst_ratio = 0;  // largest |fixed - double| / bound seen
};

void run_config(const DeviceConfig& cfg, uint64_t seed, uint64_t n, Stats& st) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const double mmax = matrix_format(cfg).max_value();
  const double pspan = std::min(48.0, point_format(cfg).max_value() / 2);
  Job job;
  job.nx = job.ny = job.nz = 1u << std::min(cfg.DW, 6);
  FloatPose pose;
  for (uint64_t k = 0; k < n; ++k) {
    if (k % 64 == 0) {  // a new pose every 64 points
      double R[3][3];
      random_rotation(rng, R);
      const double s = std::min(0.5 + 0.5 * (u(rng) + 1), mmax * 0.99);
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) pose.M[i][j] = R[i][j] * s;
        pose.t[i] = 32 + 40 * u(rng);
      }
      quantize_pose(cfg, pose, job);
    }
    const double p[3] = {pspan * u(rng), pspan * u(rng), pspan * u(rng)};
    const ShellWord w = quantize_point(cfg, p, "p");
    const Transformed tr = transform(cfg, job, w);
    const Located loc = locate(cfg, job, tr);
    double y[3];
    float_transform(pose, p, y);
    for (int i = 0; i < 3; ++i) {
      // The exact sum on the quantised inputs, recomputed term by term, floored by division.
      Acc exact = Acc(job.t[i]);
      for (int j = 0; j < 3; ++j) exact += Acc(job.M[i][j]) * Acc(w[j]);
      if (Acc(loc.index[i]) != floor_div(exact, cfg.TF()) || !(exact == tr.acc[i])) ++st.exact_mismatch;
      // The double model's own rounding: a few ulps of the largest term.
      double mag = std::fabs(pose.t[i]);
      for (int j = 0; j < 3; ++j) mag += std::fabs(pose.M[i][j] * p[j]);
      const double eps = 8 * std::ldexp(mag, -52);
      const double bound = error_bound(cfg, job, i, p, false);
      const double fixed_value = double(static_cast<long double>(exact) / std::ldexp(1.0L, cfg.TF()));
      const double diff = std::fabs(fixed_value - y[i]);
      st.worst_ratio = std::max(st.worst_ratio, diff / bound);
      if (diff > bound + eps) ++st.value_violations;
      const double dbl_index = std::floor(y[i]);
      if (dbl_index != double(loc.index[i])) {
        ++st.disagreements;
        // A disagreement is allowed only within the bound of the voxel boundary between the two indices.
        const double boundary = std::max(dbl_index, double(loc.index[i]));
        if (std::fabs(y[i] - boundary) > bound + eps) ++st.violations;
      }
    }
    ++st.lookups;
  }
}

TEST(Property, FixedPointAgainstExactAndDoubleModels) {
  const uint64_t seed = test_seed();
  std::printf("property test \n");
  struct Named {
    const char* name;
    DeviceConfig cfg;
  };
  std::vector<Named> cfgs;
  cfgs.push_back({"default", DeviceConfig{}});
  DeviceConfig coarse;  // few fraction bits: disagreements are frequent, so the bound is really exercised
  coarse.PW = 14;
  coarse.PF = 3;
  coarse.MW = 10;
  coarse.MF = 8;
  coarse.TW = 24;
  coarse.DW = 7;
  cfgs.push_back({"coarse", coarse});
  DeviceConfig fine;
  fine.PW = 32;
  fine.PF = 16;
  fine.MW = 26;
  fine.MF = 24;
  fine.TW = 64;
  cfgs.push_back({"fine", fine});
  DeviceConfig mid;
  mid.PW = 20;
  mid.PF = 6;
  mid.MW = 14;
  mid.MF = 12;
  mid.TW = 36;
  cfgs.push_back({"mid", mid});
  uint64_t total = 0;
  for (size_t c = 0; c < cfgs.size(); ++c) {
    Stats st;
    ASSERT_NO_THROW(cfgs[c].cfg.validate()) << cfgs[c].name;
    run_config(cfgs[c].cfg, seed + c, 250000, st);
    std::printf("  %-8s %8llu lookups, %7llu index disagreements with double, worst error / bound %.3f\n",
                cfgs[c].name, (unsigned long long)st.lookups, (unsigned long long)st.disagreements,
                st.worst_ratio);
    EXPECT_EQ(st.exact_mismatch, 0u) << cfgs[c].name << " seed " << seed;
    EXPECT_EQ(st.violations, 0u) << cfgs[c].name << " seed " << seed;
    EXPECT_EQ(st.value_violations, 0u) << cfgs[c].name << " seed " << seed;
    EXPECT_LE(st.worst_ratio, 1.0) << cfgs[c].name;
    total += st.lookups;
    if (std::string(cfgs[c].name) == "coarse") {
      // Sensitivity: with 8 matrix and 3 point fraction bits the two models must disagree sometimes, and the
      // error must use a real part of the bound; otherwise this test could not fail.
      EXPECT_GT(st.disagreements, 1000u);
      EXPECT_GT(st.worst_ratio, 0.3);
    }
  }
  EXPECT_GE(total, 1000000u);
}

}  // namespace
}  // namespace voxcd
