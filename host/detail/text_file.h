// A whole file read into memory, for the readers of the library's text formats (campaign, sweep and timing files,
// journals, yosys's output): each names its own error.
#pragma once

#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace voxcd::detail {

// The file's bytes; nullopt when it cannot be opened or read.
inline std::optional<std::string> read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return s.str();
}

}  // namespace voxcd::detail
