// The workload of bench_sparse_lookup: one object, a ball, in both forms a sparse device takes (docs/contract.md, "Sparse
// voxmaps and shells"): its voxmap dense and sparse (2-bit states, or a distance field), and points to look up, as
// dense shell words and as a sparse shell. The two forms of the map hold the same voxels (a sparse distance map's
// bricks are of level 0, the dense field's nodes), so a lookup gives the same answer on either and the hits agree.
//  - states: voxel (x, y, z) of centre c = (x, y, z) + 1/2 is surface where | |c - C| - R | < 0.87, else interior
//    inside the ball, else empty;
//  - distances: node (X, Y, Z) holds round(32 d) clamped to [-128, 127], d = |(X, Y, Z) - C| - R (the host's step of
//    1/32 voxel: a band of 4 voxels);
//  - points: near the surface (| |p - C| - R | < 1.5) or anywhere in the map's box, through a rotation of 30 degrees
//    about z; a sparse shell: the bricks of the shell voxels of a sphere of radius R (docs/contract.md, "Shell
//    bricks"), chained by steps, and the same points as dense words.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd::bench {

struct Ball {
  double c, r;  // centre (c, c, c) and radius, in voxels
  double distance(double x, double y, double z) const {
    return std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) - r;
  }
  uint8_t state(uint64_t x, uint64_t y, uint64_t z) const {
    const double d = distance(double(x) + 0.5, double(y) + 0.5, double(z) + 0.5);
    return std::fabs(d) < 0.87 ? kSurface : d < 0 ? kInterior : kEmpty;
  }
  int64_t node(uint64_t x, uint64_t y, uint64_t z) const {
    return std::clamp<int64_t>(std::llround(32 * distance(double(x), double(y), double(z))), -128, 127);
  }
};

// Appends the dense 2-bit map of n^3 voxels to `map`; returns its base.
inline uint32_t append_dense_states(const Ball& b, uint32_t n, std::vector<uint64_t>& map) {
  const uint32_t base = uint32_t(map.size());
  const uint64_t voxels = uint64_t(n) * n * n;
  map.resize(base + (voxels + 31) / 32, 0);
  uint64_t i = 0;
  for (uint64_t z = 0; z < n; ++z)
    for (uint64_t y = 0; y < n; ++y)
      for (uint64_t x = 0; x < n; ++x, ++i) map[base + i / 32] |= uint64_t(b.state(x, y, z)) << (2 * (i % 32));
  return base;
}

// Appends the dense distance map of n^3 cells (its (n + 1)^3 nodes, SB 8, MEMW 64) on a bank boundary.
inline uint32_t append_dense_field(const Ball& b, uint32_t n, std::vector<uint64_t>& map) {
  map.resize((map.size() + 7) / 8 * 8, 0);
  const uint32_t base = uint32_t(map.size());
  const uint64_t h = n / 2 + 1;
  map.resize(base + 8 * ((h * h * h + 7) / 8), 0);
  for (uint64_t Z = 0; Z <= n; ++Z)
    for (uint64_t Y = 0; Y <= n; ++Y)
      for (uint64_t X = 0; X <= n; ++X) {
        const uint64_t hi = (X >> 1) + h * ((Y >> 1) + h * (Z >> 1)), bank = (X & 1) | (Y & 1) << 1 | (Z & 1) << 2;
        map[base + 8 * (hi / 8) + bank] |= (uint64_t(b.node(X, Y, Z)) & 0xff) << (8 * (hi % 8));
      }
  return base;
}

// A cell's code: uniform where every voxel (node) it holds agrees, found from its centre's distance where the ball
// cannot reach it, else by looking; a brick otherwise (2-bit: code 3; distance: level 0).
inline uint8_t cell_code(const DeviceConfig& cfg, const Ball& b, uint64_t cx, uint64_t cy, uint64_t cz) {
  const uint64_t B = brick_edge(cfg);
  const double half = double(B) / 2, reach = half * std::sqrt(3.0) + (cfg.distance() ? 4.0 : 0.87) + 0.1;
  const double d = b.distance(double(cx * B) + half, double(cy * B) + half, double(cz * B) + half);
  if (d > reach) return kCodeFar;  // 0: empty, or far outside
  if (d < -reach) return cfg.distance() ? kCodeDeep : uint8_t(kInterior);
  const uint64_t e = cfg.distance() ? B + 1 : B;
  int64_t first = 0;
  bool same = true;
  for (uint64_t i = 0; i < e * e * e && same; ++i) {
    const uint64_t x = cx * B + i % e, y = cy * B + i / e % e, z = cz * B + i / (e * e);
    const int64_t v = cfg.distance() ? b.node(x, y, z) : b.state(x, y, z);
    if (i == 0) first = v;
    same = v == first;
  }
  if (!same || (cfg.distance() && first != 127 && first != -128)) return cfg.distance() ? kCodeLevel0 : kCodeBrick;
  return cfg.distance() ? (first == 127 ? kCodeFar : kCodeDeep) : uint8_t(first);
}

