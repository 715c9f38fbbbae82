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
#include "voxcd/host/device/device.h"
#include "voxcd/ref/float_model.h"

using namespace voxcd;

namespace {

struct Scenario {
  const char* name;
  uint32_t nx, ny, nz;
  size_t points, jobs;
};

// A shell of `n` points spread over a cube of side `span` voxels, and a pose that maps it onto the map.
void build(const DeviceConfig& cfg, const Scenario& s, size_t n, DeviceMemory& mem, Job& job, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const double span = std::max({s.nx, s.ny, s.nz});
  mem.shell.clear();
  for (size_t k = 0; k < n; ++k) {
    const double p[3] = {span * u(rng), span * u(rng), span * u(rng)};
    mem.shell.push_back(quantize_point(cfg, p, "p"));
  }
  const uint64_t voxels = uint64_t(s.nx) * s.ny * s.nz;
  mem.map.assign((voxels + 31) / 32, 0);
  for (auto& w : mem.map) w = rng() & 0x5555555555555555ull & rng();  // about a quarter surface voxels
  job = Job{};
  job.mode = Mode::Count;
  job.shell_count = uint32_t(n);
  job.nx = s.nx, job.ny = s.ny, job.nz = s.nz;
  // A rotation of 30 degrees about z, scaled per axis onto the map's extent (anisotropic scale keeps the
  // points spread over the whole map).
  FloatPose pose;
  const double c = std::cos(0.5236), sn = std::sin(0.5236);
  const double sx = s.nx / span / 1.4, sy = s.ny / span / 1.4, sz = s.nz / span;
  pose.M[0][0] = c * sx, pose.M[0][1] = -sn * sx, pose.M[0][2] = 0;
  pose.M[1][0] = sn * sy, pose.M[1][1] = c * sy, pose.M[1][2] = 0;
  pose.M[2][0] = 0, pose.M[2][1] = 0, pose.M[2][2] = sz * 0.999;
  pose.t[0] = s.nx * 0.3, pose.t[1] = s.ny * 0.05, pose.t[2] = 0;
  quantize_pose(cfg, pose, job);
}

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
    build(cfg, s, s.points, mem, job, 7);
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
