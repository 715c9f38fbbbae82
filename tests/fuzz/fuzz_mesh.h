// The mesh fuzz targets' shared body: `body` is written to a scratch file ending in `ext` and loaded by load_mesh
// (ext ".memory.raw": parsed from memory by parse_raw, then prepared). A mesh that loads is voxelised into an
// object (voxmap and point shell) at an eighth of its extent, so what the loaders accept also reaches the
// voxeliser. MeshError is the documented error and must start with the file name; anything else is a finding.
#pragma once

#include <cstdio>
#include <sstream>
#include <string>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/object_file.h"
#include "tests/fuzz/fuzz_common.h"

namespace voxcd::fuzz {

inline void voxelise(const Mesh& m, const std::string& name) {
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  ObjectOptions opt;
  opt.voxel = (hi - lo).maxCoeff() / 8;
  opt.max_dim = 64;
  opt.threads = 1;
  try {
    const ObjectFile obj = make_object(m, name, 0, opt);
    if (obj.voxmap.size() == 0) finding(name + ": an object with an empty voxmap");
  } catch (const MeshError& e) {
    expect_prefix(e.what(), name + ":", "MeshError from make_object");
  }
}

inline void load_mesh_input(const std::string& ext, const std::string& body) {
  if (ext == ".memory.raw") {
    const std::string name = "memory.raw";
    try {
      std::istringstream in(body);
      Mesh m = parse_raw(in, name);
      prepare(m);
      voxelise(m, name);
    } catch (const MeshError& e) {
      expect_prefix(e.what(), name + ":", "MeshError");
    }
    return;
  }
  const std::string path = scratch_path(ext);
  write_bytes(path, reinterpret_cast<const uint8_t*>(body.data()), body.size());
  try {
    const Mesh m = load_mesh(path);
    // A point cloud (no triangles, its vertices the surface) is a mesh; nothing at all is not.
    if (m.size() == 0 && !m.points_only()) finding(path + ": load_mesh returned a mesh without triangles or points");
    voxelise(m, path);
  } catch (const MeshError& e) {
    expect_prefix(e.what(), path + ":", "MeshError");
  }
  std::remove(path.c_str());
}

}  // namespace voxcd::fuzz
