// Fuzz target: the conformance vector parser (parse_vectors, what voxcd conform reads). VectorError is the
// documented error and must start with "<name>:". A file that parses is run on the reference model when it is
// small, and the stream compared with the file's expectations (a difference is a normal result, an exception is
// not: the parser has already checked every job against the memory).
#include <string>

#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/vectors.h"
#include "tests/fuzz/fuzz_common.h"

using namespace voxcd;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string name = "fuzz.vec";
  VectorFile f;
  try {
    f = parse_vectors(std::string(reinterpret_cast<const char*>(data), size), name);
  } catch (const VectorError& e) {
    fuzz::expect_prefix(e.what(), name + ":", "VectorError");
    return 0;
  }
  uint64_t lookups = 0;
  for (const Job& j : f.jobs) lookups += j.shell_count;
  if (lookups > (1u << 16)) return 0;  // a valid file that only costs time
  const std::vector<Record> got = run_stream(f.config, f.memory, f.jobs);
  compare_streams(f, got, false);
  return 0;
}
