// voxcd_sysc_example: runs a conformance vector file through the example platform (a host processor and the
// device behind its TLM-2.0 socket) and prints what came back and how long it took, in simulated and wall time.
//   voxcd_sysc_example --target rtl|tlm FILE [--lanes L] [--clock-ns N] [--print] [--trace FILE.fst]
#include <chrono>
#include <cstdio>
#include <string>

#include "voxcd/ref/vectors.h"
#include "voxcd/sysc/address_map.h"
#include "voxcd/sysc/platform.h"

using namespace voxcd;
using namespace voxcd::sysc;

namespace {

int usage(const std::string& why) {
  std::fprintf(stderr,
               "voxcd_sysc_example: %s\nusage: voxcd_sysc_example --target rtl|tlm FILE [--lanes L] [--clock-ns N] "
               "[--print] [--trace FILE.fst]\n",
               why.c_str());
  return 2;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int sc_main(int argc, char** argv) {
  PlatformOptions opt;
  std::string file;
  int lanes = 0;
  bool print = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--target") {
      const auto k = parse_target(value());
      if (!k) return usage("--target takes rtl or tlm");
      opt.target = *k;
    } else if (a == "--lanes") {
      lanes = std::atoi(value().c_str());
    } else if (a == "--clock-ns") {
      opt.clock_period = sc_core::sc_time(std::atof(value().c_str()), sc_core::SC_NS);
    } else if (a == "--trace") {
      opt.trace_path = value();
    } else if (a == "--print") {
      print = true;
    } else if (!a.empty() && a[0] != '-' && file.empty()) {
      file = a;
    } else {
      return usage("unexpected argument " + a);
    }
  }
  if (file.empty()) return usage("no vector file");
  try {
    const VectorFile vf = read_vectors(file);
    opt.config = vf.config;
    if (lanes) opt.config.LANES = lanes;
    Platform platform("platform", opt);

    const auto t0 = std::chrono::steady_clock::now();
    platform.execute([&](HostCpu& cpu) { cpu.load(vf.memory); });
    const sc_core::sc_time loaded = sc_core::sc_time_stamp();
    std::vector<Record> got;
    uint64_t cycles_reg = 0, id = 0;
    const auto t1 = std::chrono::steady_clock::now();
    platform.execute([&](HostCpu& cpu) {
      id = cpu.read_reg(kRegId);
      got = cpu.run(vf.jobs);
      cycles_reg = cpu.read_reg(kRegCycles);
    });
    const double wall_run = seconds_since(t1), wall_all = seconds_since(t0);
    const sc_core::sc_time ran = sc_core::sc_time_stamp() - loaded;

    if (print)
      for (const Record& r : got) std::printf("%s\n", r.to_string().c_str());
    size_t hits = 0, lookups = 0;
    for (const Record& r : got) hits += r.kind == Record::Hit;
    for (const Job& j : vf.jobs) lookups += j.shell_count;
    // Cycles in the file are for its own LANES.
    const bool cycles = !lanes || lanes == vf.config.LANES;
    const std::string diff = compare_streams(vf, got, cycles);
    std::printf("target %s, device id %016llx, %s\n", target_name(opt.target), (unsigned long long)id,
                opt.config.to_string().c_str());
    std::printf("memory: %zu shell words, %zu voxmap words loaded in %s\n", vf.memory.shell.size(),
                vf.memory.map.size(), loaded.to_string().c_str());
    std::printf("jobs: %zu, lookups: %zu, records: %zu (%zu hits)\n", vf.jobs.size(), lookups, got.size(), hits);
    std::printf("device cycles (CYCLES register): %llu = %s at %s per cycle\n", (unsigned long long)cycles_reg,
                (opt.clock_period * double(cycles_reg)).to_string().c_str(), opt.clock_period.to_string().c_str());
    std::printf("simulated time of the run: %s (staging, launch and read-out included)\n", ran.to_string().c_str());
    std::printf("wall time: %.3f s for the run, %.3f s in all; %.0f jobs/s, %.0f lookups/s\n", wall_run, wall_all,
                double(vf.jobs.size()) / wall_run, double(lookups) / wall_run);
    std::printf("%s: %s\n", file.c_str(),
                diff.empty() ? (cycles ? "matches the file (records and cycles)" : "matches the file (records)")
                             : ("MISMATCH: " + diff).c_str());
    return diff.empty() ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "voxcd_sysc_example: %s\n", e.what());
    return 2;
  }
}
