// Lookup speed of the device backends on the host: nanoseconds per shell point for the cpu backend on one core
// and on every core, against ref/ (the peer: the same contract, one point at a time) in the same run; with the
// voxmap in cache (32^3 voxels, 8 KiB) and not (1024 x 1024 x 64 voxels, 16 MiB, points spread over all of it).
// Writes a markdown table to stdout (and to --out FILE).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "bench/bench_common.h"
#include "bench/lookup_scene.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/float_model.h"

using namespace voxcd;

namespace {

struct Scenario {
  const char* name;
  uint32_t nx, ny, nz;
  size_t points, jobs;
};

}  // namespace

int main(int argc, char** argv) {
  std::string out_path;
  int repeats = 7;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else {
      std::fprintf(stderr, "usage: bench_device [--out FILE] [--repeats N]\n");
      return 2;
    }
  }
  DeviceConfig cfg;
  cfg.MAW = 22;  // room for the 16 MiB map
  const Scenario scenarios[] = {
      {"in cache: 32^3 voxmap (8 KiB), 4096-point shell", 32, 32, 32, 4096, 256},
      {"not in cache: 1024x1024x64 voxmap (16 MiB), 65536-point shell", 1024, 1024, 64, 65536, 16}};
  std::ostringstream md;
  md << bench::provenance(argc, argv) << "\n\n";
  md << "| voxmap | backend | threads | ns per point (median of " << repeats
     << "; one thread: its CPU time, all: wall time) | ratio to ref |\n"
     << "|---|---|---|---|---|\n";
  for (const Scenario& s : scenarios) {
    DeviceMemory mem;
    Job job;
    bench::lookup_scene(cfg, s.nx, s.ny, s.nz, s.points, 7, mem, job);
    const std::vector<Job> batch(s.jobs, job);
    double ref_ns = 0;
    uint32_t ref_hits = 0;
    struct Run {
      const char* backend;
      unsigned threads;
    };
    for (Run r : {Run{"ref", 1}, Run{"cpu", 1}, Run{"cpu", 0}}) {
      DeviceOptions opt;
      opt.threads = r.threads;
      auto dev = make_device(r.backend, cfg, opt);
      dev->load(mem);
      std::vector<Record> recs;
      dev->run(batch);  // warm-up
      // One thread: its CPU time (on a shared machine the time it ran, not the time it waited for a core); every
      // thread: the wall time.
      const int reps = r.backend == std::string("ref") ? 3 : repeats;
      double t = 0;
      if (r.threads == 1) {
        std::vector<double> ts;
        for (int k = 0; k < reps; ++k) {
          const double t0 = bench::thread_cpu_seconds();
          recs = dev->run(batch);
          ts.push_back(bench::thread_cpu_seconds() - t0);
        }
        t = bench::median(ts);
      } else {
        t = bench::median_time(reps, [&] { recs = dev->run(batch); });
      }
      const double ns = t * 1e9 / double(s.points * s.jobs);
      const uint32_t hits = recs.back().hits;
      if (r.backend == std::string("ref")) ref_ns = ns, ref_hits = hits;
      if (hits != ref_hits) {
        std::fprintf(stderr, "%s disagrees with ref: %u vs %u hits\n", r.backend, hits, ref_hits);
        return 1;
      }
      char line[256];
      std::snprintf(line, sizeof line, "| %s | %s | %s | %.2f | %.1fx faster |\n", s.name, r.backend,
                    r.threads ? std::to_string(r.threads).c_str() : "all", ns, ref_ns / ns);
      md << line;
      std::fprintf(stderr, "%s", line);
    }
  }
  md << "\nMachine: " << bench::machine_description()
     << ". COUNT jobs in batches (in cache: 256 jobs of 4096 points; not in cache: 16 of 65536); hits agree "
        "with ref in every row.\n";
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  return 0;
}
