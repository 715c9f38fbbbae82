// The one seed of every random test: VOXCD_SEED when it is set, else the test's own fixed default. Every call prints
// the seed it returns with how to replay it; tests/testing/check_seeds.py (ctest -R testing.seeds) checks that no test seeds a generator any
// other way.
#pragma once

#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace voxcd::test {

// VOXCD_SEED parsed: a decimal or 0x-hexadecimal unsigned 64-bit number; anything else is an error that says so.
inline uint64_t parse_seed(const char* text) {
  const std::string s = text;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str(), &end, 0);
  if (s.empty() || s[0] < '0' || s[0] > '9' || *end != '\0' || errno == ERANGE)
    throw std::invalid_argument("VOXCD_SEED: '" + s + "' is not an unsigned 64-bit number (decimal or 0x hex)");
  return v;
}

// The seed of a random test: VOXCD_SEED if set, else `fallback` (the test's default); printed with how to replay it.
inline uint64_t seed(uint64_t fallback = 20240601) {
  const char* s = std::getenv("VOXCD_SEED");
  const uint64_t v = s ? parse_seed(s) : fallback;
  std::printf("seed %llu (replay with VOXCD_SEED=%llu)\n", (unsigned long long)v, (unsigned long long)v);
  std::fflush(stdout);
  return v;
}

}  // namespace voxcd::test
