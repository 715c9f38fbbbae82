#include "voxcd/ref/detail/vector_gen_sparse.h"

#include <algorithm>
#include <cmath>

#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd::detail {

namespace {

uint64_t uni(std::mt19937_64& rng, uint64_t lo, uint64_t hi) {
  return std::uniform_int_distribution<uint64_t>(lo, hi)(rng);
}
bool chance(std::mt19937_64& rng, double p) { return std::bernoulli_distribution(p)(rng); }

// A sphere in the map's voxel coordinates: its centre and radius.
struct Sphere {
  double c[3], r;
  double distance(double x, double y, double z) const {
    return std::sqrt((x - c[0]) * (x - c[0]) + (y - c[1]) * (y - c[1]) + (z - c[2]) * (z - c[2])) - r;
  }
};

// The codes of a 2-bit map's cells: 0 random (every code); 1 a sphere (uniform empty outside, uniform interior
// inside, bricks across its surface); 2 every cell a brick; 3 mostly uniform (surface too) with a few bricks;
// 4 bricks and uniform interior.
uint8_t state_code(std::mt19937_64& rng, int pattern, const Sphere& s, const double cell_c[3], double half) {
  switch (pattern) {
    case 0: return uint8_t(uni(rng, 0, 3));
    case 1: {
      const double d = s.distance(cell_c[0], cell_c[1], cell_c[2]);
      return d > half * 1.8 ? uint8_t(kEmpty) : d < -half * 1.8 ? uint8_t(kInterior) : kCodeBrick;
    }
    case 2: return kCodeBrick;
    case 3: return chance(rng, 0.15) ? kCodeBrick : uint8_t(uni(rng, 0, 2));
    default: return chance(rng, 0.5) ? kCodeBrick : uint8_t(kInterior);
  }
}

uint8_t state_in_brick(std::mt19937_64& rng, int pattern, const Sphere& s, double x, double y, double z) {
  switch (pattern) {
    case 1: {
      const double d = s.distance(x, y, z);
      return uint8_t(std::fabs(d) < 0.87 ? kSurface : d < 0 ? kInterior : kEmpty);
    }
    case 2: return uint8_t((int64_t(x) + int64_t(y) + int64_t(z)) % 2 ? kSurface : kEmpty);
    case 4: return uint8_t(chance(rng, 0.5) ? kInterior : kReserved);
    default: return uint8_t(uni(rng, 0, 3));
  }
}

// A distance map's codes: 0 random (invalid codes and every level); 1 a sphere's field (uniform far outside and far
// inside, bricks of level 0 or 1 across the band, a few deeper); 2 every cell a brick of alternating extremes;
// 3 and 4 like 1 with more levels.
uint8_t distance_code(std::mt19937_64& rng, int pattern, const Sphere& s, const double cell_c[3], double half,
                      double band) {
  if (pattern == 0) return uint8_t(chance(rng, 0.1) ? uni(rng, 6, 15) : uni(rng, 0, kCodeLevel0 + 2));
  if (pattern == 2) return kCodeLevel0;
  const double d = s.distance(cell_c[0], cell_c[1], cell_c[2]);
  if (d > band + half * 1.8) return kCodeFar;
  if (d < -band - half * 1.8) return kCodeDeep;
  const uint64_t deepest = pattern == 1 ? 1 : 2;
  return uint8_t(kCodeLevel0 + (chance(rng, 0.7) ? 0 : uni(rng, 1, deepest)));
}

int64_t node_value(const DeviceConfig& cfg, std::mt19937_64& rng, int pattern, const Sphere& s, double x, double y,
                   double z, double step) {
  const int64_t qmax = (int64_t{1} << (cfg.SB - 1)) - 1, qmin = -qmax - 1;
  switch (pattern) {
    case 0: return std::uniform_int_distribution<int64_t>(qmin, qmax)(rng);
    case 2: return (int64_t(x * 2) + int64_t(y * 2) + int64_t(z * 2)) % 2 ? qmax : qmin;
    default: return std::clamp<int64_t>(int64_t(std::llround(s.distance(x, y, z) * step)), qmin, qmax);
  }
}

// Writes every brick of the map at plan.brick_base (2-bit states or distance nodes).
void fill_bricks(const DeviceConfig& cfg, std::mt19937_64& rng, int pattern, const SparseMapPlan& plan,
                 const std::vector<uint8_t>& codes, const Sphere& s, std::vector<uint64_t>& map) {
  const uint64_t B = brick_edge(cfg);
  const uint64_t cx = (plan.nx + B - 1) / B, cy = (plan.ny + B - 1) / B;
  const double step = cfg.distance() ? std::max(1.0, double((int64_t{1} << (cfg.SB - 1)) - 1) / 4.0) : 1.0;
  const uint64_t vmask = (uint64_t{1} << cfg.SB) - 1;
  uint64_t unit = 0;
  for (uint64_t t = 0; t < codes.size(); ++t) {
    const int level = code_level(cfg, codes[t]);
    if (level < 0) continue;
    const Cell cell{codes[t], level, plan.brick_base + unit * unit_words(cfg)};
    unit += code_units(cfg, codes[t]);
    const double o[3] = {double((t % cx) * B), double((t / cx % cy) * B), double(t / (cx * cy) * B)};
    if (!cfg.distance()) {
      for (uint64_t i = 0; i < B * B * B; ++i) {
        const uint64_t st = state_in_brick(rng, pattern, s, o[0] + double(i % B) + 0.5, o[1] + double(i / B % B) + 0.5,
                                           o[2] + double(i / (B * B)) + 0.5);
        const uint64_t w = cell.first + i / uint64_t(cfg.states_per_word()), sh = 2 * (i % uint64_t(cfg.states_per_word()));
        map[w] = (map[w] & ~(uint64_t{3} << sh)) | (st << sh);
      }
      continue;
    }
    const uint64_t n = (B << level) + 1;
    const double unit_len = 1.0 / double(uint64_t{1} << level);
    for (uint64_t Z = 0; Z < n; ++Z)
      for (uint64_t Y = 0; Y < n; ++Y)
        for (uint64_t X = 0; X < n; ++X) {
          const int64_t q = node_value(cfg, rng, pattern, s, o[0] + double(X) * unit_len, o[1] + double(Y) * unit_len,
                                       o[2] + double(Z) * unit_len, step);
          const NodeAddress a = brick_node_address(cfg, cell, X, Y, Z);
          const uint64_t sh = uint64_t(cfg.SB) * a.slot;
          map[a.word] = (map[a.word] & ~(vmask << sh)) | ((uint64_t(q) & vmask) << sh);
        }
  }
}

}  // namespace

