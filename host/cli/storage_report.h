// Shared by `voxcd voxelize` and `voxcd info` (object_report.h): how an object is stored, dense or sparse, and what
// each form takes in device memory with the default widths (docs/objects.md, "Sparse objects").
#pragma once

#include <sstream>
#include <string>

#include "voxcd/host/cli/json_text.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/ref/config.h"

namespace voxcd::cli {

// The bytes of both forms of the voxmap and the shell (a shell on the surface has no sparse form).
struct StorageFigures {
  bool voxmap_sparse = false, shell_sparse = false, shell_has_sparse = false;
  uint64_t dense_voxmap = 0, dense_shell = 0;
  SparseVoxmap sparse_voxmap;  // as stored, or as it would be
  SparseShell sparse_shell;
  uint64_t sparse_voxmap_bytes() const { return sparse_voxmap.bytes(); }
  uint64_t sparse_shell_bytes() const { return shell_has_sparse ? sparse_shell.bytes() : dense_shell; }
};

inline StorageFigures storage_figures(const ObjectFile& obj) {
  const DeviceConfig cfg;
  StorageFigures f;
  f.voxmap_sparse = obj.voxmap_sparse();
  f.shell_sparse = obj.shell_sparse();
  const uint64_t per = uint64_t(cfg.states_per_word());
  f.dense_voxmap = (obj.voxmap_grid().size() + per - 1) / per * uint64_t(cfg.MEMW) / 8;
  f.dense_shell = (uint64_t(obj.shell_points()) * 3 * uint64_t(cfg.PW) + 7) / 8;
  f.sparse_voxmap = f.voxmap_sparse ? obj.sparse_voxmap : SparseVoxmap::from_dense(obj.voxmap);
  f.shell_has_sparse = f.shell_sparse || !obj.shell.on_surface;
  if (f.shell_has_sparse) f.sparse_shell = f.shell_sparse ? obj.sparse_shell : SparseShell::from_point_shell(obj.shell);
  return f;
}

// info --json's "storage" object.
inline Json storage_json(const StorageFigures& f) {
  const SparseVoxmap& sm = f.sparse_voxmap;
  const auto cc = sm.code_counts();
  const auto& cd = sm.coarse();
  Json sparse = {{"voxmap_bytes", f.sparse_voxmap_bytes()}, {"shell_bytes", f.sparse_shell_bytes()},
                 {"bytes", f.sparse_voxmap_bytes() + f.sparse_shell_bytes()}, {"bl", sm.bl()},
                 {"coarse_dims", {cd[0], cd[1], cd[2]}},
                 {"cells", {{"empty", cc[kEmpty]}, {"surface", cc[kSurface]}, {"interior", cc[kInterior]},
                            {"brick", cc[kCodeBrick]}}},
                 {"table_bytes", sm.table_bytes()}, {"brick_bytes", sm.brick_bytes()}};
  if (f.shell_has_sparse) {
    sparse["shell_words"] = f.sparse_shell.words();
    sparse["shell_bricks"] = f.sparse_shell.bricks.size();
    sparse["origin_words"] = f.sparse_shell.origin_words();
  }
  return Json{{"voxmap", f.voxmap_sparse ? "sparse" : "dense"},
              {"shell", f.shell_sparse ? "sparse" : "dense"},
              {"dense", {{"voxmap_bytes", f.dense_voxmap}, {"shell_bytes", f.dense_shell},
                         {"bytes", f.dense_voxmap + f.dense_shell}}},
              {"sparse", sparse}};
}

// The same as two lines of text.
inline std::string storage_text(const StorageFigures& f) {
  const SparseVoxmap& sm = f.sparse_voxmap;
  const auto cc = sm.code_counts();
  const auto& cd = sm.coarse();
  std::ostringstream t;
  t << "  storage  voxmap stored " << (f.voxmap_sparse ? "sparse" : "dense") << "; sparse (BL " << sm.bl() << "): "
    << cd[0] << " x " << cd[1] << " x " << cd[2] << " cells, " << cc[kEmpty] << " empty, " << cc[kSurface]
    << " surface, " << cc[kInterior] << " interior, " << cc[kCodeBrick] << " bricks; table " << sm.table_bytes()
    << " + bricks " << sm.brick_bytes() << " = " << sm.bytes() << " bytes; dense " << f.dense_voxmap << " bytes\n";
  t << "  storage  shell stored " << (f.shell_sparse ? "sparse" : "dense");
  if (f.shell_has_sparse)
    t << "; sparse: " << f.sparse_shell.words() << " words (" << f.sparse_shell.bricks.size() << " bricks, "
      << f.sparse_shell.origin_words() << " origin words) = " << f.sparse_shell.bytes() << " bytes; dense "
      << f.dense_shell << " bytes\n";
  else
    t << " (points on the surface have no sparse form)\n";
  return t.str();
}

}  // namespace voxcd::cli
