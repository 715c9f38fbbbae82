// voxcd_sysc_server: the example platform in a process of its own, serving one host-side Device (backends
// sysc-rtl and sysc-tlm) over the socket at file descriptor 3 (ref/server_protocol.h).
//   voxcd_sysc_server --target rtl|tlm --config "PW 24 ... LANES 4" [--trace FILE.fst]
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/server_protocol.h"
#include "voxcd/ref/vectors.h"
#include "voxcd/sysc/platform.h"

using namespace voxcd;
using namespace voxcd::sysc;

namespace {

int usage(const char* why) {
  std::fprintf(stderr, "voxcd_sysc_server: %s\nusage: voxcd_sysc_server --target rtl|tlm --config PAIRS [--trace FILE]\n",
               why);
  return 2;
}

void serve(Platform& p, Channel& ch) {
  // Kept between requests: a run that fits their capacity touches no new memory.
  std::vector<uint8_t> descriptors, records;
  for (;;) {
    uint8_t opb[8];
    if (!ch.get(opb, 8)) return;  // the Device was destroyed
    const uint64_t op = get_le(opb, 8);
    try {
      if (op == kOpLoad) {
        DeviceMemory mem;
        mem.shell.resize(ch.get_u64());
        for (ShellWord& w : mem.shell) {
          w.x = int64_t(ch.get_u64());
          w.y = int64_t(ch.get_u64());
          w.z = int64_t(ch.get_u64());
        }
        mem.map.resize(ch.get_u64());
        for (uint64_t& w : mem.map) w = ch.get_u64();
        p.execute([&](HostCpu& cpu) { cpu.load(mem); });
        ch.put_u64(0);
        ch.put_u64(sc_core::sc_time_stamp().value());
      } else if (op == kOpRun) {
        // The descriptors go to the device as they came and the records back as the device gave them. A malformed
        // descriptor is refused here, before anything runs.
        const size_t n = ch.get_u64();
        descriptors.resize(n * kJobBytes);
        if (n && !ch.get(descriptors.data(), descriptors.size())) throw std::runtime_error("short job descriptor");
        Job j;
        std::string why;
        for (size_t i = 0; i < n; ++i)
          if (!decode_job(&descriptors[i * kJobBytes], j, why)) throw std::runtime_error(why);
        const auto t0 = std::chrono::steady_clock::now();
        p.execute([&](HostCpu& cpu) { cpu.run_encoded(descriptors.data(), n, records); });
        const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - t0);
        ch.put_u64(0);
        ch.put_u64(records.size() / kRecordBytes);
        ch.put(records.data(), records.size());
        ch.put_u64(sc_core::sc_time_stamp().value());
        ch.put_u64(uint64_t(ns.count()));
      } else {
        throw std::runtime_error("unknown request " + std::to_string(op));
      }
    } catch (const std::exception& e) {
      std::string msg = e.what();
      if (!p.target().last_error().empty()) msg += " (" + p.target().last_error() + ")";
      ch.put_u64(1);
      ch.put_string(msg);
    }
    ch.flush();
  }
}

}  // namespace

int sc_main(int argc, char** argv) {
  PlatformOptions opt;
  bool have_target = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) return usage(("missing value after " + a).c_str());
    const std::string v = argv[++i];
    if (a == "--target") {
      const auto k = parse_target(v);
      if (!k) return usage(("unknown target " + v).c_str());
      opt.target = *k;
      have_target = true;
    } else if (a == "--config") {
      try {
        opt.config = parse_config_pairs(v, "--config");
      } catch (const std::exception& e) {
        return usage(e.what());
      }
    } else if (a == "--trace") {
      opt.trace_path = v;
    } else {
      return usage(("unknown option " + a).c_str());
    }
  }
  if (!have_target) return usage("--target is required");
  Channel ch(kServerFd, /*buffered=*/true);
  try {
    Platform platform("platform", opt);
    ch.put_u64(0);  // ready
    ch.flush();
    serve(platform, ch);
  } catch (const std::exception& e) {
    // Elaboration failed (no model for the configuration, ...): say why and end.
    try {
      ch.put_u64(1);
      ch.put_string(e.what());
      ch.flush();
    } catch (...) {
    }
    return 1;
  }
  return 0;
}
