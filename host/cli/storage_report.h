// Shared by `voxcd voxelize` and `voxcd info` (object_report.h): how an object is stored, dense or sparse, and what
// each form takes in device memory with the default widths (docs/objects.md, "Sparse objects").
#pragma once

#include <array>
#include <sstream>
#include <string>

#include "voxcd/host/cli/json_text.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/ref/config.h"

namespace voxcd::cli {

// The bytes of both forms of the voxmap and the shell (a shell on the surface has no sparse form), and the sparse
// forms' make-up, as stored or as they would be.
struct StorageFigures {
  bool voxmap_sparse = false, shell_sparse = false, shell_has_sparse = false;
  uint64_t dense_voxmap = 0, dense_shell = 0;
  int bl = 0;
  std::array<uint64_t, 3> coarse{};
  std::array<uint64_t, 4> cells{};  // per code
  uint64_t table_bytes = 0, brick_bytes = 0;
  uint64_t shell_words = 0, shell_bricks = 0, origin_words = 0, sparse_shell = 0;
  uint64_t sparse_voxmap() const { return table_bytes + brick_bytes; }
  uint64_t sparse_shell_bytes() const { return shell_has_sparse ? sparse_shell : dense_shell; }
};

inline void sparse_voxmap_figures(const SparseVoxmap& sm, StorageFigures& f) {
  f.bl = sm.bl();
  f.coarse = sm.coarse();
  f.cells = sm.code_counts();
  f.table_bytes = sm.table_bytes();
  f.brick_bytes = sm.brick_bytes();
}

inline void sparse_shell_figures(const SparseShell& s, StorageFigures& f) {
  f.shell_words = s.words();
  f.shell_bricks = s.bricks.size();
  f.origin_words = s.origin_words();
  f.sparse_shell = s.bytes();
}

inline StorageFigures storage_figures(const ObjectFile& obj) {
  const DeviceConfig cfg;
  StorageFigures f;
  f.voxmap_sparse = obj.voxmap_sparse();
  f.shell_sparse = obj.shell_sparse();
  const uint64_t per = uint64_t(cfg.states_per_word());
  f.dense_voxmap = (obj.voxmap_grid().size() + per - 1) / per * uint64_t(cfg.MEMW) / 8;
  f.dense_shell = (uint64_t(obj.shell_points()) * 3 * uint64_t(cfg.PW) + 7) / 8;
  if (f.voxmap_sparse)  // (not a ?: which would copy the stored map)
    sparse_voxmap_figures(obj.sparse_voxmap, f);
  else
    sparse_voxmap_figures(SparseVoxmap::from_dense(obj.voxmap), f);
  f.shell_has_sparse = f.shell_sparse || !obj.shell.on_surface;
  if (f.shell_sparse) sparse_shell_figures(obj.sparse_shell, f);
  else if (f.shell_has_sparse) sparse_shell_figures(SparseShell::from_point_shell(obj.shell), f);
  return f;
}

// info --json's "storage" object.
inline Json storage_json(const StorageFigures& f) {
  Json sparse = {{"voxmap_bytes", f.sparse_voxmap()}, {"shell_bytes", f.sparse_shell_bytes()},
                 {"bytes", f.sparse_voxmap() + f.sparse_shell_bytes()}, {"bl", f.bl},
                 {"coarse_dims", {f.coarse[0], f.coarse[1], f.coarse[2]}},
                 {"cells", {{"empty", f.cells[kEmpty]}, {"surface", f.cells[kSurface]}, {"interior", f.cells[kInterior]},
                            {"brick", f.cells[kCodeBrick]}}},
                 {"table_bytes", f.table_bytes}, {"brick_bytes", f.brick_bytes}};
  if (f.shell_has_sparse) {
    sparse["shell_words"] = f.shell_words;
    sparse["shell_bricks"] = f.shell_bricks;
    sparse["origin_words"] = f.origin_words;
  }
  return Json{{"voxmap", f.voxmap_sparse ? "sparse" : "dense"},
              {"shell", f.shell_sparse ? "sparse" : "dense"},
              {"dense", {{"voxmap_bytes", f.dense_voxmap}, {"shell_bytes", f.dense_shell},
                         {"bytes", f.dense_voxmap + f.dense_shell}}},
              {"sparse", sparse}};
}

// The same as two lines of text.
inline std::string storage_text(const StorageFigures& f) {
  std::ostringstream t;
  t << "  storage  voxmap stored " << (f.voxmap_sparse ? "sparse" : "dense") << "; sparse (BL " << f.bl << "): "
    << f.coarse[0] << " x " << f.coarse[1] << " x " << f.coarse[2] << " cells, " << f.cells[kEmpty] << " empty, "
    << f.cells[kSurface] << " surface, " << f.cells[kInterior] << " interior, " << f.cells[kCodeBrick]
    << " bricks; table " << f.table_bytes << " + bricks " << f.brick_bytes << " = " << f.sparse_voxmap()
    << " bytes; dense " << f.dense_voxmap << " bytes\n";
  t << "  storage  shell stored " << (f.shell_sparse ? "sparse" : "dense");
  if (f.shell_has_sparse)
    t << "; sparse: " << f.shell_words << " words (" << f.shell_bricks << " bricks, " << f.origin_words
      << " origin words) = " << f.sparse_shell << " bytes; dense " << f.dense_shell << " bytes\n";
  else
    t << " (points on the surface have no sparse form)\n";
  return t.str();
}

}  // namespace voxcd::cli
