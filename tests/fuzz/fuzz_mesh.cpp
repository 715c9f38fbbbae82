// Fuzz target: the mesh loaders through load_mesh, the entry point voxcd voxelize and load_source use. The first
// byte picks the format (byte % 5, so 'A' to 'E' in the seeds: STL (ASCII or binary), PLY, OFF, RAW file, RAW
// parsed from memory by parse_raw), the rest is the file. OBJ has its own target (fuzz_mesh_obj.cpp): assimp's OBJ
// reader fills a 16 MiB line buffer for every file, a hundred times the cost of the others. fuzz_mesh.h says what
// is checked.
#include <string>

#include "tests/fuzz/fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const kExt[] = {".stl", ".ply", ".off", ".raw", ".memory.raw"};
  voxcd::fuzz::load_mesh_input(kExt[data[0] % 5], std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
  return 0;
}
