// FastRunner on a distance voxmap (SB > 2). Three paths give ref/'s bits (docs/contract.md, "Distance voxmaps"):
//  - node quads: on the double path when an interpolated distance fits 51 bits (IW <= 51), SB <= 8 and the map's copy
//    in cell order (detail/node_quads.h, built here at the first job on the map) has fewer than 2^31 entries and fits
//    the runner's limit: a block of points at a time, transform, floor, bounds, the cell's 8 nodes by one 8-byte
//    read, the trilinear interpolation and the threshold test in one loop of doubles, where every value is an integer
//    below 2^53 and so exact (the 2-bit path's argument): fast/distance_quad_kernel.cpp.
//  - vector: otherwise on the double path when IW <= 51 and the map's node words fit int32 indices: the same loop with
//    the 8 node values from their parity banks (8 reads a point): fast/distance_kernel.cpp. Both for AVX-512, AVX2
//    with FMA or the baseline, chosen at run time; only the hits go on to records.
//  - scalar: otherwise, transform, floor and bounds in 64-bit integers (the double and int64 paths' accumulators fit
//    63 bits; the wide path takes ref/'s transform), and the interpolation as three exact linear interpolations,
//    a * 2^WB + (b - a) * f, x then y then z, in 64-bit integers and in 128 bits for the last step when IW > 62.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "voxcd/ref/fast/detail/sparse_copy.h"
#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/emit.h"
#include "voxcd/ref/fast/detail/node_quads.h"
#include "voxcd/ref/fast/detail/point_blocks.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/fast/detail/runner.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

// Exact a * 2^wb + (b - a) * f = a * (2^wb - f) + b * f.
template <class T>
inline T lerp(T a, T b, int64_t f, int wb) {
  return a * (T{1} << wb) + (b - a) * T(f);
}

constexpr size_t kDistanceBlock = 256;

// A dense distance map read one point at a time: its 8 node values from the parity banks and the interpolation as three
// exact linear interpolations, x, then y, then z, in 64-bit integers (128 bits for the last where IW > 62).
struct DenseNodes {
  const uint64_t* map;
  uint64_t hx, hy, vmask, sign, slot_mask;
  int npw_bits = 0, sb, wb;
  bool wide_d;

  DenseNodes(const DeviceConfig& cfg, const Job& j, const uint64_t* memory)
      : map(memory + j.map_base), hx((uint64_t{j.nx} >> 1) + 1), hy((uint64_t{j.ny} >> 1) + 1),
        vmask((uint64_t{1} << cfg.SB) - 1), sign(uint64_t{1} << (cfg.SB - 1)), sb(cfg.SB), wb(cfg.WB),
        wide_d(cfg.IW() > 62) {
    while ((1 << npw_bits) < cfg.nodes_per_word()) ++npw_bits;
    slot_mask = (uint64_t{1} << npw_bits) - 1;
  }
  // D at an inside point of cell idx with weights f.
  int64_t distance(const int64_t idx[3], const int64_t f[3]) const {
    int64_t q[8];  // q[dx | dy << 1 | dz << 2] for node (x + dx, y + dy, z + dz)
    for (int c = 0; c < 8; ++c) {
      const uint64_t X = uint64_t(idx[0]) + (c & 1), Y = uint64_t(idx[1]) + (c >> 1 & 1),
                     Z = uint64_t(idx[2]) + (c >> 2 & 1);
      const uint64_t h = (X >> 1) + hx * ((Y >> 1) + hy * (Z >> 1));
      const uint64_t bank = (X & 1) | (Y & 1) << 1 | (Z & 1) << 2;
      const uint64_t raw = (map[8 * (h >> npw_bits) + bank] >> (uint64_t(sb) * (h & slot_mask))) & vmask;
      q[c] = int64_t(raw ^ sign) - int64_t(sign);
    }
    const int64_t a0 = lerp<int64_t>(q[0], q[1], f[0], wb), a1 = lerp<int64_t>(q[2], q[3], f[0], wb);
    const int64_t a2 = lerp<int64_t>(q[4], q[5], f[0], wb), a3 = lerp<int64_t>(q[6], q[7], f[0], wb);
    const int64_t b0 = lerp<int64_t>(a0, a1, f[1], wb), b1 = lerp<int64_t>(a2, a3, f[1], wb);
    return wide_d ? int64_t(lerp<__int128>(b0, b1, f[2], wb)) : lerp<int64_t>(b0, b1, f[2], wb);
  }
};

