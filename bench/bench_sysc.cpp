// bench_sysc: simulation speed of the SystemC backends (sysc-rtl: the Verilated RTL behind the TLM-2.0 socket;
// sysc-tlm: the loosely-timed model) beside the plain Verilated C++ model (rtl) and the reference (ref), on the same
// generated jobs in the same run. Every backend's stream and cycles must equal ref's; the table (docs/systemc.md)
// gives medians over repeats. Each repeat makes a fresh device (for sysc-*, a fresh server process), loads it and
// runs the jobs twice: the first run pays the process's first touches (page faults, cold caches), the second is
// what a long simulation sees per batch.
//   bench_sysc [--seed S] [--jobs N] [--cloud P] [--lanes L] [--repeats R]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/device/detail/sysc.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"

using namespace voxcd;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  uint64_t seed = 1;
  size_t jobs = 300, cloud = 4000, repeats = 5;
  int lanes = 4;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const unsigned long long v = std::strtoull(argv[i + 1], nullptr, 0);
    if (a == "--seed") seed = v;
    else if (a == "--jobs") jobs = v;
    else if (a == "--cloud") cloud = v;
    else if (a == "--lanes") lanes = int(v);
    else if (a == "--repeats") repeats = v;
    else {
      std::fprintf(stderr, "usage: bench_sysc [--seed S] [--jobs N] [--cloud P] [--lanes L] [--repeats R]\n");
      return 2;
    }
  }
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs;
  g.cloud_points = cloud;
  g.config.LANES = lanes;
  const GeneratedVectors v = generate_vectors(g);
  std::vector<Record> want = run_stream(v.config, v.memory, v.jobs);
  annotate_cycles(v.config, v.jobs, want);
  uint64_t points = 0, cycles = 0, hits = 0;
  for (const Job& j : v.jobs) points += j.shell_count;
  for (const Record& r : want) {
    if (r.kind == Record::Done) cycles += *r.cycles;
    hits += r.kind == Record::Hit;
  }
  std::printf("bench_sysc: seed %llu, %zu jobs, %llu lookups, %llu hits, %llu device cycles, LANES %d, %zu repeats\n\n",
              (unsigned long long)seed, v.jobs.size(), (unsigned long long)points, (unsigned long long)hits,
              (unsigned long long)cycles, lanes, repeats);
  std::printf("| backend | run (ms) | jobs/s | lookups/s | device cycles/s | in-simulation (ms) | again: run (ms) | "
              "again: in-simulation (ms) | cycles equal ref |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
  double rtl[4] = {}, tlm[4] = {};  // run, in-simulation, again: run, again: in-simulation
  int failures = 0;
  for (const std::string b : {"ref", "cpu", "rtl", "sysc-rtl", "sysc-tlm"}) {
    std::vector<double> ms[4];
    bool equal = true;
    for (size_t r = 0; r < repeats; ++r) {
      DeviceOptions opt;
      opt.threads = 1;  // cpu: one thread, as the TLM target computes
      auto dev = make_device(b, v.config, opt);
      dev->load(v.memory);
      for (int again = 0; again < 2; ++again) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::vector<Record> got = dev->run(v.jobs);
        ms[2 * again].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        ms[2 * again + 1].push_back(sysc_last_run(*dev).wall_s * 1e3);
        equal = equal && got.size() == want.size();
        for (size_t i = 0; equal && i < got.size(); ++i) equal = got[i].same_as(want[i], true);
      }
    }
    double m[4];
    for (int k = 0; k < 4; ++k) m[k] = median(ms[k]);
    if (b == "sysc-rtl") std::copy(m, m + 4, rtl);
    if (b == "sysc-tlm") std::copy(m, m + 4, tlm);
    failures += !equal;
    const bool sim = b.rfind("sysc", 0) == 0;
    const auto fmt = [&](double x) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.2f", x);
      return sim ? std::string(buf) : std::string();
    };
    std::printf("| %s | %.2f | %.3g | %.3g | %.3g | %s | %.2f | %s | %s |\n", b == "cpu" ? "cpu (1 thread)" : b.c_str(),
                m[0], double(v.jobs.size()) / m[0] * 1e3, double(points) / m[0] * 1e3, double(cycles) / m[0] * 1e3,
                fmt(m[1]).c_str(), m[2], fmt(m[3]).c_str(), equal ? "yes" : "NO");
  }
  std::printf("\nsysc-tlm against sysc-rtl: first run %.0fx per run, %.0fx inside the simulation; run again %.0fx per "
              "run, %.0fx inside the simulation\n",
              rtl[0] / tlm[0], rtl[1] / tlm[1], rtl[2] / tlm[2], rtl[3] / tlm[3]);
  return failures ? 1 : 0;
}
