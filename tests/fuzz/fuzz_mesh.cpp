// Fuzz target: the mesh loaders through load_mesh, the entry point voxcd voxelize and load_source use. The first
// byte picks the format (byte % 6: 0 OBJ, 1 STL (ASCII or binary), 2 PLY, 3 OFF, 4 RAW file, 5 RAW parsed from
// memory by parse_raw), the rest is the file. A mesh that loads is voxelised into an object (voxmap and point
// shell) at an eighth of its extent, so what the loaders accept also reaches the voxeliser. MeshError is the
// documented error and must start with the file name; anything else is a finding.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "host/mesh.h"
#include "host/object_file.h"
#include "tests/fuzz/fuzz_common.h"

using namespace voxcd;

namespace {

void voxelise(const Mesh& m, const std::string& name) {
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  ObjectOptions opt;
  opt.voxel = (hi - lo).maxCoeff() / 8;
  opt.max_dim = 64;
  opt.threads = 1;
  try {
    const ObjectFile obj = make_object(m, name, 0, opt);
    if (obj.voxmap.size() == 0) fuzz::finding(name + ": an object with an empty voxmap");
  } catch (const MeshError& e) {
    fuzz::expect_prefix(e.what(), name + ":", "MeshError from make_object");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const kExt[] = {".obj", ".stl", ".ply", ".off", ".raw"};
  const unsigned format = data[0] % 6;
  const std::string body(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (format == 5) {
    const std::string name = "memory.raw";
    try {
      std::istringstream in(body);
      Mesh m = parse_raw(in, name);
      prepare(m);
      voxelise(m, name);
    } catch (const MeshError& e) {
      fuzz::expect_prefix(e.what(), name + ":", "MeshError");
    }
    return 0;
  }
  const std::string path = fuzz::scratch_path(kExt[format]);
  fuzz::write_bytes(path, data + 1, size - 1);
  try {
    const Mesh m = load_mesh(path);
    if (m.size() == 0) fuzz::finding(path + ": load_mesh returned a mesh without triangles");
    voxelise(m, path);
  } catch (const MeshError& e) {
    fuzz::expect_prefix(e.what(), path + ":", "MeshError");
  }
  std::remove(path.c_str());
  return 0;
}
