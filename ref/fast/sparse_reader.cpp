// A sparse map read one point at a time (detail/sparse_kernel.h, SparseReader): ref/pipeline.h's table_ref, read_cell,
// sparse_state, sub_cell and brick_nodes fused in 64-bit integers, and the interpolation as three exact linear
// interpolations (x, then y, then z; 128 bits for the last where IW > 62), as ref/fast/distance.cpp's scalar path does
// on a dense map. For the int64 and wide paths, and distance maps the vector kernel's copy cannot serve.
#include "voxcd/ref/fast/detail/sparse_kernel.h"

#include "voxcd/ref/sparse.h"

namespace voxcd::detail {

namespace {

template <class T>
inline T lerp(T a, T b, int64_t f, int wb) {
  return a * (T{1} << wb) + (b - a) * T(f);
}

}  // namespace

SparseReader::SparseReader(const DeviceConfig& cfg, const Job& j, const uint64_t* map)
    : map_(map),
      table_(j.map_base),
      brick_base_(j.brick_base),
      brick_units_(j.brick_units),
      uw_(unit_words(cfg)),
      bl_(cfg.BL),
      cw_(code_bits(cfg)),
      half_(cfg.MEMW / 2),
      cpw_(int(table_cells_per_word(cfg))),
      tf_(cfg.TF()),
      wb_(cfg.WB),
      sb_(cfg.SB),
      npw_(cfg.nodes_per_word()),
      distance_(cfg.distance()) {
  const CoarseDims c = coarse_dims(cfg, j);
  cx_ = c.c[0], cy_ = c.c[1];
  for (int code = 0; code < 16; ++code) units_[code] = uint32_t(code_units(cfg, uint8_t(code)));
}

int SparseReader::cell(const int64_t idx[3], uint8_t& code, uint64_t& first) const {
  const uint64_t t = (uint64_t(idx[0]) >> bl_) + cx_ * ((uint64_t(idx[1]) >> bl_) + cy_ * (uint64_t(idx[2]) >> bl_));
  const uint64_t w = map_[table_ + t / uint64_t(cpw_)];
  const uint32_t slot = uint32_t(t % uint64_t(cpw_));
  const uint64_t code_mask = (uint64_t{1} << cw_) - 1;
  uint64_t u = w >> half_;  // the rank (half <= 32)
  for (uint32_t s = 0; s < slot; ++s) u += units_[(w >> (cw_ * s)) & code_mask];
  code = uint8_t((w >> (cw_ * slot)) & code_mask);
  const uint32_t units = units_[code];
  if (units == 0) {  // uniform; a distance map's codes past the levels read as code 0
    if (distance_ && code != kCodeDeep) code = kCodeFar;
    return -1;
  }
  if (u + units > brick_units_) {  // past the job's bricks: code 0
    code = 0;
    return -1;
  }
  first = brick_base_ + u * uw_;
  return distance_ ? int(code) - kCodeLevel0 : 0;
}

uint8_t SparseReader::state(const int64_t idx[3]) const {
  uint8_t code = 0;
  uint64_t first = 0;
  if (cell(idx, code, first) < 0) return code;
  const uint64_t m = (uint64_t{1} << bl_) - 1, spw = uint64_t(half_);  // MEMW / 2 states a word
  const uint64_t i = (uint64_t(idx[0]) & m) | (uint64_t(idx[1]) & m) << bl_ | (uint64_t(idx[2]) & m) << (2 * bl_);
  return uint8_t((map_[first + i / spw] >> (2 * (i % spw))) & 3u);
}

int64_t SparseReader::distance(const int64_t idx[3], const uint64_t frac[3]) const {
  uint8_t code = 0;
  uint64_t first = 0;
  const int level = cell(idx, code, first);
  if (level < 0) {
    const int64_t q = code == kCodeDeep ? -(int64_t{1} << (sb_ - 1)) : (int64_t{1} << (sb_ - 1)) - 1;
    return int64_t(__int128(q) * (__int128(1) << (3 * wb_)));  // fits IW <= 64 bits
  }
  // The sub-cell: the voxel within the cell, then the fraction's top `level` bits; the weights the next WB bits.
  const uint64_t m = (uint64_t{1} << bl_) - 1, wmask = (uint64_t{1} << wb_) - 1;
  uint64_t X[3];
  int64_t f[3];
  for (int i = 0; i < 3; ++i) {
    X[i] = (uint64_t(idx[i]) & m) << level | (level ? frac[i] >> (tf_ - level) : 0);
    f[i] = int64_t((frac[i] >> (tf_ - level - wb_)) & wmask);
  }
  const uint64_t h_ext = ((uint64_t{1} << bl_) << level) / 2 + 1;
  const uint64_t vmask = (uint64_t{1} << sb_) - 1, sign = uint64_t{1} << (sb_ - 1);
  int64_t q[8];
  for (int c = 0; c < 8; ++c) {
    const uint64_t x = X[0] + (c & 1), y = X[1] + (c >> 1 & 1), z = X[2] + (c >> 2 & 1);
    const uint64_t h = (x >> 1) + h_ext * ((y >> 1) + h_ext * (z >> 1));
    const uint64_t bank = (x & 1) | (y & 1) << 1 | (z & 1) << 2;
    const uint64_t raw = (map_[first + 8 * (h / uint64_t(npw_)) + bank] >> (uint64_t(sb_) * (h % uint64_t(npw_)))) & vmask;
    q[c] = int64_t(raw ^ sign) - int64_t(sign);
  }
  const int64_t a0 = lerp<int64_t>(q[0], q[1], f[0], wb_), a1 = lerp<int64_t>(q[2], q[3], f[0], wb_);
  const int64_t a2 = lerp<int64_t>(q[4], q[5], f[0], wb_), a3 = lerp<int64_t>(q[6], q[7], f[0], wb_);
  const int64_t b0 = lerp<int64_t>(a0, a1, f[1], wb_), b1 = lerp<int64_t>(a2, a3, f[1], wb_);
  return sb_ + 3 * wb_ > 62 ? int64_t(lerp<__int128>(b0, b1, f[2], wb_)) : lerp<int64_t>(b0, b1, f[2], wb_);
}

}  // namespace voxcd::detail
