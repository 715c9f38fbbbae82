#include "tests/ref/sparse_images.h"

#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd::test {

namespace {

uint64_t ceil_div(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

void align_map(DeviceMemory& mem, uint64_t align) { mem.map.resize(ceil_div(mem.map.size(), align) * align, 0); }

// Appends the table of `codes` and room for their bricks; fills the placement.
SparsePlacement append_table(const DeviceConfig& cfg, const std::vector<uint8_t>& codes, DeviceMemory& mem) {
  const uint64_t align = cfg.distance() ? 8 : 1;
  SparsePlacement p;
  p.codes = codes;
  align_map(mem, align);
  p.map_base = uint32_t(mem.map.size());
  const std::vector<uint64_t> table = table_image(cfg, codes);
  mem.map.insert(mem.map.end(), table.begin(), table.end());
  align_map(mem, align);
  p.brick_base = uint32_t(mem.map.size());
  p.brick_units = uint32_t(table_units(cfg, codes));
  mem.map.resize(mem.map.size() + uint64_t(p.brick_units) * unit_words(cfg), 0);
  return p;
}

}  // namespace

Job sparse_map_job(const SparsePlacement& p, uint32_t nx, uint32_t ny, uint32_t nz) {
  Job j;
  j.sparse = kSparseMap;
  j.map_base = p.map_base;
  j.brick_base = p.brick_base;
  j.brick_units = p.brick_units;
  j.nx = nx, j.ny = ny, j.nz = nz;
  return j;
}

SparsePlacement append_sparse_states(const DeviceConfig& cfg, uint32_t nx, uint32_t ny, uint32_t nz,
                                     const std::vector<uint8_t>& states, DeviceMemory& mem) {
  const uint64_t B = brick_edge(cfg);
  const Job dims = sparse_map_job({}, nx, ny, nz);
  const CoarseDims c = coarse_dims(cfg, dims);
  auto state = [&](uint64_t x, uint64_t y, uint64_t z) -> int {
    return x < nx && y < ny && z < nz ? states[x + nx * (y + uint64_t(ny) * z)] : -1;
  };
  std::vector<uint8_t> codes(c.cells());
  for (uint64_t t = 0; t < codes.size(); ++t) {
    const uint64_t o[3] = {t % c.c[0] * B, t / c.c[0] % c.c[1] * B, t / (c.c[0] * c.c[1]) * B};
    int uniform = -1;
    bool mixed = false;
    for (uint64_t i = 0; i < B * B * B; ++i) {
      const int s = state(o[0] + i % B, o[1] + i / B % B, o[2] + i / (B * B));
      if (s < 0) continue;
      if (uniform < 0) uniform = s;
      mixed = mixed || s != uniform || s == kReserved;
    }
    codes[t] = mixed ? kCodeBrick : uint8_t(uniform < 0 ? 0 : uniform);
  }
  SparsePlacement p = append_table(cfg, codes, mem);
  uint64_t unit = 0;
  const uint64_t spw = uint64_t(cfg.states_per_word());
  for (uint64_t t = 0; t < codes.size(); ++t) {
    if (codes[t] != kCodeBrick) continue;
    const uint64_t first = p.brick_base + unit++ * unit_words(cfg);
    const uint64_t o[3] = {t % c.c[0] * B, t / c.c[0] % c.c[1] * B, t / (c.c[0] * c.c[1]) * B};
    for (uint64_t i = 0; i < B * B * B; ++i) {
      const int s = state(o[0] + i % B, o[1] + i / B % B, o[2] + i / (B * B));
      mem.map[first + i / spw] |= uint64_t(s < 0 ? 0 : s) << (2 * (i % spw));
    }
  }
  return p;
}

SparsePlacement append_sparse_field(const DeviceConfig& cfg, uint32_t nx, uint32_t ny, uint32_t nz,
                                    const std::function<int64_t(double, double, double)>& q,
                                    const std::function<int(uint64_t, uint64_t, uint64_t)>& level,
                                    DeviceMemory& mem) {
  const uint64_t B = brick_edge(cfg);
  const CoarseDims c = coarse_dims(cfg, sparse_map_job({}, nx, ny, nz));
  std::vector<uint8_t> codes(c.cells());
  for (uint64_t t = 0; t < codes.size(); ++t) {
    const int l = level(t % c.c[0], t / c.c[0] % c.c[1], t / (c.c[0] * c.c[1]));
    codes[t] = l == -1 ? kCodeFar : l == -2 ? kCodeDeep : uint8_t(kCodeLevel0 + l);
  }
  SparsePlacement p = append_table(cfg, codes, mem);
  const uint64_t vmask = (uint64_t{1} << cfg.SB) - 1;
  uint64_t unit = 0;
  for (uint64_t t = 0; t < codes.size(); ++t) {
    const int l = code_level(cfg, codes[t]);
    if (l < 0) continue;
    const Cell cell{codes[t], l, p.brick_base + unit * unit_words(cfg)};
    unit += level_units(cfg, l);
    const double o[3] = {double(t % c.c[0] * B), double(t / c.c[0] % c.c[1] * B), double(t / (c.c[0] * c.c[1]) * B)};
    const uint64_t n = (B << l) + 1;
    const double s = 1.0 / double(uint64_t{1} << l);
    for (uint64_t Z = 0; Z < n; ++Z)
      for (uint64_t Y = 0; Y < n; ++Y)
        for (uint64_t X = 0; X < n; ++X) {
          const NodeAddress a = brick_node_address(cfg, cell, X, Y, Z);
          const uint64_t v = uint64_t(q(o[0] + double(X) * s, o[1] + double(Y) * s, o[2] + double(Z) * s)) & vmask;
          mem.map[a.word] |= v << (uint64_t(cfg.SB) * a.slot);
        }
  }
  return p;
}

uint32_t append_dense_field(const DeviceConfig& cfg, uint32_t nx, uint32_t ny, uint32_t nz,
                            const std::function<int64_t(double, double, double)>& q, DeviceMemory& mem) {
  align_map(mem, 8);
  Job j;
  j.map_base = uint32_t(mem.map.size());
  j.nx = nx, j.ny = ny, j.nz = nz;
  mem.map.resize(mem.map.size() + map_words(cfg, j), 0);
  const uint64_t vmask = (uint64_t{1} << cfg.SB) - 1;
  for (uint64_t Z = 0; Z <= nz; ++Z)
    for (uint64_t Y = 0; Y <= ny; ++Y)
      for (uint64_t X = 0; X <= nx; ++X) {
        const NodeAddress a = node_address(cfg, j, X, Y, Z);
        mem.map[a.word] |= (uint64_t(q(double(X), double(Y), double(Z))) & vmask) << (uint64_t(cfg.SB) * a.slot);
      }
  return j.map_base;
}

}  // namespace voxcd::test
