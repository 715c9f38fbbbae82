// Base64 (RFC 4648, with padding) of bytes: how the viewer's data carries arrays inside JSON and HTML (the viewer and
// `voxcd view`'s command share it).
#pragma once

#include <cstddef>
#include <cstring>
#include <string>
#include <vector>

namespace voxcd::view::detail {

inline std::string base64(const void* data, size_t n) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < n; i += 3) {
    const unsigned v = unsigned(p[i]) << 16 | unsigned(p[i + 1]) << 8 | p[i + 2];
    for (int k = 3; k >= 0; --k) out += kAlphabet[(v >> (6 * k)) & 63];
  }
  if (i < n) {
    const unsigned v = unsigned(p[i]) << 16 | (i + 1 < n ? unsigned(p[i + 1]) << 8 : 0u);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += i + 1 < n ? kAlphabet[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

template <class T>
std::string base64(const std::vector<T>& v) {
  return base64(v.data(), v.size() * sizeof(T));
}

}  // namespace voxcd::view::detail
