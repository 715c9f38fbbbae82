// Fuzz target: Wavefront OBJ files through load_mesh (the whole input is the file). Apart from fuzz_mesh because
// assimp 5.2's OBJ reader fills a 16 MiB line buffer for every file: about 80 ms an input under ASan. fuzz_mesh.h
// says what is checked.
#include <string>

#include "tests/fuzz/fuzz_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  voxcd::fuzz::load_mesh_input(".obj", std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
