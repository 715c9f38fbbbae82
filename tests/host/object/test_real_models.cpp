// Real-world models: every file of Debian's assimp-testmodels (meshes exported by Blender, 3ds Max, Cinema4D,
// CAD and scanning tools in about forty formats, with the defects such files have) either cannot be read, and
// the error names the file, or voxelises at resolution 64 with a report of what was repaired.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>
#include <string>

#include "voxcd/host/object/object_file.h"

namespace voxcd {
namespace {

#ifndef VOXCD_TESTMODELS_DIR
#define VOXCD_TESTMODELS_DIR "/usr/share/assimp/models"
#endif

bool is_model(const std::filesystem::path& p) {
  static const std::set<std::string> not_models = {"png", "jpg", "jpeg", "tga", "bmp", "txt", "mtl", "glsl",
                                                   "xml", "bin", "dds", "gif", "tif", "md", "skeleton", "material",
                                                   "program", "zip", "py", "sh", "xcf", "psd", "html", "ktx"};
  std::string e = p.extension().string();
  if (!e.empty()) e = e.substr(1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return !not_models.count(e);
}

TEST(RealModelsSlow, EveryReadableModelVoxelisesAtResolution64) {
  namespace fs = std::filesystem;
  ASSERT_TRUE(fs::is_directory(VOXCD_TESTMODELS_DIR)) << "install assimp-testmodels (.ci/setup.sh does)";
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(VOXCD_TESTMODELS_DIR))
    if (e.is_regular_file() && is_model(e.path())) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  size_t unreadable = 0, voxelised = 0, repaired = 0, open = 0, clouds = 0, sheets = 0;
  for (const fs::path& f : files) {
    const std::string path = f.string();
    MeshReport rep;
    Mesh m;
    try {
      m = load_mesh(path, &rep);
    } catch (const MeshError& e) {
      ++unreadable;
      EXPECT_EQ(std::string(e.what()).rfind(path + ":", 0), 0u) << e.what();
      continue;
    }
    ASSERT_TRUE(m.size() > 0 || !m.vertices.empty()) << path << ": loaded without triangles or points";
    ObjectOptions o;
    o.resolution = 64;
    try {
      const ObjectFile obj = make_object(m, path, 0, o, &rep);
      ++voxelised;
      EXPECT_GT(obj.voxmap.counts()[kSurface], 0u) << path;
      EXPECT_GT(obj.shell.size(), 0u) << path;
      if (rep.surface_only) {
        EXPECT_EQ(obj.voxmap.counts()[kInterior], 0u) << path;
      }
      repaired += rep.repaired() ? 1 : 0;
      open += rep.open_edges > 0 ? 1 : 0;
      clouds += rep.points_only ? 1 : 0;
      sheets += rep.sheet_components > 0 ? 1 : 0;
    } catch (const MeshError& e) {
      // The one thing a resolution cannot be applied to: a model whose points all coincide.
      EXPECT_NE(std::string(e.what()).find("no extent"), std::string::npos) << e.what();
    }
  }
  std::printf("%zu files: %zu voxelised (%zu repaired, %zu open, %zu point clouds, %zu with sheets), %zu unreadable\n",
              files.size(), voxelised, repaired, open, clouds, sheets, unreadable);
  // assimp 5.2 reads about three quarters of the corpus; each of those must voxelise.
  EXPECT_GE(voxelised, 300u);
  EXPECT_GE(open, 100u);  // real files are rarely closed: the repair path is what runs
  EXPECT_GE(clouds, 5u);
}

}  // namespace
}  // namespace voxcd
