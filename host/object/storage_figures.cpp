#include "voxcd/host/object/storage_figures.h"

#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

void sparse_voxmap_figures(const SparseVoxmap& sm, StorageFigures& f) {
  f.bl = sm.bl();
  f.coarse = sm.coarse();
  f.cells = sm.code_counts();
  f.table_bytes = sm.table_bytes();
  f.brick_bytes = sm.brick_bytes();
}

void sparse_shell_figures(const SparseShell& s, StorageFigures& f) {
  f.shell_words = s.words();
  f.shell_bricks = s.bricks.size();
  f.origin_words = s.origin_words();
  f.sparse_shell = s.bytes();
}

}  // namespace

ObjectMemory dense_memory(const ObjectFile& obj, const DeviceConfig& cfg) {
  ObjectMemory m;
  const uint64_t per = uint64_t(cfg.states_per_word());
  m.voxmap_bytes = (obj.voxmap_grid().size() + per - 1) / per * uint64_t(cfg.MEMW) / 8;
  m.shell_bytes = (uint64_t(obj.shell_count()) * 3 * uint64_t(cfg.PW) + 7) / 8;
  return m;
}

ObjectMemory object_memory(const ObjectFile& obj, const DeviceConfig& cfg) {
  ObjectMemory m = dense_memory(obj, cfg);
  if (obj.voxmap_sparse()) m.voxmap_bytes = obj.sparse_voxmap.bytes(cfg.MEMW);
  if (obj.shell_sparse()) m.shell_bytes = obj.sparse_shell.bytes(cfg);
  return m;
}

DistanceMemory dense_distance_memory(int bits, const std::array<uint32_t, 3>& dims) {
  DistanceMemory m;
  m.cfg.SB = bits;
  Job j;
  j.nx = dims[0];
  j.ny = dims[1];
  j.nz = dims[2];
  m.words = map_words(m.cfg, j);
  m.bytes = m.words * uint64_t(m.cfg.MEMW) / 8;
  m.nodes = (uint64_t(dims[0]) + 1) * (uint64_t(dims[1]) + 1) * (uint64_t(dims[2]) + 1);
  return m;
}

DistanceMemory distance_memory(const ObjectFile& obj) {
  if (obj.distance.empty()) return DistanceMemory{};
  return dense_distance_memory(obj.distance.bits, obj.distance.dims);
}

DistanceMemory sparse_distance_memory(const ObjectFile& obj) {
  DistanceMemory m;
  const SparseDistanceField& f = obj.sparse_distance;
  m.cfg.SB = f.bits();
  m.cfg.BL = SparseDistanceField::kBrickLog;
  const SparseImage img = f.device_image(m.cfg);
  m.words = img.table.size() + img.bricks.size();
  m.bytes = m.words * uint64_t(m.cfg.MEMW) / 8;
  m.nodes = f.counts().nodes;
  return m;
}

DistanceFigures distance_figures(const ObjectFile& obj) {
  DistanceFigures f;
  f.present = obj.has_distance();
  if (!f.present) return f;
  f.sparse = obj.distance_sparse();
  f.stored = f.sparse ? sparse_distance_memory(obj) : distance_memory(obj);
  f.dense = f.sparse ? dense_distance_memory(obj.sparse_distance.bits(), obj.sparse_distance.dims()) : f.stored;
  if (f.sparse) f.counts = obj.sparse_distance.counts();
  return f;
}

StorageFigures storage_figures(const ObjectFile& obj) {
  StorageFigures f;
  f.voxmap_sparse = obj.voxmap_sparse();
  f.shell_sparse = obj.shell_sparse();
  const ObjectMemory dense = dense_memory(obj);
  f.dense_voxmap = dense.voxmap_bytes;
  f.dense_shell = dense.shell_bytes;
  if (f.voxmap_sparse)  // (not a ?: which would copy the stored map)
    sparse_voxmap_figures(obj.sparse_voxmap, f);
  else
    sparse_voxmap_figures(SparseVoxmap::from_dense(obj.voxmap), f);
  f.shell_has_sparse = f.shell_sparse || !obj.shell.on_surface;
  if (f.shell_sparse) sparse_shell_figures(obj.sparse_shell, f);
  else if (f.shell_has_sparse) sparse_shell_figures(SparseShell::from_point_shell(obj.shell), f);
  return f;
}

}  // namespace voxcd