// Appends the sparse map of n^3 voxels (table, then bricks); returns the job fields of a sparse job on it.
inline Job append_sparse(const DeviceConfig& cfg, const Ball& b, uint32_t n, std::vector<uint64_t>& map) {
  Job j;
  j.sparse = kSparseMap;
  j.nx = j.ny = j.nz = n;
  const uint64_t C = coarse_dims(cfg, j).c[0], B = brick_edge(cfg), align = cfg.distance() ? 8 : 1;
  std::vector<uint8_t> codes(C * C * C);
  for (uint64_t t = 0; t < codes.size(); ++t) codes[t] = cell_code(cfg, b, t % C, t / C % C, t / (C * C));
  const std::vector<uint64_t> table = table_image(cfg, codes);
  map.resize((map.size() + align - 1) / align * align, 0);
  j.map_base = uint32_t(map.size());
  map.insert(map.end(), table.begin(), table.end());
  map.resize((map.size() + align - 1) / align * align, 0);
  j.brick_base = uint32_t(map.size());
  j.brick_units = uint32_t(table_units(cfg, codes));
  map.resize(map.size() + uint64_t(j.brick_units) * unit_words(cfg), 0);
  uint64_t unit = 0;
  for (uint64_t t = 0; t < codes.size(); ++t) {
    const Cell cell{codes[t], code_level(cfg, codes[t]), j.brick_base + unit * unit_words(cfg)};
    if (cell.level < 0) continue;
    ++unit;
    const uint64_t o[3] = {t % C * B, t / C % C * B, t / (C * C) * B};
    const uint64_t e = cfg.distance() ? B + 1 : B;
    for (uint64_t i = 0; i < e * e * e; ++i) {
      const uint64_t X = i % e, Y = i / e % e, Z = i / (e * e);
      if (!cfg.distance()) {
        map[cell.first + i / 32] |= uint64_t(b.state(o[0] + X, o[1] + Y, o[2] + Z)) << (2 * (i % 32));
        continue;
      }
      const NodeAddress a = brick_node_address(cfg, cell, X, Y, Z);
      map[a.word] |= (uint64_t(b.node(o[0] + X, o[1] + Y, o[2] + Z)) & 0xff) << (8 * a.slot);
    }
  }
  return j;
}

// The pose of every job: a rotation of 30 degrees about z that keeps the ball's centre in place.
inline void ball_pose(const DeviceConfig& cfg, const Ball& b, Job& j) {
  FloatPose pose;
  const double a = 0.5236, c = std::cos(a), s = std::sin(a);
  const double R[3][3] = {{c, -s, 0}, {s, c, 0}, {0, 0, 1}};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) pose.M[i][k] = R[i][k];
    pose.t[i] = b.c - (R[i][0] + R[i][1] + R[i][2]) * b.c;
  }
  quantize_pose(cfg, pose, j);
}

// The shell word that the pose takes to map point p.
inline ShellWord shell_of(const DeviceConfig& cfg, const Ball& b, const double p[3]) {
  const double a = -0.5236, c = std::cos(a), s = std::sin(a);
  const double q[3] = {p[0] - b.c, p[1] - b.c, p[2] - b.c};
  const double w[3] = {c * q[0] - s * q[1] + b.c, s * q[0] + c * q[1] + b.c, q[2] + b.c};
  return quantize_point(cfg, w, "p");
}

// `count` points near the ball's surface (within 1.5 voxels) or anywhere in the map's box, as shell words.
inline std::vector<ShellWord> ball_points(const DeviceConfig& cfg, const Ball& b, uint32_t n, size_t count,
                                          bool surface, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  std::vector<ShellWord> out;
  while (out.size() < count) {
    double p[3];
    if (surface) {
      const double d[3] = {g(rng), g(rng), g(rng)}, len = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double r = b.r + 3 * (u(rng) - 0.5);
      for (int i = 0; i < 3; ++i) p[i] = b.c + r * d[i] / len;
    } else {
      for (double& v : p) v = n * u(rng);
    }
    out.push_back(shell_of(cfg, b, p));
  }
  return out;
}

// The sparse shell of the shell voxels of a sphere of radius r around the ball's centre (the voxels of the shell grid,
// in map voxels before the pose, whose centres lie within 0.75 of it), brick by brick in z, y, x order; an origin word
// where the next brick is no neighbour of the last.
inline std::vector<ShellWord> sphere_shell(const DeviceConfig& cfg, const Ball& b, double r) {
  std::vector<ShellWord> out;
  const int64_t unit = int64_t{1} << cfg.PF, lo = int64_t(std::floor((b.c - r - 1) / kShellBrick));
  const int64_t hi = int64_t(std::ceil((b.c + r + 1) / kShellBrick));
  int64_t prev[3] = {0, 0, 0};
  bool have = false;
  for (int64_t bz = lo; bz <= hi; ++bz)
    for (int64_t by = lo; by <= hi; ++by)
      for (int64_t bx = lo; bx <= hi; ++bx) {
        uint64_t mask = 0;
        for (int i = 0; i < 64; ++i) {
          const double c[3] = {double(bx * kShellBrick + (i & 3)) + 0.5, double(by * kShellBrick + (i >> 2 & 3)) + 0.5,
                               double(bz * kShellBrick + (i >> 4)) + 0.5};
          if (std::fabs(std::sqrt((c[0] - b.c) * (c[0] - b.c) + (c[1] - b.c) * (c[1] - b.c) +
                                  (c[2] - b.c) * (c[2] - b.c)) - r) < 0.75)
            mask |= uint64_t{1} << i;
        }
        if (!mask) continue;
        const int64_t at[3] = {bx, by, bz};
        int step[3] = {0, 0, 0};
        bool near = have;
        for (int i = 0; i < 3; ++i) near = near && at[i] - prev[i] >= -2 && at[i] - prev[i] <= 1;
        if (near)
          for (int i = 0; i < 3; ++i) step[i] = int(at[i] - prev[i]);
        else
          out.push_back(origin_word(cfg, bx * kShellBrick * unit, by * kShellBrick * unit, bz * kShellBrick * unit));
        out.push_back(brick_word(cfg, mask, step));
        std::copy(at, at + 3, prev);
        have = true;
      }
  return out;
}

}  // namespace voxcd::bench
