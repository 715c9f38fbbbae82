// voxcd selftest: generated conformance vectors on every backend that can run here (a line names each that
// cannot), at 1, 2, 4 and 8 lanes, with cycles compared where the backend models them. A summary table, then
// "N passed, N failed".
#include <chrono>
#include <cstdio>
#include <iostream>

#include "voxcd/host/cli/commands.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/vectors.h"
#include "voxcd/ref/timing.h"

namespace voxcd::cli {

namespace {

struct SelftestArgs {
  uint64_t seed = 1;
  size_t jobs = 300;
};

int selftest(const SelftestArgs& a) {
  std::printf("voxcd selftest: seed %llu, %zu jobs per run\n", (unsigned long long)a.seed, a.jobs);
  std::printf("%-10s %5s %8s %10s %10s %8s  %s\n", "backend", "lanes", "jobs", "lookups", "records", "ms",
              "result");
  size_t passed = 0, failed = 0;
  const std::vector<std::string> ready = device_backends();
  for (const BackendStatus& b : backend_status())
    if (!b.ready) std::printf("%-10s skipped: %s\n", b.name.c_str(), b.why_not.c_str());
  for (int lanes : {1, 2, 4, 8}) {
    GenerateOptions g;
    g.seed = a.seed + uint64_t(lanes);
    g.jobs = a.jobs;
    g.config.LANES = lanes;
    const GeneratedVectors v = generate_vectors(g);
    std::vector<Record> expect = run_stream(v.config, v.memory, v.jobs);
    annotate_cycles(v.config, v.memory, v.jobs, expect);
    VectorFile f;
    f.path = "generated";
    f.config = v.config;
    f.jobs = v.jobs;
    f.job_lines.assign(v.jobs.size(), 0);
    f.expected = expect;
    f.expected_lines.assign(expect.size(), 0);
    size_t lookups = 0;
    for (const Job& j : v.jobs) lookups += j.shell_count;
    for (const std::string& b : ready) {
      std::string err;
      const auto t0 = std::chrono::steady_clock::now();
      size_t nrec = 0;
      bool cycles = false;
      try {
        auto dev = make_device(b, v.config);
        cycles = dev->models_cycles();
        dev->load(v.memory);
        const std::vector<Record> got = dev->run(v.jobs);
        nrec = got.size();
        err = compare_streams(f, got, cycles);
      } catch (const std::exception& e) {
        err = e.what();
      }
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      std::printf("%-10s %5d %8zu %10zu %10zu %8.1f  %s%s\n", b.c_str(), lanes, v.jobs.size(), lookups, nrec, ms,
                  err.empty() ? "ok" : "FAIL: ", err.c_str());
      if (err.empty() && !cycles) std::printf("%-10s %5s (results only: this backend does not model cycles)\n", "", "");
      (err.empty() ? passed : failed)++;
    }
  }
  std::printf("%zu passed, %zu failed\n", passed, failed);
  return failed ? 1 : 0;
}

}  // namespace

void add_selftest(CLI::App& app) {
  auto a = std::make_shared<SelftestArgs>();
  CLI::App* c = app.add_subcommand("selftest", "Run generated conformance vectors on every backend of this build");
  c->add_option("--seed", a->seed, "Random seed")->capture_default_str();
  c->add_option("--jobs", a->jobs, "Jobs per run")->capture_default_str();
  c->callback([a] { exit_code() = selftest(*a); });
}

}  // namespace voxcd::cli
