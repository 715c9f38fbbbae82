// The cpu backend's lookup kernels alone (ref/fast: FastRunner), as bench/kernel_revisions.sh builds them at several
// git revisions beside this same program: nanoseconds per point per core of COUNT jobs, 2-bit and distance (SB 8)
// voxmaps, in cache (32^3 voxels) and not (1024 x 1024 x 64), and batches of many 24-point jobs timed with their
// cycles (what a simulation frame's small jobs cost around the lookups), on one thread (its CPU time) and two (wall
// time, per core: times two). It uses only FastRunner's
// constructor, load and run_into and ref/'s pose quantisation, which every revision has, so the same source measures
// each revision's kernels.
//   bench_kernel [--repeats N]                  one line per case: "case threads ns_per_point hits", and per case
//                                               "case:first-batch 1 ns_per_point hits": the first batch on one
//                                               thread (bench/kernel_revisions.sh reads only the former)
//   bench_kernel --count CASE JOBS              runs JOBS jobs of CASE once on one thread (for callgrind: the
//                                               difference of two counts is the kernel's instructions)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <random>
#include <string>
#include <vector>

#include "bench/lookup_scene.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"

using namespace voxcd;

namespace {

struct Case {
  const char* name;
  uint32_t nx, ny, nz;
  size_t points, jobs;
  int sb;       // 0: 2-bit states; else a distance voxmap of SB bits
  bool cycles;  // the completion records timed too (a batch of many small jobs: the cost around the lookups)
};

const Case kCases[] = {
    {"2bit-in-cache", 32, 32, 32, 4096, 256, 0, false},
    {"2bit-out-of-cache", 1024, 1024, 64, 65536, 16, 0, false},
    {"distance-in-cache", 32, 32, 32, 4096, 256, 8, false},
    {"distance-out-of-cache", 1024, 1024, 64, 65536, 16, 8, false},
    {"2bit-small-jobs", 32, 32, 32, 24, 16384, 0, true},
    {"distance-small-jobs", 32, 32, 32, 24, 16384, 8, true},
};

DeviceConfig config_of(const Case& c) {
  DeviceConfig cfg;
  cfg.MAW = c.sb ? 25 : 22;  // room for the largest map
  if (c.sb) cfg.SB = c.sb;
  return cfg;
}

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// The calling thread's CPU time: on a shared machine the time it ran, not the time it waited for a core.
double cpu_now() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

int usage() {
  std::fprintf(stderr, "usage: bench_kernel [--repeats N] | bench_kernel --count CASE JOBS\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 7;
  std::string count_case;
  size_t count_jobs = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--count") && i + 2 < argc) count_case = argv[++i], count_jobs = size_t(std::atol(argv[++i]));
    else return usage();
  }
  if (repeats < 1) return usage();
  for (const Case& c : kCases) {
    if (!count_case.empty() && count_case != c.name) continue;
    const DeviceConfig cfg = config_of(c);
    DeviceMemory mem;
    Job job;
    bench::lookup_scene(cfg, c.nx, c.ny, c.nz, c.points, 7, mem, job);
    std::vector<Record> out;
    if (!count_case.empty()) {
      FastRunner runner(cfg, 1);
      runner.load(mem);
      runner.run_into(std::vector<Job>(count_jobs, job), out, c.cycles);
      std::printf("%s %zu jobs %u hits\n", c.name, count_jobs, out.empty() ? 0u : out.back().hits);
      return 0;
    }
    const std::vector<Job> batch(c.jobs, job);
    double first_ns = 0;
    for (unsigned threads : {1u, 2u}) {
      FastRunner runner(cfg, threads);
      runner.load(mem);
      const double w0 = cpu_now();
      runner.run_into(batch, out, c.cycles);  // warm-up: the first batch on a freshly loaded runner
      if (threads == 1)  // what the first batch costs above the others (a distance map's copy in cell order, built
                         // at its first job: ref/fast/detail/node_quads.h), per point of the batch
        first_ns = (cpu_now() - w0) * 1e9 / double(c.points * c.jobs);
      std::vector<double> t;
      for (int r = 0; r < repeats; ++r) {
        // One thread: its CPU time. Two: the wall time (the pool's workers spin between batches, so their CPU time
        // is no measure), which the machine's other load inflates.
        const double t0 = threads == 1 ? cpu_now() : now();
        runner.run_into(batch, out, c.cycles);
        t.push_back((threads == 1 ? cpu_now() : now()) - t0);
      }
      std::sort(t.begin(), t.end());
      const double ns = t[t.size() / 2] * 1e9 / double(c.points * c.jobs) * threads;  // per point per core
      std::printf("%s %u %.4f %u\n", c.name, threads, ns, out.back().hits);
      if (threads == 1) std::printf("%s:first-batch 1 %.4f %u\n", c.name, first_ns, out.back().hits);
    }
  }
  if (!count_case.empty()) {
    std::fprintf(stderr, "bench_kernel: no case '%s'\n", count_case.c_str());
    return 2;
  }
  return 0;
}
