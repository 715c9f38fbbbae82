// FNV-1a 64 (Fowler, Noll, Vo): the one hash of bytes voxcd uses for checksums (object files' source hashes, the
// platform's data hashes) and for hashing points into tables.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace voxcd {

inline constexpr uint64_t kFnv1aBasis = 14695981039346656037ull;  // the 64-bit offset basis
inline constexpr uint64_t kFnv1aPrime = 1099511628211ull;         // the 64-bit prime

// h advanced over n bytes at data (start from kFnv1aBasis; chain calls to hash several pieces).
inline uint64_t fnv1a(const void* data, size_t n, uint64_t h = kFnv1aBasis) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * kFnv1aPrime;
  return h;
}

// FNV-1a 64 of a string's bytes.
inline uint64_t fnv1a(std::string_view s, uint64_t h = kFnv1aBasis) { return fnv1a(s.data(), s.size(), h); }

}  // namespace voxcd
