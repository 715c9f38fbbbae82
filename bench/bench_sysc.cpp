// bench_sysc: simulation speed of the SystemC backends (sysc-rtl: the Verilated RTL behind the TLM-2.0 socket;
// sysc-tlm: the loosely-timed model) beside the plain Verilated C++ model (rtl) and the reference (ref), on the same
// generated jobs in the same run. Every backend's stream and cycles must equal ref's; the table (docs/systemc.md)
// gives medians over repeats.
//   bench_sysc [--seed S] [--jobs N] [--cloud P] [--lanes L] [--repeats R]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "host/conform_gen.h"
#include "host/device.h"
#include "host/device_sysc.h"
#include "ref/pipeline.h"
#include "ref/timing.h"

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
  std::printf("| backend | run (ms) | jobs/s | lookups/s | device cycles/s | in-simulation (ms) | cycles equal ref |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---|\n");
  double rtl_ms = 0, tlm_ms = 0, rtl_sim_ms = 0, tlm_sim_ms = 0;
  int failures = 0;
  for (const std::string b : {"ref", "rtl", "sysc-rtl", "sysc-tlm"}) {
    std::vector<double> ms, sim_ms;
    bool equal = true;
    for (size_t r = 0; r < repeats; ++r) {
      auto dev = make_device(b, v.config);
      dev->load(v.memory);
      const auto t0 = std::chrono::steady_clock::now();
      const std::vector<Record> got = dev->run(v.jobs);
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      sim_ms.push_back(sysc_last_run(*dev).wall_s * 1e3);
      equal = equal && got.size() == want.size();
      for (size_t i = 0; equal && i < got.size(); ++i) equal = got[i].same_as(want[i], true);
    }
    const double m = median(ms), s = median(sim_ms);
    if (b == "sysc-rtl") rtl_ms = m, rtl_sim_ms = s;
    if (b == "sysc-tlm") tlm_ms = m, tlm_sim_ms = s;
    failures += !equal;
    const std::string sim = b.rfind("sysc", 0) == 0 ? std::to_string(s).substr(0, std::to_string(s).find('.') + 3) : "";
    std::printf("| %s | %.2f | %.3g | %.3g | %.3g | %s | %s |\n", b.c_str(), m, double(v.jobs.size()) / m * 1e3,
                double(points) / m * 1e3, double(cycles) / m * 1e3, sim.c_str(), equal ? "yes" : "NO");
  }
  std::printf("\nsysc-tlm is %.0fx faster than sysc-rtl per run (%.0fx inside the simulation, without the process "
              "traffic)\n",
              rtl_ms / tlm_ms, rtl_sim_ms / tlm_sim_ms);
  return failures ? 1 : 0;
}
