// Wavefront OBJ: assimp's reader, and the point clouds it finds no mesh in.
#include <fstream>
#include <sstream>

#include "voxcd/host/mesh/formats/formats.h"

namespace voxcd::formats {

namespace {

// The vertices of an OBJ file that has vertex lines and no face lines (assimp finds no mesh in it): a point cloud.
// Returns false when the file has faces or no vertices.
bool read_obj_points(const std::string& path, Mesh& m) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::vector<Eigen::Vector3d> pts;
  size_t lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    std::istringstream ls(line);
    std::string key;
    ls >> key;
    if (key == "f" || key == "l" || key == "p") return false;
    if (key != "v") continue;
    double x, y, z;
    if (!(ls >> x >> y >> z))
      throw MeshError(path + ":" + std::to_string(lineno) + ": a vertex line needs three numbers");
    pts.emplace_back(x, y, z);
  }
  if (pts.empty()) return false;
  m.name = path;
  m.vertices = std::move(pts);
  m.triangles.clear();
  return true;
}

}  // namespace

Mesh read_obj(const std::string& path) {
  Mesh m;
  try {
    m = read_assimp(path);
  } catch (const MeshError&) {
    if (!read_obj_points(path, m)) throw;
  }
  return m;
}

}  // namespace voxcd::formats