bool add_sparse_map(const DeviceConfig& cfg, std::mt19937_64& rng, uint32_t nx, uint32_t ny, uint32_t nz,
                    int pattern, uint64_t next, uint64_t limit, std::vector<uint64_t>& map, SparseMapPlan& plan) {
  const uint64_t B = brick_edge(cfg), align = cfg.distance() ? 8 : 1;
  plan = SparseMapPlan{};
  plan.nx = nx, plan.ny = ny, plan.nz = nz;
  Job j;
  j.nx = nx, j.ny = ny, j.nz = nz;
  const CoarseDims c = coarse_dims(cfg, j);
  const Sphere s{{nx / 2.0 + 0.3, ny / 2.0 - 0.2, nz / 2.0 + 0.1}, std::max(0.7, std::min({nx, ny, nz}) / 3.0)};
  const double half = double(B) / 2.0, band = 4.0;
  std::vector<uint8_t> codes(c.cells());
  for (uint64_t t = 0; t < codes.size(); ++t) {
    const double cc[3] = {double((t % c.c[0]) * B) + half, double((t / c.c[0] % c.c[1]) * B) + half,
                          double(t / (c.c[0] * c.c[1]) * B) + half};
    codes[t] = cfg.distance() ? distance_code(rng, pattern, s, cc, half, band) : state_code(rng, pattern, s, cc, half);
  }
  // Deep levels take many words: fall back to shallower ones until the map fits in a quarter of what is left.
  const uint64_t room = (limit > next ? limit - next : 0) / 4;
  for (int level = kMaxLevel; level > 0 && table_units(cfg, codes) * unit_words(cfg) > room; --level)
    for (uint8_t& code : codes)
      if (code_level(cfg, code) == level) code = uint8_t(code - 1);
  std::vector<uint64_t> table;
  try {
    table = table_image(cfg, codes);
  } catch (const std::invalid_argument&) {
    return false;  // a rank that does not fit MEMW/2 bits: no such map on this device
  }
  const uint64_t units = table_units(cfg, codes);
  plan.map_base = uint32_t((next + align - 1) / align * align);
  const uint64_t bricks = (plan.map_base + table.size() + uni(rng, 0, 2) * align + align - 1) / align * align;
  const uint64_t end = bricks + units * unit_words(cfg);
  if (end > limit || !fits_unsigned(bricks, cfg.MAW)) return false;
  plan.brick_base = uint32_t(bricks);
  // Pattern 3: the job sees fewer units than the table refers to (those cells read as code 0).
  plan.brick_units = uint32_t(pattern == 3 && units > 0 ? uni(rng, 0, units - 1) : units);
  if (map.size() < end) map.resize(end);
  std::copy(table.begin(), table.end(), map.begin() + std::ptrdiff_t(plan.map_base));
  fill_bricks(cfg, rng, pattern, plan, codes, s, map);
  return true;
}

