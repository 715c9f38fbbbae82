// Shared by `voxcd voxelize` and `voxcd info` (object_report.h): how an object is stored, dense or sparse, and what
// each form takes in device memory with the default widths (docs/objects.md, "Sparse objects"), as JSON and text of
// the library's figures (host/object/storage_figures.h).
#pragma once

#include <array>
#include <sstream>
#include <string>

#include "voxcd/host/report/json_text.h"
#include "voxcd/host/object/storage_figures.h"

namespace voxcd::report {

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

}  // namespace voxcd::report
