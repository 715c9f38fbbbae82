#include "voxcd/host/object/voxmap_surface.h"

#include <unordered_map>

namespace voxcd {

namespace {

// The mesh's vertex at grid corner (x, y, z), made once.
struct Corners {
  const Voxmap& v;
  Mesh& m;
  std::unordered_map<uint64_t, uint32_t> index;
  uint32_t at(uint32_t x, uint32_t y, uint32_t z) {
    const uint64_t key = x + (uint64_t(v.dims()[0]) + 1) * (y + (uint64_t(v.dims()[1]) + 1) * uint64_t(z));
    const auto [it, fresh] = index.emplace(key, uint32_t(m.vertices.size()));
    if (fresh) m.vertices.push_back(v.origin() + v.voxel() * Eigen::Vector3d(x, y, z));
    return it->second;
  }
};

}  // namespace

Mesh voxmap_surface(const Voxmap& v) {
  Mesh m;
  m.name = "voxmap surface";
  Corners c{v, m, {}};
  const auto& d = v.dims();
  auto solid = [&](int64_t x, int64_t y, int64_t z) {
    if (x < 0 || y < 0 || z < 0 || x >= d[0] || y >= d[1] || z >= d[2]) return false;
    return v.at(uint32_t(x), uint32_t(y), uint32_t(z)) != kEmpty;
  };
  for (uint32_t z = 0; z < d[2]; ++z)
    for (uint32_t y = 0; y < d[1]; ++y)
      for (uint32_t x = 0; x < d[0]; ++x) {
        if (!solid(x, y, z)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side) {
            int64_t n[3] = {x, y, z};
            n[axis] += side ? 1 : -1;
            if (solid(n[0], n[1], n[2])) continue;
            // The face's corners counter-clockwise seen from outside (along +axis for side 1, -axis for side 0).
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            uint32_t q[4];
            for (int k = 0; k < 4; ++k) {
              uint32_t p[3] = {x, y, z};
              p[axis] += uint32_t(side);
              p[u] += (k == 1 || k == 2) ? 1 : 0;
              p[w] += (k >= 2) ? 1 : 0;
              q[k] = c.at(p[0], p[1], p[2]);
            }
            if (side) {
              m.triangles.push_back({q[0], q[1], q[2]});
              m.triangles.push_back({q[0], q[2], q[3]});
            } else {
              m.triangles.push_back({q[0], q[2], q[1]});
              m.triangles.push_back({q[0], q[3], q[2]});
            }
          }
      }
  return m;
}

}  // namespace voxcd
