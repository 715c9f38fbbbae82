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
  const ObjectFile& o = t.object;
  if (!o.has_distance())
    throw CapacityError("object '" + t.name + "' has no distance field, and the device holds distance voxmaps (SB = " +
                        std::to_string(cfg.SB) + "): voxelise it with distance_bits = " + std::to_string(cfg.SB));
  if (o.distance_bits() > cfg.SB)
    throw CapacityError("object '" + t.name + "' has a distance field of " + std::to_string(o.distance_bits()) +
                        " bits, wider than the device's SB = " + std::to_string(cfg.SB));
  if (o.distance_sparse() && o.distance.empty() && !cfg.sparse())
    throw CapacityError("object '" + t.name + "' holds its distance field sparse, with refined bricks: it needs a " +
                        "sparse device (BL = " + std::to_string(SparseDistanceField::kBrickLog) + ")");
}

// A type's map as the device holds it: dense words, or a sparse map's table and bricks.
struct MapImage {
  std::vector<uint64_t> table, bricks;  // dense: the map's words in `table`
  uint64_t brick_units = 0;
  bool sparse = false;
};

MapImage map_image(const DeviceConfig& cfg, const ObjectType& t) {
  MapImage m;
  if (map_is_sparse(cfg, t)) {
    m.sparse = true;
    if (cfg.distance()) {
      SparseImage img = t.object.sparse_distance.device_image(cfg);
      m.table = std::move(img.table), m.bricks = std::move(img.bricks), m.brick_units = img.brick_units;
    } else {
      SparseVoxmap::DeviceImage img = t.object.sparse_voxmap.device_image(cfg);
      m.table = std::move(img.table), m.bricks = std::move(img.bricks), m.brick_units = img.brick_units;
    }
    return m;
  }
  m.table = cfg.distance() ? t.object.distance.device_words(cfg) : t.voxmap().device_words(cfg.MEMW);
  return m;
}

// Words of padding before a part of a map placed at `at` (a distance map's parts start on a bank boundary).
uint64_t pad(const DeviceConfig& cfg, uint64_t at) { return cfg.distance() ? (8 - at % 8) % 8 : 0; }

void check_dims(const DeviceConfig& cfg, const ObjectType& t) {
  const auto& d = t.object.voxmap_grid().dims;
  for (int i = 0; i < 3; ++i)
    if (d[i] > cfg.max_dim())
      throw CapacityError("object '" + t.name + "': its voxmap is " + std::to_string(d[0]) + "x" +
                          std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels, above the device's 2^DW = " +
                          std::to_string(cfg.max_dim()) + " per axis");
}

}  // namespace

bool map_is_sparse(const DeviceConfig& cfg, const ObjectType& t) {
  return cfg.sparse() && (cfg.distance() ? t.object.distance_sparse() : t.object.voxmap_sparse());
}

bool shell_is_sparse(const DeviceConfig& cfg, const ObjectType& t) {
  return cfg.sparse() && cfg.PF >= 1 && t.object.shell_sparse() && !t.shell().on_surface && t.shell().size() > 0;
}

detail::ShellOrder shell_order(const DeviceConfig& cfg, const ObjectType& t) {
  return shell_is_sparse(cfg, t) ? detail::sparse_block_order(t.shell().cells, cfg) : detail::block_order(t.shell().cells);
}

uint64_t type_shell_words(const DeviceConfig& cfg, const ObjectType& t) {
  return shell_is_sparse(cfg, t) ? shell_order(cfg, t).words.size() : t.shell().size();
}

uint64_t type_map_words(const DeviceConfig& cfg, const ObjectType& t) {
  if (map_is_sparse(cfg, t)) {
    const MapImage m = map_image(cfg, t);
    return m.table.size() + pad(cfg, m.table.size()) + m.bricks.size();
  }
  Job j;
  j.nx = t.voxmap().dims()[0];
  j.ny = t.voxmap().dims()[1];
  j.nz = t.voxmap().dims()[2];
  return map_words(cfg, j);  // ref/: states, or the distance field's parity banks
}

uint32_t DeviceImage::add(const ObjectType& t, const std::vector<uint32_t>& order) {
  detail::ShellOrder o;
  o.point = order;
  return add(t, o);
}

