// voxcd selftest: generated conformance vectors on every backend that can run here (a line names each that
// cannot), at 1, 2, 4 and 8 lanes, then on sparse devices (BL 3: 2-bit at 4 lanes and distance at 2, docs/contract.md
// "Sparse voxmaps and shells") wherever a backend has them (ref, cpu and sysc-tlm always; rtl and sysc-rtl where the
// build has a model of the configuration, else a line says why not), with cycles compared where the backend models
// them. A summary table, then "N passed, N failed".
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

// One configuration's vectors, as a vector file would hold them.
struct Vectors {
  GeneratedVectors v;
  VectorFile f;
  size_t lookups = 0;
};

Vectors vectors_of(uint64_t seed, size_t jobs, const DeviceConfig& cfg) {
  Vectors out;
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs;
  g.config = cfg;
  out.v = generate_vectors(g);
  std::vector<Record> expect = run_stream(out.v.config, out.v.memory, out.v.jobs);
  annotate_cycles(out.v.config, out.v.memory, out.v.jobs, expect);
  out.f.path = "generated";
  out.f.config = out.v.config;
  out.f.jobs = out.v.jobs;
  out.f.job_lines.assign(out.v.jobs.size(), 0);
  out.f.expected = expect;
  out.f.expected_lines.assign(expect.size(), 0);
  for (const Job& j : out.v.jobs) out.lookups += job_points(out.v.config, out.v.memory.shell, j).size();
  return out;
}

enum class Outcome { Passed, Failed, Skipped };

// Runs the vectors on backend b and prints its row. `optional`: a backend that cannot be made for this
// configuration (no model of it) is skipped with a line saying why, not failed.
Outcome run_row(const std::string& b, const Vectors& x, const std::string& label, bool optional) {
  std::string err;
  const auto t0 = std::chrono::steady_clock::now();
  size_t nrec = 0;
  bool cycles = false;
  std::unique_ptr<Device> dev;
  try {
    dev = make_device(b, x.v.config);
  } catch (const DeviceError& e) {
    if (!optional) err = e.what();
    else {
      std::printf("%-10s %-14s skipped: %s\n", b.c_str(), label.c_str(), e.what());
      return Outcome::Skipped;
    }
  }
  try {
    if (dev) {
      cycles = dev->models_cycles();
      dev->load(x.v.memory);
      const std::vector<Record> got = dev->run(x.v.jobs);
      nrec = got.size();
      err = compare_streams(x.f, got, cycles);
    }
  } catch (const std::exception& e) {
    err = e.what();
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("%-10s %-14s %8zu %10zu %10zu %8.1f  %s%s\n", b.c_str(), label.c_str(), x.v.jobs.size(), x.lookups,
              nrec, ms, err.empty() ? "ok" : "FAIL: ", err.c_str());
  if (err.empty() && !cycles) std::printf("%-10s %-14s (results only: this backend does not model cycles)\n", "", "");
  return err.empty() ? Outcome::Passed : Outcome::Failed;
}

int selftest(const SelftestArgs& a) {
  std::printf("voxcd selftest: seed %llu, %zu jobs per run\n", (unsigned long long)a.seed, a.jobs);
  std::printf("%-10s %-14s %8s %10s %10s %8s  %s\n", "backend", "device", "jobs", "lookups", "records", "ms",
              "result");
  size_t counts[3] = {0, 0, 0};
  const std::vector<std::string> ready = device_backends();
  for (const BackendStatus& b : backend_status())
    if (!b.ready) std::printf("%-10s skipped: %s\n", b.name.c_str(), b.why_not.c_str());
  for (int lanes : {1, 2, 4, 8}) {
    DeviceConfig cfg;
    cfg.LANES = lanes;
    const Vectors x = vectors_of(a.seed + uint64_t(lanes), a.jobs, cfg);
    for (const std::string& b : ready) ++counts[int(run_row(b, x, "lanes " + std::to_string(lanes), false))];
  }
  // Sparse devices: the backends computing on the host take any configuration; the RTL ones where they have it. The
  // distance device has 2 lanes, as the sparse distance models of both RTL backends have by default
  // (VOXCD_RTL_SPARSE_MODELS, VOXCD_SYSC_SPARSE_MODELS).
  for (int sb : {2, 8}) {
    DeviceConfig cfg;
    cfg.BL = 3;
    cfg.SB = sb;
    cfg.LANES = sb == 2 ? 4 : 2;
    const Vectors x = vectors_of(a.seed + 100 + uint64_t(sb), a.jobs, cfg);
    const std::string label = sb == 2 ? "BL 3" : "BL 3 SB 8";
    for (const std::string& b : ready)
      ++counts[int(run_row(b, x, label, b == "rtl" || b == "sysc-rtl"))];
  }
  std::printf("%zu passed, %zu failed", counts[0], counts[1]);
  if (counts[2]) std::printf(", %zu skipped (no model of the device)", counts[2]);
  std::printf("\n");
  return counts[1] ? 1 : 0;
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
