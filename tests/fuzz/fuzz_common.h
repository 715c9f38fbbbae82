// Shared by the fuzz targets: a per-process scratch file, and the one way a target reports a finding (abort, which
// libFuzzer and the replay driver both catch). A target catches the exception types the code under test documents
// and checks that their text names the input; any other exception escapes and is a finding too.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace voxcd::fuzz {

// A file name of this process in $TMPDIR (or /tmp) ending in `suffix`: parallel fuzz jobs do not share files.
inline std::string scratch_path(const std::string& suffix) {
  const char* dir = std::getenv("TMPDIR");
  return std::string(dir && *dir ? dir : "/tmp") + "/voxcd_fuzz_" + std::to_string(getpid()) + suffix;
}

inline void write_bytes(const std::string& path, const uint8_t* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  if (!out) {
    std::fprintf(stderr, "fuzz: cannot write %s\n", path.c_str());
    std::abort();
  }
}

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FINDING: %s\n", what.c_str());
  std::abort();
}

// An error text must say where: it starts with the file (or name) the input was given as.
inline void expect_prefix(const std::string& text, const std::string& prefix, const char* kind) {
  if (text.compare(0, prefix.size(), prefix) != 0)
    finding(std::string(kind) + " does not start with '" + prefix + "': " + text);
}

}  // namespace voxcd::fuzz