namespace {

// The shell words of a type in a dense order (every point when the order is empty).
std::vector<ShellWord> dense_shell_words(const DeviceConfig& cfg, const ObjectType& t, const std::vector<uint32_t>& order) {
  std::vector<ShellWord> sw = t.shell().words(cfg);
  if (order.empty()) return sw;
  if (order.size() != sw.size())
    throw std::invalid_argument("DeviceImage::add: an order of " + std::to_string(order.size()) + " slots for '" +
                                t.name + "', whose shell has " + std::to_string(sw.size()) + " points");
  std::vector<ShellWord> in_order(sw.size());
  for (size_t k = 0; k < sw.size(); ++k) in_order[k] = sw.at(order[k]);
  return in_order;
}

}  // namespace

uint32_t DeviceImage::add(const ObjectType& t, const detail::ShellOrder& order) {
  check_dims(cfg_, t);
  check_distance(cfg_, t);
  const std::vector<ShellWord> sw = order.sparse() ? order.words : dense_shell_words(cfg_, t, order.point);
  MapImage m = map_image(cfg_, t);
  // A distance map's parts start on a bank boundary: the words before each up to one are padding.
  const uint64_t pad0 = pad(cfg_, mem_.map.size()), pad1 = m.sparse ? pad(cfg_, mem_.map.size() + pad0 + m.table.size()) : 0;
  const uint64_t shell = sw.size(), words = pad0 + m.table.size() + pad1 + m.bricks.size();
  const uint64_t shell_free = cfg_.shell_depth() - mem_.shell.size(), map_free = cfg_.map_depth() - mem_.map.size();
  if (shell > shell_free || words > map_free)
    throw CapacityError("object '" + t.name + "' needs " + std::to_string(shell) + " shell words and " +
                        std::to_string(words) + " voxmap words; the device has " + std::to_string(shell_free) +
                        " of 2^SAW = " + std::to_string(cfg_.shell_depth()) + " shell words and " +
                        std::to_string(map_free) + " of 2^MAW = " + std::to_string(cfg_.map_depth()) +
                        " voxmap words free");
  Placement p;
  p.shell_base = uint32_t(mem_.shell.size());
  p.shell_count = uint32_t(shell);
  p.points = uint32_t(t.shell().size());
  p.sparse = uint8_t((m.sparse ? kSparseMap : 0) | (order.sparse() ? kSparseShell : 0));
  p.dims = t.object.voxmap_grid().dims;
  mem_.shell.insert(mem_.shell.end(), sw.begin(), sw.end());
  mem_.map.resize(mem_.map.size() + pad0, 0);
  p.map_base = uint32_t(mem_.map.size());
  p.map_words = uint32_t(m.table.size());
  mem_.map.insert(mem_.map.end(), m.table.begin(), m.table.end());
  if (m.sparse) {
    mem_.map.resize(mem_.map.size() + pad1, 0);
    p.brick_base = uint32_t(mem_.map.size());
    p.brick_units = uint32_t(m.brick_units);
    mem_.map.insert(mem_.map.end(), m.bricks.begin(), m.bricks.end());
  }
  placements_.push_back(p);
  return uint32_t(placements_.size() - 1);
}

DeviceConfig fit_memory(DeviceConfig cfg, const std::vector<const ObjectType*>& types) {
  uint64_t shell = 0, words = 0;
  for (const ObjectType* t : types) {
    check_dims(cfg, *t);
    check_distance(cfg, *t);
    shell += type_shell_words(cfg, *t);
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
  // A type stored sparse (its voxmap; on a distance device its field) takes a sparse device of its bricks.
  for (const ObjectType* t : types) {
    const ObjectFile& o = t->object;
    const int bl = cfg.distance() ? (o.distance_sparse() ? SparseDistanceField::kBrickLog : 0)
                                  : (o.voxmap_sparse() ? o.sparse_voxmap.bl() : 0);
    if (bl && cfg.BL && bl != cfg.BL)
      throw CapacityError("object '" + t->name + "' has bricks of 2^" + std::to_string(bl) +
                          " voxels, another type's are 2^" + std::to_string(cfg.BL) + ": one device takes one brick size");
    if (bl) cfg.BL = bl;
  }
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
