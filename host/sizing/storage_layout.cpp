#include "voxcd/host/sizing/storage_layout.h"

#include <algorithm>

#include "voxcd/host/pairs/image.h"
#include "voxcd/ref/banks.h"

namespace voxcd {

namespace {

// One type's words from its placement: the map's words run from the end of the previous type's (`start`) to the end
// of the image (`end`); what is neither table nor bricks is padding.
TypeWords type_words(const DeviceConfig& cfg, const ObjectType& t, const DeviceImage::Placement& p, uint64_t start,
                     uint64_t end) {
  TypeWords w;
  w.name = t.name;
  w.map_sparse = map_is_sparse(cfg, t);
  w.shell_sparse = shell_is_sparse(cfg, t);
  w.table = p.map_words;
  w.bricks = w.map_sparse ? end - p.brick_base : 0;
  w.padding = end - start - w.table - w.bricks;
  w.shell = p.shell_count;
  return w;
}

LayoutMemory counted(const std::string& what, const MemoryShape& shape) {
  LayoutMemory m;
  m.what = what;
  m.shape = shape;
  m.ramb36 = shape.count * memory_blocks(shape, "xilinx-7");
  m.ebr = shape.count * memory_blocks(shape, "ice40-hx8k");
  return m;
}

// A voxmap memory of its own for `words` words: cfg's voxmap memory with one read port and the fewest address bits
// that hold them (at least the banks' and a distance device's parity banks').
LayoutMemory voxmap_part(const std::string& what, DeviceConfig cfg, uint64_t words) {
  cfg.BL = 0;
  int least = cfg.distance() ? 3 : 1;
  while ((1 << least) < std::max(1, memory_banks(cfg))) ++least;
  cfg.MAW = least;
  while (cfg.map_depth() < words) ++cfg.MAW;
  return counted(what, memory_shapes(cfg).back());
}

}  // namespace

LayoutWords layout_words(const DeviceConfig& cfg, const std::vector<const ObjectType*>& types) {
  DeviceConfig big = cfg;
  big.SAW = 24;
  big.MAW = 28;
  DeviceImage image(big);
  LayoutWords w;
  uint64_t start = 0;
  for (const ObjectType* t : types) {
    const DeviceImage::Placement p = image.placement(image.add(*t, shell_order(big, *t)));
    const uint64_t end = image.memory().map.size();
    w.types.push_back(type_words(big, *t, p, start, end));
    start = end;
    const TypeWords& tw = w.types.back();
    w.table += tw.table, w.bricks += tw.bricks, w.padding += tw.padding, w.shell += tw.shell;
  }
  return w;
}

std::vector<LayoutMemory> built_memories(const DeviceConfig& cfg) {
  std::vector<LayoutMemory> out;
  for (const MemoryShape& m : memory_shapes(cfg)) out.push_back(counted(m.what, m));
  return out;
}

std::vector<LayoutMemory> split_memories(const DeviceConfig& cfg, const LayoutWords& w) {
  std::vector<LayoutMemory> out = {counted("shell bank", memory_shapes(cfg).front())};
  out.push_back(voxmap_part("table memory", cfg, w.table + w.padding));
  if (w.bricks > 0) out.push_back(voxmap_part("brick memory", cfg, w.bricks));
  return out;
}

}  // namespace voxcd
