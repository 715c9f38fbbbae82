// Where the package's own files are at run time: found from the directory of the loaded host library, so that an
// installed package works wherever it was installed (`cmake --install build --prefix P`) and the build tree works
// the same way. Nothing here refers to the source tree.
#pragma once

#include <string>
#include <vector>

namespace voxcd {

// The directory of the RTL and its file list (P/share/voxcd/rtl; build/share/voxcd/rtl in the build tree).
// Throws std::runtime_error naming the places it looked when neither holds voxcd.f.
std::string rtl_dir();

// The SystemC platform server of the sysc backends: $VOXCD_SYSC_SERVER, else P/libexec/voxcd/voxcd_sysc_server,
// else next to the library (the build tree). Throws std::runtime_error naming the places it looked.
std::string sysc_server_path();

// The rtl backend's module, which drives the Verilated models (voxcd_rtl_backend.so): $VOXCD_RTL_MODULE, else
// P/lib/voxcd/voxcd_rtl_backend.so, else next to the library (the build tree). With `coverage`, the module of the
// coverage models (voxcd_rtl_cov_backend.so, $VOXCD_RTL_COV_MODULE). Throws std::runtime_error naming the places it
// looked.
std::string rtl_module_path(bool coverage = false);

// The command that builds the device models (the rtl module, the SystemC models and server) for the library in use:
// `cmake --build DIR --target voxcd_models` when the library is in a build tree DIR; "" for an installed package.
std::string models_build_command();

// The files of an RTL file list (voxcd.f: one file per line relative to the list, // comments), as full paths.
// Throws std::runtime_error when the list cannot be read or names no file.
std::vector<std::string> rtl_files(const std::string& dir);

}  // namespace voxcd
