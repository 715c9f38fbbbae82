// The node-quad copy of a distance voxmap (detail/node_quads.h), built plane by plane from the parity banks.
#include "voxcd/ref/fast/detail/node_quads.h"

#include <new>
#include <vector>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace voxcd::detail {

namespace {

// Decodes node plane Z (nodes (X, Y, Z), X in [0, nx], Y in [0, ny]) into `plane` as q + 2^(SB-1), row-major in X.
struct PlaneDecoder {
  const uint64_t* map;
  uint64_t hx, hy;  // the half-grid's extents
  uint32_t nx, ny;
  int sb;
  uint64_t npw;

  void operator()(uint32_t Z, std::vector<uint8_t>& plane) const {
    const uint64_t vmask = (uint64_t{1} << sb) - 1, sign = uint64_t{1} << (sb - 1);
    const bool pow2 = (npw & (npw - 1)) == 0;
    int npw_bits = 0;
    while ((uint64_t{1} << npw_bits) < npw) ++npw_bits;
    uint8_t* out = plane.data();
    for (uint32_t Y = 0; Y <= ny; ++Y) {
      const uint64_t row = hx * ((Y >> 1) + hy * (Z >> 1));
      const uint64_t bank_yz = (Y & 1u) << 1 | (Z & 1u) << 2;
      for (uint32_t X = 0; X <= nx; ++X) {
        const uint64_t h = (X >> 1) + row;
        const uint64_t w = pow2 ? h >> npw_bits : h / npw, slot = pow2 ? h & (npw - 1) : h % npw;
        const uint64_t raw = (map[8 * w + (bank_yz | (X & 1u))] >> (uint64_t(sb) * slot)) & vmask;
        *out++ = uint8_t(raw ^ sign);  // q + 2^(SB-1)
      }
    }
  }
};

}  // namespace

uint32_t* allocate_quads(size_t n) {
  constexpr size_t kHuge = size_t{1} << 21;
  const size_t bytes = n * sizeof(uint32_t);
  void* p = nullptr;
  if (bytes >= kHuge) {
    p = std::aligned_alloc(kHuge, (bytes + kHuge - 1) / kHuge * kHuge);
#ifdef __linux__
    if (p) madvise(p, (bytes + kHuge - 1) / kHuge * kHuge, MADV_HUGEPAGE);  // advice only: 4 KiB pages work too
#endif
  } else {
    p = std::malloc(bytes ? bytes : 1);
  }
  if (!p) throw std::bad_alloc();
  return static_cast<uint32_t*>(p);
}

uint64_t node_quad_bytes(uint32_t nx, uint32_t ny, uint32_t nz) {
  return (uint64_t{nx} + 1) * ny * nz * sizeof(uint32_t);
}

NodeQuads build_node_quads(const uint64_t* map, uint64_t map_base, uint64_t map_words, uint32_t nx, uint32_t ny,
                           uint32_t nz, int sb, int nodes_per_word) {
  NodeQuads q;
  q.map_base = map_base;
  q.map_end = map_base + map_words;
  q.nx = nx, q.ny = ny, q.nz = nz;
  q.count = size_t(node_quad_bytes(nx, ny, nz) / sizeof(uint32_t));
  q.entries.reset(allocate_quads(q.count));
  fill_node_quads(map, nx, ny, nz, sb, nodes_per_word, q.entries.get());
  return q;
}

void fill_node_quads(const uint64_t* map, uint32_t nx, uint32_t ny, uint32_t nz, int sb, int nodes_per_word,
                     uint32_t* out) {
  const PlaneDecoder decode{map, uint64_t{nx >> 1} + 1, uint64_t{ny >> 1} + 1, nx, ny, sb, uint64_t(nodes_per_word)};
  const size_t row = size_t(nx) + 1, plane_nodes = row * (size_t(ny) + 1);
  std::vector<uint8_t> lo(plane_nodes), hi(plane_nodes);
  if (nz > 0) decode(0, lo);
  for (uint32_t Z = 0; Z < nz; ++Z) {
    decode(Z + 1, hi);
    for (uint32_t Y = 0; Y < ny; ++Y) {
      const uint8_t *a = &lo[Y * row], *b = &lo[(Y + 1) * row], *c = &hi[Y * row], *d = &hi[(Y + 1) * row];
      for (size_t X = 0; X < row; ++X)
        *out++ = uint32_t(a[X]) | uint32_t(b[X]) << 8 | uint32_t(c[X]) << 16 | uint32_t(d[X]) << 24;
    }
    lo.swap(hi);
  }
}

}  // namespace voxcd::detail
