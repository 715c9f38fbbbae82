#include "voxcd/host/package/paths.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#ifndef VOXCD_REL_LIBEXEC
#define VOXCD_REL_LIBEXEC "../libexec/voxcd"
#endif
#ifndef VOXCD_REL_MODULES
#define VOXCD_REL_MODULES "voxcd"
#endif
#ifndef VOXCD_REL_DATA
#define VOXCD_REL_DATA "../share/voxcd"
#endif

namespace voxcd {
namespace {

namespace fs = std::filesystem;

// The directory of the library this function is in.
fs::path library_dir() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&library_dir), &info) == 0 || !info.dli_fname)
    throw std::runtime_error("cannot tell where the voxcd library was loaded from (dladdr failed)");
  std::error_code ec;
  fs::path p = fs::canonical(info.dli_fname, ec);
  if (ec) p = info.dli_fname;
  return p.parent_path();
}

// The first of `candidates` for which ok() holds, or an error listing them all.
template <class Ok>
std::string first_of(const std::vector<fs::path>& candidates, const std::string& what, Ok ok) {
  std::string tried;
  for (const fs::path& c : candidates) {
    if (ok(c)) return c.lexically_normal().string();
    tried += (tried.empty() ? "" : ", ") + c.lexically_normal().string();
  }
  throw std::runtime_error("cannot find " + what + " (looked in " + tried + ")");
}

}  // namespace

std::string rtl_dir() {
  const fs::path lib = library_dir();
  return first_of({lib / VOXCD_REL_DATA / "rtl", lib / "share/voxcd/rtl"}, "the RTL file list voxcd.f",
                  [](const fs::path& d) { return fs::is_regular_file(d / "voxcd.f"); });
}

std::string sysc_server_path() {
  if (const char* e = std::getenv("VOXCD_SYSC_SERVER")) return e;
  const fs::path lib = library_dir();
  return first_of({lib / VOXCD_REL_LIBEXEC / "voxcd_sysc_server", lib / "voxcd_sysc_server"},
                  "the SystemC platform server voxcd_sysc_server (set VOXCD_SYSC_SERVER to its path)",
                  [](const fs::path& p) { return ::access(p.c_str(), X_OK) == 0; });
}

std::string rtl_module_path(bool coverage) {
  if (const char* e = std::getenv(coverage ? "VOXCD_RTL_COV_MODULE" : "VOXCD_RTL_MODULE")) return e;
  const fs::path lib = library_dir();
  const char* name = coverage ? "voxcd_rtl_cov_backend.so" : "voxcd_rtl_backend.so";
  return first_of({lib / VOXCD_REL_MODULES / name, lib / name}, std::string("the RTL models' module ") + name,
                  [](const fs::path& p) { return fs::is_regular_file(p); });
}

std::string models_build_command() {
  const fs::path lib = library_dir();
  // A build tree: CMake's cache is beside the library (every target's output is in the build directory).
  if (!fs::is_regular_file(lib / "CMakeCache.txt")) return "";
  return "cmake --build " + lib.string() + " --target voxcd_models";
}

std::vector<std::string> rtl_files(const std::string& dir) {
  const fs::path list = fs::path(dir) / "voxcd.f";
  std::ifstream in(list);
  if (!in) throw std::runtime_error("cannot read the RTL file list " + list.string());
  std::vector<std::string> files;
  std::string line;
  while (std::getline(in, line)) {
    const size_t b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line.compare(b, 2, "//") == 0) continue;
    const size_t e = line.find_last_not_of(" \t\r");
    files.push_back((fs::path(dir) / line.substr(b, e - b + 1)).string());
  }
  if (files.empty()) throw std::runtime_error("the RTL file list " + list.string() + " names no file");
  return files;
}

}  // namespace voxcd
