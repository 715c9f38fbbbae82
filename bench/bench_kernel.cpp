// The cpu backend's lookup kernels alone (ref/fast: FastRunner), as bench/kernel_revisions.sh builds them at several
// git revisions beside this same program: nanoseconds per point per core of COUNT jobs, 2-bit and distance (SB 8)
// voxmaps, in cache (32^3 voxels) and not (1024 x 1024 x 64), on one thread (its CPU time) and two (wall time, per
// core: times two). It uses only FastRunner's
// constructor, load and run_into and ref/'s pose quantisation, which every revision has, so the same source measures
// each revision's kernels.
//   bench_kernel [--repeats N]                  one line per case: "case threads ns_per_point hits"
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

#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"

using namespace voxcd;

namespace {

struct Case {
  const char* name;
  uint32_t nx, ny, nz;
  size_t points, jobs;
  int sb;  // 0: 2-bit states; else a distance voxmap of SB bits
};

const Case kCases[] = {
    {"2bit-in-cache", 32, 32, 32, 4096, 256, 0},
    {"2bit-out-of-cache", 1024, 1024, 64, 65536, 16, 0},
    {"distance-in-cache", 32, 32, 32, 4096, 256, 8},
    {"distance-out-of-cache", 1024, 1024, 64, 65536, 16, 8},
};

DeviceConfig config_of(const Case& c) {
  DeviceConfig cfg;
  cfg.MAW = c.sb ? 25 : 22;  // room for the largest map
  if (c.sb) cfg.SB = c.sb;
  return cfg;
}

// A shell of random points over a cube, a pose that spreads them over the whole map (as bench_device's), and a map
// of random words (a quarter surface voxels; random node values on a distance map, a threshold near their middle).
void build(const DeviceConfig& cfg, const Case& c, DeviceMemory& mem, Job& job) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  const double span = std::max({c.nx, c.ny, c.nz});
  mem.shell.clear();
  for (size_t k = 0; k < c.points; ++k) {
    const double p[3] = {span * u(rng), span * u(rng), span * u(rng)};
    mem.shell.push_back(quantize_point(cfg, p, "p"));
  }
  job = Job{};
  job.mode = Mode::Count;
  job.shell_count = uint32_t(c.points);
  job.nx = c.nx, job.ny = c.ny, job.nz = c.nz;
  FloatPose pose;
  const double co = std::cos(0.5236), sn = std::sin(0.5236);
  const double sx = c.nx / span / 1.4, sy = c.ny / span / 1.4, sz = c.nz / span;
  pose.M[0][0] = co * sx, pose.M[0][1] = -sn * sx, pose.M[0][2] = 0;
  pose.M[1][0] = sn * sy, pose.M[1][1] = co * sy, pose.M[1][2] = 0;
  pose.M[2][0] = 0, pose.M[2][1] = 0, pose.M[2][2] = sz * 0.999;
  pose.t[0] = c.nx * 0.3, pose.t[1] = c.ny * 0.05, pose.t[2] = 0;
  quantize_pose(cfg, pose, job);
  mem.map.resize(map_words(cfg, job));
  for (auto& w : mem.map) w = c.sb ? rng() : (rng() & 0x5555555555555555ull & rng());
  job.threshold = 0;
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
    build(cfg, c, mem, job);
    std::vector<Record> out;
    if (!count_case.empty()) {
      FastRunner runner(cfg, 1);
      runner.load(mem);
      runner.run_into(std::vector<Job>(count_jobs, job), out, false);
      std::printf("%s %zu jobs %u hits\n", c.name, count_jobs, out.empty() ? 0u : out.back().hits);
      return 0;
    }
    const std::vector<Job> batch(c.jobs, job);
    for (unsigned threads : {1u, 2u}) {
      FastRunner runner(cfg, threads);
      runner.load(mem);
      runner.run_into(batch, out, false);  // warm-up
      std::vector<double> t;
      for (int r = 0; r < repeats; ++r) {
        // One thread: its CPU time. Two: the wall time (the pool's workers spin between batches, so their CPU time
        // is no measure), which the machine's other load inflates.
        const double t0 = threads == 1 ? cpu_now() : now();
        runner.run_into(batch, out, false);
        t.push_back((threads == 1 ? cpu_now() : now()) - t0);
      }
      std::sort(t.begin(), t.end());
      const double ns = t[t.size() / 2] * 1e9 / double(c.points * c.jobs) * threads;  // per point per core
      std::printf("%s %u %.4f %u\n", c.name, threads, ns, out.back().hits);
    }
  }
  if (!count_case.empty()) {
    std::fprintf(stderr, "bench_kernel: no case '%s'\n", count_case.c_str());
    return 2;
  }
  return 0;
}
