#include "voxcd/sysc/platform.h"

#include "voxcd/sysc/axi_target.h"
#include "voxcd/sysc/rtl_target.h"
#include "voxcd/sysc/tlm_target.h"

namespace voxcd::sysc {

using namespace sc_core;

const char* target_name(TargetKind k) {
  return k == TargetKind::Rtl ? "rtl" : (k == TargetKind::RtlAxi ? "rtl-axi" : "tlm");
}

std::optional<TargetKind> parse_target(const std::string& s) {
  if (s == "rtl") return TargetKind::Rtl;
  if (s == "tlm") return TargetKind::Tlm;
  if (s == "rtl-axi") return TargetKind::RtlAxi;
  return std::nullopt;
}

Platform::Platform(sc_module_name name, const PlatformOptions& opt)
    : sc_module(name), cpu("cpu", opt.quantum, opt.burst), opt_(opt) {
  if (opt.target == TargetKind::Rtl)
    target_ = std::make_unique<RtlTarget>("device", opt.config, opt.clock_period, opt.access_latency, opt.trace_path);
  else if (opt.target == TargetKind::RtlAxi)
    target_ = std::make_unique<AxiRtlTarget>("device", opt.config, opt.clock_period, opt.access_latency);
  else
    target_ = std::make_unique<TlmTarget>("device", opt.config, opt.clock_period, opt.access_latency);
  cpu.socket.bind(target_->socket);
}

void Platform::execute(HostCpu::Task task) {
  cpu.post(std::move(task));
  run_until_idle({&cpu});
}

void run_until_idle(std::initializer_list<HostCpu*> hosts) {
  const auto busy = [&] {
    for (HostCpu* h : hosts)
      if (h->pending()) return true;
    return false;
  };
  while (busy()) {
    if (sc_get_status() != SC_ELABORATION && !sc_pending_activity())
      throw std::runtime_error("simulation starved with host tasks unfinished");
    sc_start();
  }
  for (HostCpu* h : hosts)
    if (std::exception_ptr e = h->take_error()) std::rethrow_exception(e);
}

}  // namespace voxcd::sysc
