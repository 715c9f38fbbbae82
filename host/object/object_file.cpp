// ObjectFile's own operations apart from its file I/O (object_write.cpp, object_read.cpp): the distance field's
// conservative cells, and the dense forms of an object held sparse.
#include "voxcd/host/object/object_file.h"

#include <algorithm>
#include <cmath>

#include "voxcd/host/object/shapes.h"

namespace voxcd {

bool ObjectFile::distance_near_conservative(const Eigen::Vector3d& g) const {
  if (distance_sparse()) return sparse_distance.near_conservative(g);
  if (distance.empty() || voxmap.words().empty()) return false;
  uint32_t v[3];
  for (int i = 0; i < 3; ++i) v[i] = uint32_t(std::clamp(std::floor(g[i]), 0.0, double(distance.dims[i]) - 1));
  return distance.near_conservative(voxmap, v[0], v[1], v[2]);
}

void add_dense_forms(ObjectFile& obj) {
  if (obj.voxmap_sparse() && !obj.has_dense_voxmap()) {
    const auto& d = obj.sparse_voxmap.dims();
    if (std::max({d[0], d[1], d[2]}) <= kMaxDenseDim) obj.voxmap = obj.sparse_voxmap.to_dense();
  }
  if (obj.shell_sparse() && obj.shell.size() == 0) {
    const auto& d = obj.sparse_shell.grid.dims;
    if (std::max({d[0], d[1], d[2]}) <= ShellOptions{}.max_dim) obj.shell = obj.sparse_shell.to_point_shell();
  }
}

}  // namespace voxcd