// What the kernels need of job j (detail::DistanceJob); with `quads`, of that copy.
detail::DistanceJob distance_job(const DeviceConfig& cfg, const Job& j, const uint64_t* map,
                                 const detail::NodeQuads* quads) {
  detail::DistanceJob J;
  const int shift = cfg.TF() - cfg.WB;
  const double scale = std::ldexp(1.0, -shift);
  for (int i = 0; i < 9; ++i) J.m[i] = double(j.M[i / 3][i % 3]) * scale;
  for (int i = 0; i < 3; ++i) J.t[i] = double(j.t[i]) * scale;
  J.n[0] = j.nx, J.n[1] = j.ny, J.n[2] = j.nz;
  J.weight = std::ldexp(1.0, cfg.WB);
  J.inv_weight = std::ldexp(1.0, -cfg.WB);
  J.threshold = double(j.threshold);
  J.hx = int32_t(j.nx / 2 + 1), J.hy = int32_t(j.ny / 2 + 1);
  J.npw_bits = 0;
  while ((1 << J.npw_bits) < cfg.nodes_per_word()) ++J.npw_bits;
  J.sb = cfg.SB;
  J.sb_bits = 0;
  while ((1 << J.sb_bits) < J.sb) ++J.sb_bits;
  J.map = map + j.map_base;
  if (quads) {
    // The nodes' bias 2^(SB-1) times the weights' sum 2^(3 WB): 2^(IW-1), so threshold + bias is in [0, 2^IW).
    const int64_t bias = int64_t{1} << (cfg.SB - 1 + 3 * cfg.WB);
    J.quads = quads->entries.get();
    J.nx1 = double(j.nx) + 1;
    J.bias = double(bias);
    J.biased_threshold = double(j.threshold + bias);
  }
  return J;
}

}  // namespace

bool FastRunner::Impl::distance_vector(const Job& j) const {
  // Indices of node words as int32 and exact doubles throughout (see the file's comment).
  const uint64_t nodes = (uint64_t{j.nx} / 2 + 1) * (uint64_t{j.ny} / 2 + 1) * (uint64_t{j.nz} / 2 + 1);
  const int npw = cfg_.nodes_per_word(), sb = cfg_.SB;
  return path_ == Path::Double && cfg_.IW() <= 51 && (npw & (npw - 1)) == 0 && (sb & (sb - 1)) == 0 &&
         nodes < (uint64_t{1} << 31) &&
         8 * (nodes / uint64_t(npw) + 2) < (uint64_t{1} << 31);
}

const detail::NodeQuads* FastRunner::Impl::node_quads(const Job& j) const {
  // Exact doubles (IW <= 51: the biased distance too) and entries as int32 indices; then the limit.
  if (path_ != Path::Double || cfg_.IW() > 51 || cfg_.SB > 8) return nullptr;
  const uint64_t bytes = detail::node_quad_bytes(j.nx, j.ny, j.nz);
  if (bytes / 4 >= (uint64_t{1} << 31)) return nullptr;
  const std::lock_guard<std::mutex> lock(copies_mutex_);
  for (const auto& q : copies_)
    if (q->map_base == j.map_base && q->nx == j.nx && q->ny == j.ny && q->nz == j.nz) return q.get();
  if (copy_bytes_ + bytes > copy_limit_) return nullptr;
  copies_.push_back(std::make_unique<detail::NodeQuads>(detail::build_node_quads(
      map_.data() + j.map_base, j.map_base, voxcd::map_words(cfg_, j), j.nx, j.ny, j.nz, cfg_.SB, cfg_.nodes_per_word())));
  copy_bytes_ += bytes;
  return copies_.back().get();
}

void FastRunner::Impl::drop_node_quads(uint64_t first, uint64_t end) {
  const std::lock_guard<std::mutex> lock(copies_mutex_);
  for (size_t i = copies_.size(); i-- > 0;) {
    if (copies_[i]->map_base >= end || copies_[i]->map_end <= first) continue;
    copy_bytes_ -= copies_[i]->bytes();
    copies_.erase(copies_.begin() + std::ptrdiff_t(i));
  }
  for (size_t i = sparse_copies_.size(); i-- > 0;) {
    if (!sparse_copies_[i]->overlaps(first, end)) continue;
    copy_bytes_ -= sparse_copies_[i]->bytes();
    sparse_copies_.erase(sparse_copies_.begin() + std::ptrdiff_t(i));
  }
}

