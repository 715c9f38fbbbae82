// DistanceField's interpolant and memory image; the field itself is built in distance_build.cpp.
#include "voxcd/host/object/distance_field.h"

#include <algorithm>
#include <cmath>

#include "voxcd/ref/pipeline.h"

namespace voxcd {

double DistanceField::sample(const Eigen::Vector3d& g, Eigen::Vector3d* gradient) const {
  uint64_t c[3];
  double f[3];
  for (int i = 0; i < 3; ++i) {
    const double n = double(dims[size_t(i)]);
    const double v = std::clamp(g[i], 0.0, n);
    const double cell = std::min(std::floor(v), n - 1);
    c[i] = uint64_t(cell);
    f[i] = v - cell;
  }
  double v[8];
  for (int k = 0; k < 8; ++k) v[k] = at(c[0] + (k & 1), c[1] + (k >> 1 & 1), c[2] + (k >> 2 & 1)) * step;
  auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
  const double x00 = lerp(v[0], v[1], f[0]), x10 = lerp(v[2], v[3], f[0]);
  const double x01 = lerp(v[4], v[5], f[0]), x11 = lerp(v[6], v[7], f[0]);
  const double y0 = lerp(x00, x10, f[1]), y1 = lerp(x01, x11, f[1]);
  if (gradient) {
    const double dx0 = lerp(v[1] - v[0], v[3] - v[2], f[1]), dx1 = lerp(v[5] - v[4], v[7] - v[6], f[1]);
    (*gradient)[0] = lerp(dx0, dx1, f[2]);
    (*gradient)[1] = lerp(x10 - x00, x11 - x01, f[2]);
    (*gradient)[2] = y1 - y0;
  }
  return lerp(y0, y1, f[2]);
}

bool DistanceField::near_conservative(const Voxmap& vm, uint32_t x, uint32_t y, uint32_t z) const {
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int64_t cx = int64_t(x) + dx, cy = int64_t(y) + dy, cz = int64_t(z) + dz;
        if (cx < 0 || cy < 0 || cz < 0 || cx >= dims[0] || cy >= dims[1] || cz >= dims[2]) continue;
        if (vm.at(vm.index(uint32_t(cx), uint32_t(cy), uint32_t(cz))) == kSurface &&
            hits_everywhere(uint64_t(cx), uint64_t(cy), uint64_t(cz)))
          return true;
      }
  return false;
}

std::vector<uint64_t> DistanceField::device_words(const DeviceConfig& cfg) const {
  Job j;
  j.nx = dims[0];
  j.ny = dims[1];
  j.nz = dims[2];
  std::vector<uint64_t> words(map_words(cfg, j), 0);
  const uint64_t vmask = (uint64_t{1} << cfg.SB) - 1;
  for (uint64_t Z = 0; Z <= dims[2]; ++Z)
    for (uint64_t Y = 0; Y <= dims[1]; ++Y)
      for (uint64_t X = 0; X <= dims[0]; ++X) {
        const NodeAddress a = node_address(cfg, j, X, Y, Z);
        words[a.word] |= (uint64_t(int64_t(at(X, Y, Z))) & vmask) << (uint64_t(cfg.SB) * a.slot);
      }
  return words;
}

}  // namespace voxcd
