// Fuzz target: the JSON scene file parser (parse_scene_file, what voxcd simulate SCENE.json and voxcd size read).
// SceneFileError is the documented error and must start with "<name>: ". A file that parses must give a positive
// default accuracy and object count. make_scene is left out: it voxelises, and fuzz_scene covers its checks.
#include <cmath>
#include <string>
#include <string_view>

#include "voxcd/host/scene/scene_file.h"
#include "tests/fuzz/fuzz_common.h"

using namespace voxcd;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string name = "fuzz.json";
  try {
    const RunConfig f = parse_scene_file(std::string_view(reinterpret_cast<const char*>(data), size), name);
    const double acc = f.accuracy_or_default();
    if (!(acc > 0) || !std::isfinite(acc)) fuzz::finding(name + ": parsed, but its accuracy is " + std::to_string(acc));
    if (f.objects() == 0) fuzz::finding(name + ": parsed, but it has no objects");
  } catch (const SceneFileError& e) {
    fuzz::expect_prefix(e.what(), name + ": ", "SceneFileError");
  }
  return 0;
}
