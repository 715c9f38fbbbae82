// The cells of a tab-separated table's line and its figures, for the library's tables (the timing table, the energy
// table): each reader names its own error.
#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace voxcd::detail {

// The line's cells between tabs (one cell for a line without a tab).
inline std::vector<std::string> split_tabs(const std::string& line) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const size_t tab = line.find('\t', start);
    out.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
    if (tab == std::string::npos) return out;
    start = tab + 1;
  }
}

// The cells joined by spaces, as messages name columns.
inline std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

// A finite number that parses whole; false otherwise.
inline bool to_number(const std::string& text, double* v) {
  if (text.empty()) return false;
  std::istringstream in(text);
  in >> *v;
  return in && in.peek() == std::char_traits<char>::eof() && std::isfinite(*v);
}

}  // namespace voxcd::detail
