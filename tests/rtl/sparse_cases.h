// What the sparse RTL tests share (tests/rtl/test_rtl_sparse*.cpp): the sparse models of the build, ref/'s exact
// stream for a memory and jobs (results, then the cycles of the timing model with the memory: a sparse shell's slots
// and a banked device's conflicts), and one run on the rtl backend compared with it.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tests/rtl/scoreboard.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"

namespace voxcd::test {

// The sparse models of the build (VOXCD_RTL_SPARSE_MODELS) of one kind: 2-bit (sb 2) or distance (sb > 2).
inline std::vector<DeviceConfig> sparse_models(bool distance) {
  std::vector<DeviceConfig> out;
  for (const DeviceConfig& c : rtl_sparse_configs())
    if (c.distance() == distance) out.push_back(c);
  return out;
}

// `jobs` generated vectors (ref/vector_gen.h) for cfg, the generator's seed drawn from `seed` and the configuration so
// that each model of a run gets its own stream.
inline GeneratedVectors generated(const DeviceConfig& cfg, uint64_t seed, size_t jobs) {
  GenerateOptions g;
  g.seed = seed * 64 + uint64_t(cfg.LANES * 8 + cfg.BANKS + cfg.SB * 100 + cfg.depth * 1000);
  g.jobs = jobs;
  g.config = cfg;
  return generate_vectors(g);
}

// ref/'s stream with the timing model's cycles.
inline std::vector<Record> exact_stream(const DeviceConfig& cfg, const DeviceMemory& mem,
                                        const std::vector<Job>& jobs) {
  std::vector<Record> r = run_stream(cfg, mem, jobs);
  annotate_cycles(cfg, mem, jobs, r);
  return r;
}

// Runs `jobs` on the rtl model of `cfg` with an always-ready consumer and checks every record, cycles included;
// returns ref/'s stream.
inline std::vector<Record> expect_rtl_exact(const DeviceConfig& cfg, const DeviceMemory& mem,
                                            const std::vector<Job>& jobs, const std::string& what) {
  const std::vector<Record> want = exact_stream(cfg, mem, jobs);
  auto dev = make_device("rtl", cfg);
  dev->load(mem);
  expect_exact(want, dev->run(jobs), what + " on " + cfg.to_string());
  return want;
}

// The hit records of a stream, in order.
inline std::vector<Record> hits_of(const std::vector<Record>& s) {
  std::vector<Record> out;
  for (const Record& r : s)
    if (r.kind == Record::Hit) out.push_back(r);
  return out;
}

}  // namespace voxcd::test
