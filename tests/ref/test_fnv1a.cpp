// FNV-1a 64 (ref/fnv1a.h), the one byte hash: the published test vectors, chaining, and the object files' source
// hash computed with it.
#include <gtest/gtest.h>

#include <string>

#include "voxcd/host/object/object_file.h"
#include "voxcd/ref/fnv1a.h"

namespace voxcd {
namespace {

TEST(Fnv1a, PublishedVectors) {
  EXPECT_EQ(fnv1a(""), 0xcbf29ce484222325ull);
  EXPECT_EQ(fnv1a("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a("foobar"), 0x85944171f73967e8ull);
}

TEST(Fnv1a, ChainingIsHashingTheConcatenation) {
  const std::string a = "voxcd ", b = "object";
  EXPECT_EQ(fnv1a(b, fnv1a(a)), fnv1a(a + b));
  EXPECT_NE(fnv1a(a + b), fnv1a(b + a));
}

TEST(Fnv1a, ObjectFilesHashTheirSourceWithIt) {
  EXPECT_EQ(hash_bytes("shape:torus"), fnv1a("shape:torus"));
}

}  // namespace
}  // namespace voxcd
