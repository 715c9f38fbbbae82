// The copy of a sparse map with its table resolved (detail/sparse_copy.h): every cell's code read as ref/'s read_cell
// reads it (so a reference past the job's units, and a distance map's codes 6..15, are code 0); on a distance map the
// uniform cells pointed at two uniform bricks of level 0 and every brick's nodes laid out as node quads by the dense
// map's copy (fill_node_quads: a brick of level l is laid out as a dense distance map of B 2^l cells per axis).
#include "voxcd/ref/fast/detail/sparse_copy.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd::detail {

namespace {

constexpr uint64_t kEntryLimit = uint64_t{1} << 30;

// Calls f(t, cell) for every coarse cell of job j's table, in table order.
template <class F>
void for_each_cell(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& j, F&& f) {
  const uint64_t cells = coarse_dims(cfg, j).cells(), cpw = table_cells_per_word(cfg);
  for (uint64_t t = 0; t < cells; ++t) f(t, read_cell(cfg, map, j, TableRef{j.map_base + t / cpw, uint32_t(t % cpw)}));
}

// The quads of a brick of level l: (n + 1) n^2, n = B 2^l.
uint64_t brick_quad_count(const DeviceConfig& cfg, int level) {
  const uint64_t n = brick_edge(cfg) << level;
  return (n + 1) * n * n;
}

}  // namespace

uint64_t sparse_copy_bytes(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& j) {
  if (!cfg.distance()) return coarse_dims(cfg, j).cells() * sizeof(uint32_t);
  uint64_t quads = 2 * brick_quad_count(cfg, 0);  // the two uniform bricks
  for_each_cell(cfg, map, j, [&](uint64_t, const Cell& c) {
    if (c.level >= 0) quads += brick_quad_count(cfg, c.level);
  });
  if (quads >= kEntryLimit) return UINT64_MAX;
  return (quads + coarse_dims(cfg, j).cells()) * sizeof(uint32_t);
}

SparseCopy build_sparse_copy(const DeviceConfig& cfg, const std::vector<uint64_t>& map, const Job& j) {
  SparseCopy q;
  q.map_base = j.map_base, q.brick_base = j.brick_base, q.brick_units = j.brick_units;
  q.nx = j.nx, q.ny = j.ny, q.nz = j.nz;
  q.table_end = j.map_base + map_words(cfg, j);
  q.brick_end = j.brick_base + brick_words(cfg, j);
  q.cells = size_t(coarse_dims(cfg, j).cells());
  q.count = size_t(sparse_copy_bytes(cfg, map, j) / sizeof(uint32_t)) - q.cells;
  q.entries.reset(allocate_quads(q.cells));
  if (!cfg.distance()) {
    for_each_cell(cfg, map, j, [&](uint64_t t, const Cell& c) {
      q.entries[t] = c.level < 0 ? kUniformCell | c.code : uint32_t(c.first);
    });
    return q;
  }
  q.quads.reset(allocate_quads(q.count));
  // The uniform bricks: far (every node qmax, stored as 2^SB - 1) at 0, deep (qmin, stored as 0) after it.
  const uint64_t uniform = brick_quad_count(cfg, 0);
  const uint32_t far = (uint32_t{1} << cfg.SB) - 1;
  std::fill(q.quads.get(), q.quads.get() + uniform, far * 0x01010101u);
  std::fill(q.quads.get() + uniform, q.quads.get() + 2 * uniform, 0u);
  uint64_t next = 2 * uniform;
  for_each_cell(cfg, map, j, [&](uint64_t t, const Cell& c) {
    if (c.level < 0) {
      q.entries[t] = c.code == kCodeDeep ? uint32_t(uniform) : 0u;
      return;
    }
    const uint32_t n = uint32_t(brick_edge(cfg) << c.level);
    fill_node_quads(map.data() + c.first, n, n, n, cfg.SB, cfg.nodes_per_word(), q.quads.get() + next);
    q.entries[t] = uint32_t(c.level) << 30 | uint32_t(next);
    next += brick_quad_count(cfg, c.level);
  });
  return q;
}

BrickQuadJob brick_quad_job(const DeviceConfig& cfg, const Job& j, const SparseCopy& q) {
  BrickQuadJob J;
  const double scale = std::ldexp(1.0, -(cfg.TF() - cfg.WB));
  for (int i = 0; i < 9; ++i) J.m[i] = double(j.M[i / 3][i % 3]) * scale;
  for (int i = 0; i < 3; ++i) J.t[i] = double(j.t[i]) * scale;
  J.n[0] = j.nx, J.n[1] = j.ny, J.n[2] = j.nz;
  J.weight = std::ldexp(1.0, cfg.WB);
  J.inv_weight = std::ldexp(1.0, -cfg.WB);
  for (int l = 0; l < 8; ++l) {
    const int level = std::min(l, kMaxLevel);  // entries hold levels 0..3 only
    J.level_scale[l] = std::ldexp(1.0, level);
    J.edge[l] = int32_t(brick_edge(cfg) << level);
  }
  const CoarseDims c = coarse_dims(cfg, j);
  J.cx = int32_t(c.c[0]), J.cy = int32_t(c.c[1]);
  J.bl = cfg.BL;
  J.entries = q.entries.get();
  J.quads = q.quads.get();
  const int64_t bias = int64_t{1} << (cfg.SB - 1 + 3 * cfg.WB);
  J.bias = double(bias);
  J.biased_threshold = double(j.threshold + bias);
  return J;
}

}  // namespace voxcd::detail
