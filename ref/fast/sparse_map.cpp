// FastRunner on a sparse map (docs/contract.md, "Sparse voxmaps and shells"; fast/fast.h): the 2-bit kernel on the
// contract's layout (fast/sparse_kernel.cpp) or the distance kernel on the map's node-quad copy
// (fast/sparse_distance_kernel.cpp) on the double path; one point at a time with 64-bit integers elsewhere
// (fast/sparse_reader.cpp), the transform as the dense paths make it.
#include <mutex>

#include "voxcd/ref/fast/detail/sparse_copy.h"
#include "voxcd/ref/fast/detail/emit.h"
#include "voxcd/ref/fast/detail/point_blocks.h"
#include "voxcd/ref/fast/detail/sparse_kernel.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/fast/detail/runner.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {
constexpr size_t kSparseBlock = 256;
}  // namespace

const char* FastRunner::sparse_kernel() { return detail::sparse_block_name(); }
const char* FastRunner::sparse_distance_kernel() { return detail::brick_quad_block_name(); }

const detail::SparseCopy* FastRunner::Impl::sparse_copy(const Job& j) const {
  // int32 voxels and cells (below 2^31 voxels); on a distance map exact doubles (IW <= 51) and node bytes (SB <= 8);
  // then the limit.
  if (path_ != Path::Double || j.voxels() >= (uint64_t{1} << 31)) return nullptr;
  if (cfg_.distance() && (cfg_.IW() > 51 || cfg_.SB > 8)) return nullptr;
  const std::lock_guard<std::mutex> lock(copies_mutex_);
  for (const auto& q : sparse_copies_)
    if (q->serves(j)) return q.get();
  const uint64_t bytes = detail::sparse_copy_bytes(cfg_, map_, j);
  if (bytes == UINT64_MAX || copy_bytes_ + bytes > copy_limit_) return nullptr;
  sparse_copies_.push_back(std::make_unique<detail::SparseCopy>(detail::build_sparse_copy(cfg_, map_, j)));
  copy_bytes_ += bytes;
  return sparse_copies_.back().get();
}

void FastRunner::Impl::run_sparse_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& hit_count,
                                  const detail::ShellCursor* at) const {
  const detail::ShellArrays arrays = shell_arrays();
  int32_t cx[kSparseBlock], cy[kSparseBlock], cz[kSparseBlock];
  const bool vector = path_ == Path::Double && j.voxels() < (uint64_t{1} << 31);
  if (vector && !cfg_.distance()) {
    detail::SparseJob S = detail::sparse_job(cfg_, j, map_.data(), tf_scale_);
    const detail::SparseCopy* copy = sparse_copy(j);
    if (copy) S.entries = copy->entries.get();
    const detail::SparseBlockFn kernel = copy ? detail::sparse_entry_block() : detail::sparse_block();
    uint8_t state[kSparseBlock];
    return detail::for_blocks(cfg_, arrays, j, begin, end, at, detail::PointBlocks::kInt32, kSparseBlock,
                              [&](uint32_t b, size_t n, const detail::BlockCoords& c) {
                                const uint32_t count = kernel(c.x, c.y, c.z, n, S, cx, cy, cz, state);
                                if (count == 0) return false;
                                if (j.mode == Mode::Count) return hit_count += count, false;
                                return detail::emit_cells(j, b, n, cx, cy, cz, state, count, hits, hit_count);
                              });
  }
  if (const detail::SparseCopy* q = cfg_.distance() ? sparse_copy(j) : nullptr) {
    const detail::BrickQuadJob J = detail::brick_quad_job(cfg_, j, *q);
    const detail::BrickQuadBlockFn kernel = detail::brick_quad_block();
    uint8_t hit[kSparseBlock];
    double dist[kSparseBlock];
    return detail::for_blocks(cfg_, arrays, j, begin, end, at, detail::PointBlocks::kInt32, kSparseBlock,
                              [&](uint32_t b, size_t n, const detail::BlockCoords& c) {
                                const uint32_t count = kernel(c.x, c.y, c.z, n, J, hit, cx, cy, cz, dist);
                                return detail::emit_distances(j, b, n, count, hit, cx, cy, cz, dist, hits, hit_count);
                              });
  }
  run_sparse_points(j, begin, end, hits, hit_count, at);
}

void FastRunner::Impl::run_sparse_points(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& hit_count,
                                   const detail::ShellCursor* at) const {
  const detail::SparseReader reader(cfg_, j, map_.data());
  const int tf = cfg_.TF();
  const uint64_t frac_mask = (uint64_t{1} << tf) - 1;
  const int64_t n[3] = {int64_t(j.nx), int64_t(j.ny), int64_t(j.nz)};
  // One point: true when FIRST has its hit.
  auto point = [&](uint32_t k, const ShellWord& p) {
    int64_t idx[3];
    uint64_t frac[3];
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
      if (path_ == Path::Wide) {
        const Acc a = Acc(j.t[i]) + Acc(j.M[i][0]) * p.x + Acc(j.M[i][1]) * p.y + Acc(j.M[i][2]) * p.z;
        const Acc v = a >> tf;
        inside &= v >= 0 && v < Acc(n[i]);
        idx[i] = inside ? int64_t(v) : 0;
        frac[i] = uint64_t(a) & frac_mask;
      } else {
        const int64_t a = j.t[i] + j.M[i][0] * p.x + j.M[i][1] * p.y + j.M[i][2] * p.z;  // fits 63 bits
        idx[i] = a >> tf;
        inside &= idx[i] >= 0 && idx[i] < n[i];
        frac[i] = uint64_t(a) & frac_mask;
      }
    }
    if (!inside) return false;
    uint8_t state = 0;
    int64_t d = 0;
    if (cfg_.distance()) {
      d = reader.distance(idx, frac);
      if (d > j.threshold) return false;
    } else {
      state = reader.state(idx);
      if (!((j.hit_mask >> state) & 1u)) return false;
    }
    ++hit_count;
    if (j.mode == Mode::Count) return false;
    hits.reserve_more(1);
    hits.put(k, uint32_t(idx[0]), uint32_t(idx[1]), uint32_t(idx[2]), state, d);
    return j.mode == Mode::First;
  };
  detail::for_blocks(cfg_, shell_arrays(), j, begin, end, at, detail::PointBlocks::kWords, kSparseBlock,
                     [&](uint32_t b, size_t count, const detail::BlockCoords& c) {
                       for (size_t k = 0; k < count; ++k)
                         if (point(b + uint32_t(k), c.w[k])) return true;
                       return false;
                     });
}

}  // namespace voxcd