void FastRunner::Impl::set_node_copy_limit(uint64_t bytes) {
  copy_limit_ = bytes;
  drop_node_quads(0, UINT64_MAX);
}

uint64_t FastRunner::Impl::node_copy_bytes() const {
  const std::lock_guard<std::mutex> lock(copies_mutex_);
  return copy_bytes_;
}

void FastRunner::Impl::run_distance_vector(const Job& j, const detail::NodeQuads* quads, uint32_t begin, uint32_t end,
                                     HitColumns& hits, uint32_t& hit_count, const detail::ShellCursor* at) const {
  const detail::DistanceJob J = distance_job(cfg_, j, map_.data(), quads);
  uint8_t hit[kDistanceBlock];
  int32_t cx[kDistanceBlock], cy[kDistanceBlock], cz[kDistanceBlock];
  double dist[kDistanceBlock];
  const detail::DistanceBlockFn kernel = quads ? detail::distance_quad_block() : detail::distance_block();
  if (j.sparse_shell())
    return detail::sparse_shell_blocks(cfg_, shell_arrays(), j, begin, end, at, detail::PointBlocks::kInt32,
                                       kDistanceBlock, [&](uint32_t b, size_t n, const detail::BlockCoords& c) {
                                         const uint32_t count = kernel(c.x, c.y, c.z, n, J, hit, cx, cy, cz, dist);
                                         return detail::emit_distances(j, b, n, count, hit, cx, cy, cz, dist, hits,
                                                                       hit_count);
                                       });
  for (uint32_t b = begin; b < end; b += uint32_t(kDistanceBlock)) {  // a dense shell's words as they are
    const size_t n = std::min<size_t>(kDistanceBlock, end - b), base = size_t(j.shell_base) + b;
    const uint32_t count = kernel(&sx_[base], &sy_[base], &sz_[base], n, J, hit, cx, cy, cz, dist);
    if (detail::emit_distances(j, b, n, count, hit, cx, cy, cz, dist, hits, hit_count)) return;
  }
}

void FastRunner::Impl::run_distance_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits,
                                    uint32_t& hit_count, const detail::ShellCursor* at) const {
  if (const detail::NodeQuads* q = node_quads(j)) return run_distance_vector(j, q, begin, end, hits, hit_count, at);
  if (distance_vector(j)) return run_distance_vector(j, nullptr, begin, end, hits, hit_count, at);
  const int tf = cfg_.TF(), wb = cfg_.WB;
  const int64_t fmask = (int64_t{1} << wb) - 1;
  const int64_t n[3] = {int64_t(j.nx), int64_t(j.ny), int64_t(j.nz)};
  const DenseNodes nodes(cfg_, j, map_.data());
  // One point at a time: true when FIRST has its hit.
  auto point = [&](uint32_t k, const ShellWord& p) {
    int64_t idx[3], f[3];
    bool inside = true;
    if (path_ == Path::Wide) {
      const Transformed t = transform(cfg_, j, p);
      for (int i = 0; i < 3; ++i) {
        const Acc a = t.acc[i] >> tf;
        inside &= a >= 0 && a < Acc(n[i]);
        idx[i] = inside ? int64_t(a) : 0;
        f[i] = int64_t((t.acc[i] >> (tf - wb)) & Acc(fmask));
      }
    } else {
      for (int i = 0; i < 3; ++i) {
        const int64_t a = j.t[i] + j.M[i][0] * p.x + j.M[i][1] * p.y + j.M[i][2] * p.z;  // fits 63 bits
        idx[i] = a >> tf;
        inside &= idx[i] >= 0 && idx[i] < n[i];
        f[i] = (a >> (tf - wb)) & fmask;
      }
    }
    if (!inside) return false;
    const int64_t d = nodes.distance(idx, f);
    if (d > j.threshold) return false;
    ++hit_count;
    if (j.mode == Mode::Count) return false;
    hits.reserve_more(1);
    hits.put(k, uint32_t(idx[0]), uint32_t(idx[1]), uint32_t(idx[2]), 0, d);
    return j.mode == Mode::First;
  };
  detail::for_blocks(cfg_, shell_arrays(), j, begin, end, at, detail::PointBlocks::kWords, kDistanceBlock,
                     [&](uint32_t b, size_t count, const detail::BlockCoords& c) {
                       for (size_t k = 0; k < count; ++k)
                         if (point(b + uint32_t(k), c.w[k])) return true;
                       return false;
                     });
}

}  // namespace voxcd
