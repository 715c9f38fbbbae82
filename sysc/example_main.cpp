// voxcd_sysc_example: runs a conformance vector file through the example platform (a host processor and the
// device behind its TLM-2.0 socket) and prints what came back and how long it took, in simulated and wall time.
//   voxcd_sysc_example --target rtl|tlm FILE [--lanes L] [--clock-ns N] [--print] [--trace FILE.fst]
#include <chrono>
#include <cstdio>
#include <string>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/vectors.h"
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

struct Args {
  PlatformOptions opt;
  std::string file;
  int lanes = 0;
  bool print = false;
};

// Reads the command line into `args`; "" when it is good, else why not.
std::string parse_args(int argc, char** argv, Args& args) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string { return i + 1 < argc ? argv[++i] : ""; };
    if (a == "--target") {
      const auto k = parse_target(value());
      if (!k) return "--target takes rtl or tlm";
      args.opt.target = *k;
    } else if (a == "--lanes") {
      args.lanes = std::atoi(value().c_str());
    } else if (a == "--clock-ns") {
      args.opt.clock_period = sc_core::sc_time(std::atof(value().c_str()), sc_core::SC_NS);
    } else if (a == "--trace") {
      args.opt.trace_path = value();
    } else if (a == "--print") {
      args.print = true;
    } else if (!a.empty() && a[0] != '-' && args.file.empty()) {
      args.file = a;
    } else {
      return "unexpected argument " + a;
    }
  }
  return args.file.empty() ? "no vector file" : "";
}

// What a run of the file gave: its records, the device's registers and the simulated and wall times.
struct Run {
  std::vector<Record> got;
  uint64_t cycles_reg = 0, id = 0;
  sc_core::sc_time loaded, ran;
  double wall_run = 0, wall_all = 0;
};

// Loads the file's memory and runs its jobs through the platform.
Run run_file(Platform& platform, const VectorFile& vf) {
  Run r;
  const auto t0 = std::chrono::steady_clock::now();
  platform.execute([&](HostCpu& cpu) { cpu.load(vf.memory); });
  r.loaded = sc_core::sc_time_stamp();
  const auto t1 = std::chrono::steady_clock::now();
  platform.execute([&](HostCpu& cpu) {
    r.id = cpu.read_reg(kRegId);
    r.got = cpu.run(vf.jobs);
    r.cycles_reg = cpu.read_reg(kRegCycles);
  });
  r.wall_run = seconds_since(t1);
  r.wall_all = seconds_since(t0);
  r.ran = sc_core::sc_time_stamp() - r.loaded;
  return r;
}

// Prints the run and whether it matches the file (cycles too when the file is for these LANES); 0 if it does.
int report(const Args& args, const VectorFile& vf, const Run& r) {
  const PlatformOptions& opt = args.opt;
  if (args.print)
    for (const Record& rec : r.got) std::printf("%s\n", rec.to_string().c_str());
  size_t hits = 0, lookups = 0;
  for (const Record& rec : r.got) hits += rec.kind == Record::Hit;
  for (const Job& j : vf.jobs) lookups += j.shell_count;
  // Cycles in the file are for its own LANES.
  const bool cycles = !args.lanes || args.lanes == vf.config.LANES;
  const std::string diff = compare_streams(vf, r.got, cycles);
  std::printf("target %s, device id %016llx, %s\n", target_name(opt.target), (unsigned long long)r.id,
              opt.config.to_string().c_str());
  std::printf("memory: %zu shell words, %zu voxmap words loaded in %s\n", vf.memory.shell.size(),
              vf.memory.map.size(), r.loaded.to_string().c_str());
  std::printf("jobs: %zu, lookups: %zu, records: %zu (%zu hits)\n", vf.jobs.size(), lookups, r.got.size(), hits);
  std::printf("device cycles (CYCLES register): %llu = %s at %s per cycle\n", (unsigned long long)r.cycles_reg,
              (opt.clock_period * double(r.cycles_reg)).to_string().c_str(), opt.clock_period.to_string().c_str());
  std::printf("simulated time of the run: %s (staging, launch and read-out included)\n", r.ran.to_string().c_str());
  std::printf("wall time: %.3f s for the run, %.3f s in all; %.0f jobs/s, %.0f lookups/s\n", r.wall_run, r.wall_all,
              double(vf.jobs.size()) / r.wall_run, double(lookups) / r.wall_run);
  std::printf("%s: %s\n", args.file.c_str(),
              diff.empty() ? (cycles ? "matches the file (records and cycles)" : "matches the file (records)")
                           : ("MISMATCH: " + diff).c_str());
  return diff.empty() ? 0 : 1;
}

}  // namespace

int sc_main(int argc, char** argv) {
  Args args;
  if (const std::string why = parse_args(argc, argv, args); !why.empty()) return usage(why);
  try {
    const VectorFile vf = read_vectors(args.file);
    args.opt.config = vf.config;
    if (args.lanes) args.opt.config.LANES = args.lanes;
    Platform platform("platform", args.opt);
    return report(args, vf, run_file(platform, vf));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "voxcd_sysc_example: %s\n", e.what());
    return 2;
  }
}
