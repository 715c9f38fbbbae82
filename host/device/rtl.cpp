// The rtl backend, host side: the module that drives the Verilated models (host/device/detail/rtl_module.h) is
// loaded on first use, so that the library and the tool build and run without the models; what the backend lacks
// is said once, with the command that builds it (docs/build.md).
#include "voxcd/host/device/detail/rtl.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>

#include "voxcd/host/device/detail/rtl_module.h"
#include "voxcd/host/package/paths.h"
#include "voxcd_rtl_abi.h"  // VOXCD_RTL_MODULE_ABI (host/device/rtl_abi.cmake)

namespace voxcd {
namespace {

// The module, or why there is none.
struct Loaded {
  const RtlModule* module = nullptr;
  std::string why_not;
};

// For a wide configuration (more than 8 lanes) without a model: how wide models are built.
std::string wide_hint(const DeviceConfig& cfg) {
  if (cfg.LANES <= 8) return "";
  return "; wide devices (16 to 64 lanes) are built on demand: add the configuration to VOXCD_RTL_WIDE_FULL_MODELS "
         "(it has LANES 16, 32, 64, LANES 32 BANKS 8 BL 3, LANES 64 BANKS 16 BL 3 and LANES 32 DEPTH 5), configure "
         "with -DVOXCD_RTL_WIDE=ON and build voxcd_models (docs/build.md, \"Options\")";
}

// What to run to (re)build the models, for the end of a message.
std::string rebuild_hint() {
  const std::string cmd = models_build_command();
  if (!cmd.empty()) return "build them with `" + cmd + "`";
  return "build them with `cmake --build BUILD --target voxcd_models` before `cmake --install BUILD`";
}

Loaded load_from(const std::string& path) {
  Loaded l;
  void* h = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!h) {
    const char* err = ::dlerror();
    l.why_not = "cannot load the RTL models' module " + path + ": " + (err ? err : "unknown error") + " (" +
                rebuild_hint() + ")";
    return l;
  }
  // Loaded modules stay loaded: devices made from them may outlive any caller.
  using AbiFn = const char* (*)();
  using ModuleFn = const RtlModule* (*)();
  auto abi = reinterpret_cast<AbiFn>(::dlsym(h, "voxcd_rtl_module_abi"));
  auto module = reinterpret_cast<ModuleFn>(::dlsym(h, "voxcd_rtl_module"));
  if (!abi || !module) {
    l.why_not = path + " is not an RTL models' module (no voxcd_rtl_module entry points)";
  } else if (std::strcmp(abi(), VOXCD_RTL_MODULE_ABI) != 0) {
    l.why_not = "the RTL models' module " + path + " was built from other sources than this library (" +
                rebuild_hint() + ")";
  } else {
    l.module = module();
  }
  return l;
}

// The module of the ordinary models, or with `coverage` the coverage models' (docs/verification.md).
Loaded load(bool coverage = false) {
#if !VOXCD_DEVICE_MODELS
  if (!std::getenv(coverage ? "VOXCD_RTL_COV_MODULE" : "VOXCD_RTL_MODULE"))
    return {nullptr, "this build was configured without the device models (-DVOXCD_DEVICE_MODELS=OFF)"};
#endif
  std::string path;
  try {
    path = rtl_module_path(coverage);
  } catch (const std::runtime_error&) {
    const bool installed = models_build_command().empty();
    return {nullptr, std::string(installed ? "this installation has no RTL " : "the RTL ") +
                         (coverage ? "coverage models" : "models") + (installed ? "" : " are not built") + " (" +
                         rebuild_hint() + ")"};
  }
  // One load per path; a failure is tried again next time (the models may have been built meanwhile).
  static std::mutex mutex;
  static std::map<std::string, const RtlModule*> modules;
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = modules.find(path); it != modules.end()) return {it->second, ""};
  Loaded l = load_from(path);
  if (l.module) modules[path] = l.module;
  return l;
}

std::vector<DeviceConfig> family(const char* name) {
  const Loaded l = load();
  std::vector<DeviceConfig> out;
  if (!l.module) return out;
  for (const RtlModelInfo& m : l.module->models())
    if (m.family == name) out.push_back(m.config);
  return out;
}

}  // namespace

std::string rtl_unavailable() { return load().why_not; }

std::vector<int> rtl_lanes() {
  std::vector<int> out;
  for (const DeviceConfig& c : family("lanes")) out.push_back(c.LANES);
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<DeviceConfig> rtl_configs() { return family("derived"); }
std::vector<DeviceConfig> rtl_distance_configs() { return family("distance"); }
std::vector<DeviceConfig> rtl_banked_configs() { return family("banked"); }
std::vector<DeviceConfig> rtl_depth_configs() { return family("depth"); }
std::vector<DeviceConfig> rtl_sparse_configs() { return family("sparse"); }
std::vector<DeviceConfig> rtl_wide_configs() { return family("wide"); }

std::unique_ptr<Device> make_rtl_device(const DeviceConfig& cfg, const DeviceOptions& opt) {
  return make_rtl_device(cfg, opt, RtlFaults{});
}

std::unique_ptr<Device> make_rtl_device(const DeviceConfig& cfg, const DeviceOptions& opt, const RtlFaults& faults) {
  cfg.validate();
  const bool coverage = !opt.coverage_path.empty();
  const Loaded l = load(coverage);
  if (!l.module) throw DeviceError("rtl: " + l.why_not);
  if (std::unique_ptr<Device> d = l.module->make(cfg, opt, faults)) return d;
  if (coverage) {
    std::string built;
    for (const RtlModelInfo& m : l.module->models()) built += (built.empty() ? "" : "; ") + m.config.to_string();
    throw DeviceError("rtl: this build has coverage models for " + built + ", not " + cfg.to_string() +
                      " (the lists VOXCD_RTL_COVERAGE_MODELS and, with -DVOXCD_RTL_COVERAGE_FULL=ON, VOXCD_RTL_COVERAGE_FULL_MODELS; docs/verification.md)");
  }
  // No model of exactly this configuration: name the ones there are.
  std::string lanes, extra;
  for (const RtlModelInfo& m : l.module->models()) {
    if (m.family == "lanes")
      lanes += (lanes.empty() ? "" : ", ") + std::to_string(m.config.LANES);
    else
      extra += "; " + m.config.to_string();
  }
  DeviceConfig built;
  built.LANES = cfg.LANES;
  if (cfg.same_widths(built) && cfg.BANKS == built.BANKS && cfg.depth == built.depth)
    throw DeviceError("rtl: this build has models for LANES " + lanes + " at the default widths, not LANES " +
                      std::to_string(cfg.LANES) + " (the list VOXCD_RTL_LANES, docs/build.md)" + wide_hint(cfg));
  throw DeviceError("rtl: this build has models for the default widths (" + DeviceConfig{}.to_string() +
                    " with LANES " + lanes + ")" + extra + ", not for " + cfg.to_string() + wide_hint(cfg));
}

}  // namespace voxcd