namespace {

// A chain of brick words through the bricks of a sphere's surface (radius r shell voxels), in z, y, x order: a
// step where the next brick is a neighbour (-2..1 per axis), an origin word where it is not.
std::vector<ShellWord> sphere_chain(const DeviceConfig& cfg, std::mt19937_64& rng, size_t words) {
  const double r = double(uni(rng, 3, 30));
  const int64_t nb = int64_t(std::ceil(2 * r / kShellBrick)) + 1;
  std::vector<ShellWord> out;
  int64_t prev[3] = {0, 0, 0};
  bool have = false;
  const int64_t unit = int64_t{1} << cfg.PF;
  for (int64_t bz = 0; bz < nb && out.size() < words; ++bz)
    for (int64_t by = 0; by < nb && out.size() < words; ++by)
      for (int64_t bx = 0; bx < nb && out.size() < words; ++bx) {
        uint64_t mask = 0;
        for (int i = 0; i < 64; ++i) {
          const double p[3] = {double(bx * kShellBrick + (i & 3)) + 0.5 - r, double(by * kShellBrick + (i >> 2 & 3)) + 0.5 - r,
                               double(bz * kShellBrick + (i >> 4)) + 0.5 - r};
          if (std::fabs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - r) < 0.75) mask |= uint64_t{1} << i;
        }
        if (!mask) continue;
        const int64_t b[3] = {bx, by, bz};
        int step[3];
        bool near = have;
        for (int i = 0; i < 3; ++i) near = near && b[i] - prev[i] >= -2 && b[i] - prev[i] <= 1;
        if (!near) {
          out.push_back(origin_word(cfg, bx * kShellBrick * unit, by * kShellBrick * unit, bz * kShellBrick * unit));
          for (int& v : step) v = 0;
        } else {
          for (int i = 0; i < 3; ++i) step[i] = int(b[i] - prev[i]);
        }
        if (out.size() < words) out.push_back(brick_word(cfg, mask, step));
        for (int i = 0; i < 3; ++i) prev[i] = b[i];
        have = true;
      }
  return out;
}

}  // namespace

std::vector<ShellWord> sparse_shell_block(const DeviceConfig& cfg, std::mt19937_64& rng, int pattern, size_t words) {
  if (pattern == 1) return sphere_chain(cfg, rng, words);
  std::vector<ShellWord> out;
  const int64_t unit = int64_t{1} << cfg.PF;
  const int64_t omax = (int64_t{1} << (cfg.PW - 2)) - 1;  // z has PW - 1 bits
  for (size_t k = 0; k < words; ++k) {
    if (k == 0 || chance(rng, pattern == 3 ? 0.4 : 0.08)) {
      int64_t o[3];
      for (int64_t& v : o) {
        if (pattern == 2)
          v = chance(rng, 0.5) ? omax - int64_t(uni(rng, 0, 3)) * unit : -omax - 1 + int64_t(uni(rng, 0, 3)) * unit;
        else
          v = (int64_t(uni(rng, 0, 12)) - 3) * kShellBrick * unit + int64_t(uni(rng, 0, 2)) * unit / 2;
      }
      out.push_back(origin_word(cfg, o[0], o[1], o[2]));
      continue;
    }
    int step[3];
    for (int& v : step) v = int(uni(rng, 0, 3)) - 2;
    uint64_t mask = 0;
    switch (pattern == 2 ? uni(rng, 3, 5) : uni(rng, 0, 5)) {
      case 0: mask = 0; break;
      case 1: mask = uint64_t{1} << uni(rng, 0, 63); break;
      case 2: mask = ~uint64_t{0}; break;
      case 3: mask = std::uniform_int_distribution<uint64_t>()(rng); break;
      default:
        for (int i = 0; i < 64; ++i)
          if (chance(rng, 0.25)) mask |= uint64_t{1} << i;
        break;
    }
    out.push_back(brick_word(cfg, mask, step));
  }
  return out;
}

}  // namespace voxcd::detail
