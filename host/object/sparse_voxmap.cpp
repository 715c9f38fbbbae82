#include "voxcd/host/object/sparse_voxmap.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace voxcd {

namespace {

constexpr uint64_t kLow = 0x5555555555555555ull;  // the low bit of every 2-bit code or state

uint8_t state_at(const uint64_t* words, uint64_t i) { return uint8_t((words[i >> 5] >> (2 * (i & 31))) & 3); }
void set_state(uint64_t* words, uint64_t i, uint8_t s) { words[i >> 5] |= uint64_t(s) << (2 * (i & 31)); }

}  // namespace

SparseVoxmap::SparseVoxmap(const GridPlacement& g, int bl) : grid_(g), bl_(bl) {
  if (bl < kMinBrickLog || bl > kMaxBrickLog)
    throw std::invalid_argument("sparse voxmap: BL = " + std::to_string(bl) + " is not " +
                                std::to_string(kMinBrickLog) + ".." + std::to_string(kMaxBrickLog));
  const uint64_t b = edge();
  for (int a = 0; a < 3; ++a) coarse_[a] = (uint64_t(g.dims[a]) + b - 1) / b;
  cells_ = coarse_[0] * coarse_[1] * coarse_[2];
  if (cells_ >> 32)
    throw std::invalid_argument("sparse voxmap: " + std::to_string(cells_) + " cells do not fit 32-bit ranks");
  codes_.assign((cells_ + 31) / 32, 0);
  rank_.assign(codes_.size(), 0);
}

std::vector<uint8_t> SparseVoxmap::codes() const {
  std::vector<uint8_t> c(cells_);
  for (uint64_t t = 0; t < cells_; ++t) c[t] = code(t);
  return c;
}

uint64_t SparseVoxmap::brick_index(uint64_t t) const {
  const uint64_t w = codes_[t >> 5];
  const uint64_t below = (uint64_t{1} << (2 * (t & 31))) - 1;
  return rank_[t >> 5] + uint64_t(__builtin_popcountll(w & (w >> 1) & kLow & below));
}

VoxelState SparseVoxmap::at(uint32_t x, uint32_t y, uint32_t z) const {
  const uint64_t t = (x >> bl_) + coarse_[0] * ((y >> bl_) + coarse_[1] * (z >> bl_));
  const uint8_t c = code(t);
  if (c != kCodeBrick) return VoxelState(c);
  const uint32_t m = edge() - 1;
  const uint64_t i = (x & m) + edge() * ((y & m) + uint64_t(edge()) * (z & m));
  return VoxelState(state_at(brick(brick_index(t)), i));
}

std::array<uint32_t, 3> SparseVoxmap::extent(uint64_t cx, uint64_t cy, uint64_t cz) const {
  const uint64_t c[3] = {cx, cy, cz};
  std::array<uint32_t, 3> e;
  for (int a = 0; a < 3; ++a) e[a] = uint32_t(std::min<uint64_t>(edge(), grid_.dims[a] - c[a] * edge()));
  return e;
}

std::array<uint64_t, 4> SparseVoxmap::code_counts() const {
  std::array<uint64_t, 4> n = {0, 0, 0, 0};
  for (uint64_t t = 0; t < cells_; ++t) ++n[code(t)];
  return n;
}

std::array<uint64_t, 4> SparseVoxmap::counts() const {
  std::array<uint64_t, 4> n = {0, 0, 0, 0};
  const uint64_t per = uint64_t{1} << (3 * bl_);
  uint64_t t = 0;
  for (uint64_t cz = 0; cz < coarse_[2]; ++cz)
    for (uint64_t cy = 0; cy < coarse_[1]; ++cy)
      for (uint64_t cx = 0; cx < coarse_[0]; ++cx, ++t) {
        const uint8_t c = code(t);
        const auto e = extent(cx, cy, cz);
        const uint64_t inside = uint64_t(e[0]) * e[1] * e[2];
        if (c != kCodeBrick) {
          n[c] += inside;
          continue;
        }
        // Voxels beyond the grid are 0: every other empty voxel is inside.
        const uint64_t* w = brick(brick_index(t));
        uint64_t s[4] = {0, 0, 0, 0};
        for (uint64_t k = 0; k < brick_words(); ++k) {
          const uint64_t lo = w[k] & kLow, hi = (w[k] >> 1) & kLow;
          s[kSurface] += uint64_t(__builtin_popcountll(lo & ~hi));
          s[kInterior] += uint64_t(__builtin_popcountll(hi & ~lo));
          s[kReserved] += uint64_t(__builtin_popcountll(lo & hi));
        }
        n[kSurface] += s[kSurface];
        n[kInterior] += s[kInterior];
        n[kReserved] += s[kReserved];
        n[kEmpty] += per - s[kSurface] - s[kInterior] - s[kReserved] - (per - inside);
      }
  return n;
}

uint64_t SparseVoxmap::table_bytes(int memw) const {
  const uint64_t cpw = uint64_t(memw) / 4;  // 2-bit codes in the low half of a word
  return (cells_ + cpw - 1) / cpw * uint64_t(memw) / 8;
}

