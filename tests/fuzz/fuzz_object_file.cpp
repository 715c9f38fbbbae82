// Fuzz target: the object file reader (read_object, what voxcd info, pair and simulate read). ObjectFileError is
// the documented error and must start with the path. A file that reads is written back and read again: the copy
// must hold the same voxmap and shell.
#include <cstdio>
#include <string>

#include "voxcd/host/object/object_file.h"
#include "tests/fuzz/fuzz_common.h"

using namespace voxcd;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = fuzz::scratch_path(".vox");
  fuzz::write_bytes(path, data, size);
  ObjectFile obj;
  bool ok = false;
  try {
    obj = read_object(path);
    ok = true;
  } catch (const ObjectFileError& e) {
    fuzz::expect_prefix(e.what(), path + ":", "ObjectFileError");
  }
  std::remove(path.c_str());
  if (!ok) return 0;
  const std::string copy = fuzz::scratch_path(".copy.vox");
  write_object(copy, obj);
  const ObjectFile again = read_object(copy);
  std::remove(copy.c_str());
  if (again.voxmap.words() != obj.voxmap.words() || again.voxmap.dims() != obj.voxmap.dims() ||
      again.shell.cells != obj.shell.cells || again.source != obj.source)
    fuzz::finding(path + ": the object read back after write_object differs");
  return 0;
}
