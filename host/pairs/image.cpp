// The device image: object types placed in the device's memories, and the device configuration that fits them.
#include "voxcd/host/pairs/image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

void check_distance(const DeviceConfig& cfg, const ObjectType& t) {
  if (!cfg.distance()) return;
  const DistanceField& f = t.object.distance;
  if (f.empty())
    throw CapacityError("object '" + t.name + "' has no distance field, and the device holds distance voxmaps (SB = " +
                        std::to_string(cfg.SB) + "): voxelise it with --distance-bits " + std::to_string(cfg.SB));
  if (f.bits > cfg.SB)
    throw CapacityError("object '" + t.name + "' has a distance field of " + std::to_string(f.bits) +
                        " bits, wider than the device's SB = " + std::to_string(cfg.SB));
}

void check_dims(const DeviceConfig& cfg, const ObjectType& t) {
  const auto& d = t.voxmap().dims();
  for (int i = 0; i < 3; ++i)
    if (d[i] > cfg.max_dim())
      throw CapacityError("object '" + t.name + "': its voxmap is " + std::to_string(d[0]) + "x" +
                          std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels, above the device's 2^DW = " +
                          std::to_string(cfg.max_dim()) + " per axis");
}

}  // namespace

uint64_t type_map_words(const DeviceConfig& cfg, const ObjectType& t) {
  Job j;
  j.nx = t.voxmap().dims()[0];
  j.ny = t.voxmap().dims()[1];
  j.nz = t.voxmap().dims()[2];
  return map_words(cfg, j);  // ref/: states, or the distance field's parity banks
}

uint32_t DeviceImage::add(const ObjectType& t, const std::vector<uint32_t>& order) {
  check_dims(cfg_, t);
  check_distance(cfg_, t);
  // A distance map starts on a bank boundary: the words before it up to one are padding.
  const uint64_t pad = cfg_.distance() ? (8 - mem_.map.size() % 8) % 8 : 0;
  const uint64_t shell = t.shell().size(), words = type_map_words(cfg_, t) + pad;
  const uint64_t shell_free = cfg_.shell_depth() - mem_.shell.size(), map_free = cfg_.map_depth() - mem_.map.size();
  if (shell > shell_free || words > map_free)
    throw CapacityError("object '" + t.name + "' needs " + std::to_string(shell) + " shell words and " +
                        std::to_string(words) + " voxmap words; the device has " + std::to_string(shell_free) +
                        " of 2^SAW = " + std::to_string(cfg_.shell_depth()) + " shell words and " +
                        std::to_string(map_free) + " of 2^MAW = " + std::to_string(cfg_.map_depth()) +
                        " voxmap words free");
  std::vector<ShellWord> sw = t.shell().words(cfg_);
  if (!order.empty()) {
    if (order.size() != sw.size())
      throw std::invalid_argument("DeviceImage::add: an order of " + std::to_string(order.size()) + " slots for '" +
                                  t.name + "', whose shell has " + std::to_string(sw.size()) + " points");
    std::vector<ShellWord> in_order(sw.size());
    for (size_t k = 0; k < sw.size(); ++k) in_order[k] = sw.at(order[k]);
    sw = std::move(in_order);
  }
  std::vector<uint64_t> mw = cfg_.distance() ? t.object.distance.device_words(cfg_) : t.voxmap().device_words(cfg_.MEMW);
  mem_.map.resize(mem_.map.size() + pad, 0);
  Placement p;
  p.shell_base = uint32_t(mem_.shell.size());
  p.shell_count = uint32_t(shell);
  p.map_base = uint32_t(mem_.map.size());
  p.map_words = uint32_t(words - pad);
  p.dims = t.voxmap().dims();
  mem_.shell.insert(mem_.shell.end(), sw.begin(), sw.end());
  mem_.map.insert(mem_.map.end(), mw.begin(), mw.end());
  placements_.push_back(p);
  return uint32_t(placements_.size() - 1);
}

DeviceConfig fit_memory(DeviceConfig cfg, const std::vector<const ObjectType*>& types) {
  uint64_t shell = 0, words = 0;
  for (const ObjectType* t : types) {
    check_dims(cfg, *t);
    check_distance(cfg, *t);
    shell += t->shell().size();
    words += type_map_words(cfg, *t) + (cfg.distance() ? 7 : 0);  // at most 7 words of padding before a map
  }
  while (cfg.shell_depth() < shell && cfg.SAW < 24) ++cfg.SAW;
  while (cfg.map_depth() < words && cfg.MAW < 28) ++cfg.MAW;
  if (cfg.shell_depth() < shell || cfg.map_depth() < words)
    throw CapacityError("the object types need " + std::to_string(shell) + " shell words and " +
                        std::to_string(words) + " voxmap words; the largest device memories hold 2^24 and 2^28");
  return cfg;
}

int matrix_width_for(const DeviceConfig& cfg, const std::vector<const ObjectType*>& types, double* ratio) {
  // M = R * (A's shell spacing / B's voxel): its entries reach that ratio for some rotation, and must lie below
  // 2^(MW - MF - 1).
  double r = 0;
  for (const ObjectType* a : types)
    for (const ObjectType* b : types) r = std::max(r, a->shell().grid.voxel / b->voxmap().voxel());
  if (ratio) *ratio = r;
  int mw = cfg.MF + 2;
  while (std::ldexp(1.0, mw - cfg.MF - 1) <= r) ++mw;
  return std::max(cfg.MW, mw);
}

DeviceConfig device_config_for(const std::string& backend, int lanes, const std::vector<const ObjectType*>& types,
                               int distance_bits) {
  DeviceConfig cfg;
  cfg.LANES = lanes;
  if (distance_bits > 0) cfg.SB = distance_bits;
  double ratio = 0;
  const int mw = matrix_width_for(cfg, types, &ratio);
  if (mw != cfg.MW) {
    if (backend == "rtl") {
      char b[512];
      std::snprintf(b, sizeof b,
                    "the objects' voxels differ too much for the rtl backend's models (MW %d, MF %d: matrix entries "
                    "below %g): a shell spacing over another object's voxel reaches %.4g and needs MW %d. Voxelise "
                    "the objects at voxels within a factor of %.3g of each other, or use the cpu or ref backend "
                    "(which take any width)",
                    cfg.MW, cfg.MF, std::ldexp(1.0, cfg.MW - cfg.MF - 1), ratio, mw,
                    std::ldexp(1.0, cfg.MW - cfg.MF - 1) * std::sqrt(2.0));
      throw CapacityError(b);
    }
    cfg.MW = mw;
    cfg.validate();
  }
  return backend == "rtl" ? cfg : fit_memory(cfg, types);
}

}  // namespace voxcd
