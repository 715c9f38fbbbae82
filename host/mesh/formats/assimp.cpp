// Every format assimp reads: its scene flattened into one triangle list (or a point cloud).
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cctype>
#include <fstream>

#include "voxcd/host/mesh/formats/formats.h"

namespace voxcd::formats {

namespace {

// Faces are checked before any post-processing: a damaged file (a truncated PLY declares faces it does not hold,
// and assimp gives them no vertices) would otherwise reach Triangulate, whose assertion aborts.
void check_faces(const aiScene* raw, const std::string& path) {
  for (unsigned i = 0; i < raw->mNumMeshes; ++i) {
    const aiMesh* am = raw->mMeshes[i];
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices == 0 || !face.mIndices)
        throw MeshError(path + ": face " + std::to_string(f) + " of mesh " + std::to_string(i) +
                        " has no vertices (is the file truncated?)");
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= am->mNumVertices)
          throw MeshError(path + ": face " + std::to_string(f) + " of mesh " + std::to_string(i) +
                          " has vertex index " + std::to_string(face.mIndices[k]) + " out of range (" +
                          std::to_string(am->mNumVertices) + " vertices)");
    }
  }
}

void append_vertices(const aiMesh* am, std::vector<Eigen::Vector3d>& to) {
  for (unsigned v = 0; v < am->mNumVertices; ++v) to.emplace_back(am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z);
}

// The triangles of every mesh; when there are none, the vertices of the meshes without triangles (a point cloud).
Mesh flatten(const aiScene* sc, const std::string& path) {
  Mesh m;
  m.name = path;
  std::vector<Eigen::Vector3d> points;
  for (unsigned i = 0; i < sc->mNumMeshes; ++i) {
    const aiMesh* am = sc->mMeshes[i];
    if (!(am->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) {
      append_vertices(am, points);
      continue;
    }
    const uint32_t base = uint32_t(m.vertices.size());
    append_vertices(am, m.vertices);
    for (unsigned f = 0; f < am->mNumFaces; ++f) {
      const aiFace& face = am->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines sorted into their own meshes are not surface
      m.triangles.push_back({base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]});
    }
  }
  if (m.triangles.empty()) m.vertices = std::move(points);
  return m;
}

}  // namespace

std::string lower_ext(const std::string& path) {
  const size_t dot = path.find_last_of('.');
  const size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string e = path.substr(dot + 1);
  for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
  return e;
}

Mesh read_assimp(const std::string& path) {
  if (!std::ifstream(path, std::ios::binary)) throw MeshError(path + ": cannot open");
  Assimp::Importer imp;
  // Only positions matter: dropping the other components lets equal positions merge.
  imp.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                     aiComponent_COLORS | aiComponent_TEXCOORDS |
                                                     aiComponent_BONEWEIGHTS | aiComponent_MATERIALS);
  const aiScene* raw = imp.ReadFile(path, aiProcess_ValidateDataStructure);
  if (!raw) throw MeshError(path + ": cannot load: " + imp.GetErrorString());
  check_faces(raw, path);
  const aiScene* sc = imp.ApplyPostProcessing(aiProcess_RemoveComponent | aiProcess_Triangulate |
                                              aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!sc) throw MeshError(path + ": cannot load: " + imp.GetErrorString());
  return flatten(sc, path);
}

}  // namespace voxcd::formats