SparseVoxmap::DeviceImage SparseVoxmap::device_image(const DeviceConfig& cfg) const {
  if (!cfg.sparse() || cfg.distance() || cfg.BL != bl_)
    throw std::invalid_argument("sparse voxmap: device " + cfg.to_string() + " is not a 2-bit sparse device of BL " +
                                std::to_string(bl_));
  const uint64_t uw = unit_words(cfg);
  if (uw == 0)
    throw std::invalid_argument("sparse voxmap: a brick of " + std::to_string(edge()) + "^3 states is narrower than " +
                                "MEMW = " + std::to_string(cfg.MEMW) + " bits");
  DeviceImage im;
  im.table = table_image(cfg, codes());
  im.brick_units = bricks();
  if (cfg.MEMW == 64) {
    im.bricks = bricks_;
    return im;
  }
  const uint64_t per = uint64_t(cfg.MEMW) / 2, states = uint64_t{1} << (3 * bl_);
  im.bricks.assign(bricks() * uw, 0);
  for (uint64_t b = 0; b < bricks(); ++b)
    for (uint64_t i = 0; i < states; ++i)
      im.bricks[b * uw + i / per] |= uint64_t(state_at(brick(b), i)) << (2 * (i % per));
  return im;
}

void SparseVoxmap::append(uint8_t c, const uint64_t* words) {
  if (appended_ >= cells_) throw std::logic_error("sparse voxmap: more cells appended than the grid has");
  const uint64_t t = appended_++;
  if (t % 32 == 0) rank_[t >> 5] = uint32_t(bricks());
  codes_[t >> 5] |= uint64_t(c & 3) << (2 * (t & 31));
  if (c == kCodeBrick) bricks_.insert(bricks_.end(), words, words + brick_words());
}

const char* SparseVoxmap::brick_problem(uint64_t t, const uint64_t* words) const {
  const uint64_t cx = t % coarse_[0], cy = t / coarse_[0] % coarse_[1], cz = t / (coarse_[0] * coarse_[1]);
  const auto e = extent(cx, cy, cz);
  const uint32_t b = edge();
  const uint8_t first = state_at(words, 0);
  bool uniform = true;
  for (uint32_t z = 0; z < b; ++z)
    for (uint32_t y = 0; y < b; ++y)
      for (uint32_t x = 0; x < b; ++x) {
        const uint8_t s = state_at(words, x + b * (y + uint64_t(b) * z));
        if (s == kReserved) return "a voxel in the reserved state 3";
        if ((x >= e[0] || y >= e[1] || z >= e[2]) && s != kEmpty) return "a voxel beyond the grid that is not empty";
        uniform = uniform && s == first;
      }
  return uniform ? "every voxel in one state (a uniform cell, not a brick)" : nullptr;
}

SparseVoxmap SparseVoxmap::from_dense(const Voxmap& vm, int bl) {
  SparseVoxmap sm(vm.grid(), bl);
  const uint32_t b = sm.edge();
  std::vector<uint64_t> words(sm.brick_words());
  for (uint64_t cz = 0; cz < sm.coarse_[2]; ++cz)
    for (uint64_t cy = 0; cy < sm.coarse_[1]; ++cy)
      for (uint64_t cx = 0; cx < sm.coarse_[0]; ++cx) {
        const auto e = sm.extent(cx, cy, cz);
        std::fill(words.begin(), words.end(), 0);
        const bool full = e[0] == b && e[1] == b && e[2] == b;
        const uint8_t first = uint8_t(vm.at(uint32_t(cx * b), uint32_t(cy * b), uint32_t(cz * b)));
        bool uniform = full || first == kEmpty;
        for (uint32_t z = 0; z < e[2]; ++z)
          for (uint32_t y = 0; y < e[1]; ++y)
            for (uint32_t x = 0; x < e[0]; ++x) {
              const uint8_t s = uint8_t(vm.at(uint32_t(cx * b + x), uint32_t(cy * b + y), uint32_t(cz * b + z)));
              set_state(words.data(), x + b * (y + uint64_t(b) * z), s);
              uniform = uniform && s == first;
            }
        sm.append(uniform ? first : kCodeBrick, words.data());
      }
  return sm;
}

Voxmap SparseVoxmap::to_dense() const {
  Voxmap vm(grid_);
  const uint32_t b = edge();
  uint64_t t = 0;
  for (uint64_t cz = 0; cz < coarse_[2]; ++cz)
    for (uint64_t cy = 0; cy < coarse_[1]; ++cy)
      for (uint64_t cx = 0; cx < coarse_[0]; ++cx, ++t) {
        const uint8_t c = code(t);
        if (c == kEmpty) continue;
        const auto e = extent(cx, cy, cz);
        const uint64_t* w = c == kCodeBrick ? brick(brick_index(t)) : nullptr;
        for (uint32_t z = 0; z < e[2]; ++z)
          for (uint32_t y = 0; y < e[1]; ++y)
            for (uint32_t x = 0; x < e[0]; ++x) {
              const uint8_t s = w ? state_at(w, x + b * (y + uint64_t(b) * z)) : c;
              if (s != kEmpty)
                vm.set(vm.index(uint32_t(cx * b + x), uint32_t(cy * b + y), uint32_t(cz * b + z)), VoxelState(s));
            }
      }
  return vm;
}

bool SparseVoxmap::operator==(const SparseVoxmap& o) const {
  return grid_.origin == o.grid_.origin && grid_.voxel == o.grid_.voxel && grid_.dims == o.grid_.dims &&
         bl_ == o.bl_ && codes_ == o.codes_ && bricks_ == o.bricks_;
}

}  // namespace voxcd
