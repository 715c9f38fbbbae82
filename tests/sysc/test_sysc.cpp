// The SystemC platform (sysc/): both targets pass the conformance vectors with cycles; the time they annotate is
// the device's cycles times the clock period; the RTL and TLM targets give identical transaction logs for the same
// stimulus; malformed accesses get TLM error responses. One SystemC elaboration per test process: each test builds
// every platform it needs before it first simulates (gtest_discover_tests runs each test in its own process).
// Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <random>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vectors.h"
#include "voxcd/sysc/platform.h"
#include "voxcd/sysc/rtl_target.h"
#include "tests/ref/directed_cases.h"
#include "tests/sysc/built_lanes.h"
#include "tests/seed.h"

namespace voxcd::sysc {
namespace {

using namespace sc_core;

uint64_t test_seed() { return test::seed(777); }

const sc_time kClock(10, SC_NS);

struct Case {
  std::string name;
  DeviceConfig config;
  DeviceMemory memory;
  std::vector<Job> jobs;
  std::vector<Record> expected;  // with the timing model's cycles
};

Case generated(uint64_t seed, const DeviceConfig& cfg, size_t jobs) {
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs;
  g.cloud_points = 600;
  g.config = cfg;
  const GeneratedVectors v = generate_vectors(g);
  Case c{"generated " + cfg.to_string(), v.config, v.memory, v.jobs, run_stream(v.config, v.memory, v.jobs)};
  annotate_cycles(c.config, c.memory, c.jobs, c.expected);  // a banked device's cycles count its bank conflicts
  return c;
}

// Generated jobs for the default widths on `lanes` lanes.
Case generated(uint64_t seed, int lanes, size_t jobs) {
  DeviceConfig cfg;
  cfg.LANES = lanes;
  return generated(seed, cfg, jobs);
}

// Generated cases on every lane count (the RTL target: every lane count it has models of) and the directed cases
// (the RTL target: those of its widths, on the first lane count it has when it has none of theirs).
std::vector<Case> conformance_cases(uint64_t seed, bool rtl_models_only, size_t jobs) {
  const std::vector<int> lanes = rtl_models_only ? rtl_target_lanes() : std::vector<int>{1, 2, 4, 8};
  std::vector<Case> out;
  for (int l : lanes) out.push_back(generated(seed + uint64_t(l), l, jobs));
  for (const auto& d : testing::directed_cases()) {
    DeviceConfig cfg = d.config;
    if (rtl_models_only) {
      DeviceConfig built;
      built.LANES = cfg.LANES;
      if (!cfg.same_widths(built)) continue;
      cfg.LANES = built_lanes(cfg.LANES);
    }
    Case c{"directed " + d.name, cfg, d.memory, d.jobs, run_stream(cfg, d.memory, d.jobs)};
    annotate_cycles(c.config, c.jobs, c.expected);
    out.push_back(c);
  }
  return out;
}

std::unique_ptr<Platform> make_platform(const std::string& name, TargetKind k, const DeviceConfig& cfg,
                                        sc_time quantum = sc_time(1, SC_US), size_t burst = 4096) {
  PlatformOptions o;
  o.target = k;
  o.config = cfg;
  o.clock_period = kClock;
  o.quantum = quantum;
  o.burst = burst;
  return std::make_unique<Platform>(name.c_str(), o);
}

void expect_stream(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i)
    ASSERT_TRUE(got[i].same_as(want[i], true))
        << what << " record " << i << ": expected '" << want[i].to_string() << "', got '" << got[i].to_string() << "'";
}

void run_cases(TargetKind k, const std::vector<Case>& cases) {
  std::vector<std::unique_ptr<Platform>> ps;
  for (size_t i = 0; i < cases.size(); ++i)
    ps.push_back(make_platform("p" + std::to_string(i), k, cases[i].config));
  for (size_t i = 0; i < cases.size(); ++i) {
    std::vector<Record> got;
    ps[i]->execute([&](HostCpu& cpu) {
      cpu.load(cases[i].memory);
      got = cpu.run(cases[i].jobs);
    });
    expect_stream(cases[i].expected, got, std::string(target_name(k)) + " " + cases[i].name);
  }
}

void conformance(TargetKind k, size_t jobs) {
  const uint64_t seed = test_seed();
  const std::vector<Case> cases = conformance_cases(seed, k == TargetKind::Rtl, jobs);
  ASSERT_GE(cases.size(), 10u);
  run_cases(k, cases);
}

// Every distance device the build has a SystemC RTL model of (SB 4, 8, 16 by default): generated jobs with thresholds, their
// hit records with distances, and cycles (three more slot registers); the TLM target on the same configurations.
void distance_conformance(TargetKind k) {
  const uint64_t seed = test_seed();
  std::vector<Case> cases;
  for (const DeviceConfig& cfg : rtl_target_configs())
    if (cfg.distance()) cases.push_back(generated(seed + uint64_t(cfg.SB), cfg, 150));
  ASSERT_FALSE(cases.empty()) << "the build's distance models (VOXCD_SYSC_DIST_MODELS)";
  size_t with_dist = 0;
  for (const Case& c : cases)
    for (const Record& r : c.expected) with_dist += r.kind == Record::Hit && r.dist != 0;
  EXPECT_GT(with_dist, 100u) << "the cases must have hits with distances";
  run_cases(k, cases);
}

// The devices with shared voxmap banks and with deeper pipelines the build has SystemC RTL models of
// (VOXCD_SYSC_BANKED_MODELS, VOXCD_SYSC_DEPTH_MODELS): generated jobs, exact streams with cycles (bank conflicts and
// the depth's latency and squash included), and the CONFLICTS register equal to ref/'s count; on the TLM target the
// same, and every depth at two lanes.
void banked_and_deeper(TargetKind k) {
  const uint64_t seed = test_seed();
  std::vector<Case> cases;
  bool banked = false, deeper = false;
  for (const DeviceConfig& cfg : rtl_target_configs()) {
    if (!cfg.banked() && cfg.depth == 0) continue;
    banked = banked || cfg.banked();
    deeper = deeper || cfg.depth > 0;
    cases.push_back(generated(seed + uint64_t(cfg.BANKS * 10 + cfg.depth), cfg, 200));
  }
  ASSERT_TRUE(banked && deeper) << "the build's banked and deeper SystemC models";
  if (k == TargetKind::Tlm) {
    for (int d = 1; d <= kMaxDepth; ++d) {
      DeviceConfig cfg;
      cfg.LANES = 2;
      cfg.depth = d;
      cases.push_back(generated(seed + 100 + uint64_t(d), cfg, 200));
    }
    DeviceConfig dist;  // a distance device with shared banks, its FIRST jobs reading behind their hits
    dist.SB = 8;
    dist.LANES = 4;
    dist.BANKS = 1;
    cases.push_back(generated(seed + 200, dist, 200));
  }
  std::vector<std::unique_ptr<Platform>> ps;
  for (size_t i = 0; i < cases.size(); ++i) ps.push_back(make_platform("p" + std::to_string(i), k, cases[i].config));
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    std::vector<Record> got;
    uint64_t conflicts = 0;
    ps[i]->execute([&](HostCpu& cpu) {
      cpu.load(c.memory);
      got = cpu.run(c.jobs);
      conflicts = cpu.read_reg(kRegConflicts);
    });
    const std::string what = std::string(target_name(k)) + " " + c.name;
    expect_stream(c.expected, got, what);
    uint64_t want = 0;
    if (c.config.banked())
      for (uint64_t n : bank_conflicts(c.config, c.memory, c.jobs, c.expected)) want += n;
    EXPECT_EQ(conflicts, want) << what << ": the CONFLICTS register";
    if (c.config.banked()) {
      EXPECT_GT(want, 0u) << what << ": the jobs must make the banks conflict";
    }
  }
}

// Sparse devices (BL 3; docs/contract.md, "Sparse voxmaps and shells"): generated version-3 jobs (sparse maps and
// shells among dense ones) through the address map's descriptors, on every sparse device the build has a SystemC RTL
// model of (VOXCD_SYSC_SPARSE_MODELS: 2-bit and distance by default); the TLM target on the same configurations and on
// 2-bit and distance devices with shared banks and a deeper pipeline. The exact stream with cycles, the CONFLICTS
// register equal to ref/'s count, and BL in the configuration register.
void sparse_conformance(TargetKind k) {
  const uint64_t seed = test_seed();
  std::vector<Case> cases;
  for (const DeviceConfig& cfg : rtl_target_configs())
    if (cfg.sparse()) cases.push_back(generated(seed + 20 + uint64_t(cfg.SB * 10 + cfg.LANES), cfg, 200));
  ASSERT_FALSE(cases.empty()) << "the build's sparse models (VOXCD_SYSC_SPARSE_MODELS)";
  if (k == TargetKind::Tlm)
    for (int sb : {2, 8})
      for (int banks : {0, 2}) {
        DeviceConfig cfg;
        cfg.BL = 3, cfg.SB = sb, cfg.BANKS = banks, cfg.depth = banks ? 0 : 3;
        cases.push_back(generated(seed + uint64_t(sb + banks), cfg, 200));
      }
  std::vector<std::unique_ptr<Platform>> ps;
  for (size_t i = 0; i < cases.size(); ++i) ps.push_back(make_platform("p" + std::to_string(i), k, cases[i].config));
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const std::string what = std::string(target_name(k)) + " " + c.name;
    size_t maps = 0, shells = 0;
    for (const Job& j : c.jobs) {
      maps += (j.sparse & 1) != 0;
      shells += (j.sparse & 2) != 0;
    }
    EXPECT_GT(maps, c.jobs.size() / 10) << what << ": jobs with sparse maps";
    EXPECT_GT(shells, c.jobs.size() / 10) << what << ": jobs with sparse shells";
    std::vector<Record> got;
    uint64_t conflicts = 0, config1 = 0;
    ps[i]->execute([&](HostCpu& cpu) {
      cpu.load(c.memory);
      got = cpu.run(c.jobs);
      conflicts = cpu.read_reg(kRegConflicts);
      config1 = cpu.read_reg(kRegConfig1);
    });
    expect_stream(c.expected, got, what);
    EXPECT_EQ(config1 >> 56, 3u) << what << ": BL in CONFIG1";
    EXPECT_EQ(config1, config_word1(c.config)) << what;
    uint64_t want = 0;
    if (c.config.banked())
      for (uint64_t n : bank_conflicts(c.config, c.memory, c.jobs, c.expected)) want += n;
    EXPECT_EQ(conflicts, want) << what << ": the CONFLICTS register";
    if (c.config.banked()) {
      EXPECT_GT(want, 0u) << what;
    }
  }
}

TEST(SyscRtl, SparseDevicesWithCycles) { sparse_conformance(TargetKind::Rtl); }
TEST(SyscTlm, SparseDevicesWithCycles) { sparse_conformance(TargetKind::Tlm); }
TEST(SyscTlm, ConformanceVectorsWithCycles) { conformance(TargetKind::Tlm, 400); }
TEST(SyscRtl, BankedAndDeeperDevicesWithCycles) { banked_and_deeper(TargetKind::Rtl); }
TEST(SyscTlm, BankedAndDeeperDevicesWithCycles) { banked_and_deeper(TargetKind::Tlm); }
TEST(SyscRtl, ConformanceVectorsWithCycles) { conformance(TargetKind::Rtl, 150); }
TEST(SyscRtl, DistanceDevicesWithCycles) { distance_conformance(TargetKind::Rtl); }
TEST(SyscTlm, DistanceDevicesWithCycles) { distance_conformance(TargetKind::Tlm); }

// A batch launched at time t on an idle device: its first job is presented at the first edge after t and accepted
// at the next; each completion record is taken one edge after its emission, `cycles` after the previous one. So
// the read that returns the last record ends at (edge_after(t) + 2 + sum of cycles) * T, and the CYCLES register
// holds the sum.
TEST(Sysc, AnnotatedTimeIsCyclesTimesClockPeriod) {
  const Case c = generated(test_seed(), built_lanes(4), 120);
  uint64_t sum = 0;
  for (const Record& r : c.expected)
    if (r.kind == Record::Done) sum += *r.cycles;
  ASSERT_GT(sum, c.jobs.size());
  // The TLM platform's quantum is longer than the whole run: its kernel time must not move at all.
  auto tlm = make_platform("tlm", TargetKind::Tlm, c.config, sc_time(1, SC_SEC));
  auto rtl = make_platform("rtl", TargetKind::Rtl, c.config);
  for (Platform* p : {tlm.get(), rtl.get()}) {
    sc_time launched, last_read, kernel_after;
    uint64_t cycles_reg = 0;
    p->cpu.logging = true;
    p->execute([&](HostCpu& cpu) {
      cpu.load(c.memory);
      cpu.compute(sc_time(3, SC_NS));  // off the clock grid on purpose
      launched = cpu.now();
      const std::vector<Record> got = cpu.run(c.jobs);
      last_read = cpu.log.back().end;
      kernel_after = sc_time_stamp();
      cycles_reg = cpu.read_reg(kRegCycles);
      expect_stream(c.expected, got, target_name(p->options().target));
    });
    // The staging writes and the RUN write take no device time: the batch starts from `launched`.
    const uint64_t first_edge = launched.value() / kClock.value() + 1;
    EXPECT_EQ(last_read, kClock * double(first_edge + 2 + sum)) << target_name(p->options().target);
    EXPECT_EQ(cycles_reg, sum) << target_name(p->options().target);
    if (p == tlm.get())
      EXPECT_EQ(kernel_after, SC_ZERO_TIME) << "the TLM target's b_transport must annotate, not wait";
    else
      EXPECT_EQ(kernel_after, last_read) << "the RTL target's time passes in the kernel";
  }
}

// A stimulus that exercises every part of the address map: loads, batches of random sizes staged in pieces, a
// batch launched while another runs, registers read while batches run, result reads of random sizes, memory
// rewritten right after a batch (which waits for the device to drain), and bad accesses.
void stimulus(HostCpu& cpu, const Case& c, uint64_t seed) {
  std::mt19937_64 rng(seed);
  const auto pick = [&](size_t lo, size_t hi) { return std::uniform_int_distribution<size_t>(lo, hi)(rng); };
  cpu.load(c.memory);
  std::vector<uint8_t> buf;
  const auto stage = [&](size_t from, size_t n) {
    buf.assign(n * kJobBytes, 0);
    for (size_t i = 0; i < n; ++i) encode_job(c.jobs[from + i], &buf[i * kJobBytes]);
    cpu.access(true, kJobBase, buf.data(), buf.size());
  };
  const auto poke_registers = [&] {
    for (uint64_t r : {kRegStatus, kRegResultCount, kRegJobsDone, kRegCycles, kRegHits, kRegPoints, kRegStaged})
      if (pick(0, 2) == 0) cpu.read_reg(r);
  };
  // Directed first: a FIRST job whose hit is in its first slot leaves the slots issued behind it draining after its
  // completion record; a memory write right after must wait for them.
  size_t directed = 0;
  for (size_t j = 0, r = 0; j < c.jobs.size() && directed < 3; ++j) {
    const size_t first = r;
    while (c.expected[r].kind == Record::Hit) ++r;
    const Record& done = c.expected[r++];
    const Job& job = c.jobs[j];
    const uint32_t lanes = uint32_t(c.config.LANES);
    if (job.mode != Mode::First || done.hits == 0 ||
        (job.shell_count + lanes - 1) / lanes < c.expected[first].point / lanes + 3)
      continue;
    ++directed;
    stage(j, 1);
    cpu.write_reg(kRegRun, 1);
    buf.assign(2 * kRecordBytes, 0);
    cpu.access(false, kResultBase, buf.data(), buf.size());
    buf.assign(kShellStride, 0);
    for (int a = 0; a < 3; ++a) put_le(&buf[4 * size_t(a)], uint64_t(c.memory.shell[0][a]), 4);
    cpu.access(true, kShellBase, buf.data(), buf.size());
  }
  EXPECT_GE(directed, 1u) << "the case must have FIRST jobs that stop early with slots behind them";
  size_t k = 0, outstanding = 0;
  while (k < c.jobs.size() || outstanding) {
    if (k < c.jobs.size() && (outstanding == 0 || pick(0, 3) == 0)) {
      const size_t n = std::min(pick(1, 30), c.jobs.size() - k);
      const size_t split = pick(0, n);
      if (split) stage(k, split);
      if (n > split) stage(k + split, n - split);
      poke_registers();
      cpu.write_reg(kRegRun, 1);
      k += n;
      outstanding += n;
      cpu.compute(sc_time(double(pick(0, 500)), SC_NS));
      continue;
    }
    poke_registers();
    // Read some records: whole jobs come out of the device together.
    const size_t want = pick(1, 48);
    buf.assign(want * kRecordBytes, 0);
    cpu.access(false, kResultBase, buf.data(), buf.size());
    Record r;
    for (size_t i = 0; i < want && decode_record(&buf[i * kRecordBytes], r); ++i) outstanding -= r.kind == Record::Done;
    if (pick(0, 3) == 0) cpu.compute(sc_time(double(pick(0, 300)), SC_NS));
    if (pick(0, 5) == 0) {
      // Rewrite a piece of both memories with what they hold (the stream stays the same).
      const size_t s = pick(0, c.memory.shell.size() - 1), m = pick(0, c.memory.map.size() - 1);
      buf.assign(kShellStride * std::min<size_t>(9, c.memory.shell.size() - s), 0);
      for (size_t i = 0; i < buf.size() / kShellStride; ++i)
        for (int a = 0; a < 3; ++a) put_le(&buf[i * kShellStride + 4 * size_t(a)], uint64_t(c.memory.shell[s + i][a]), 4);
      cpu.access(true, kShellBase + s * kShellStride, buf.data(), buf.size());
      buf.assign(kMapStride * std::min<size_t>(5, c.memory.map.size() - m), 0);
      for (size_t i = 0; i < buf.size() / kMapStride; ++i) put_le(&buf[i * kMapStride], c.memory.map[m + i], 8);
      cpu.access(true, kMapBase + m * kMapStride, buf.data(), buf.size());
    }
    if (pick(0, 7) == 0) {
      uint8_t b[16] = {};
      cpu.access(false, kShellBase, b, 16);     // write-only memory
      cpu.access(true, kRegBase + 0x800, b, 8);  // no such register
      cpu.access(false, kRegBase + 4, b, 8);     // unaligned
    }
  }
  poke_registers();
}

TEST(Sysc, RtlAndTlmGiveIdenticalTransactionLogs) {
  const uint64_t seed = test_seed();
  // FIRST jobs last in a batch leave squashed slots draining: the generator's mix has them, and so do these
  // lane counts' different slot sizes.
  std::vector<Case> cases = {generated(seed, built_lanes(4), 160), generated(seed + 1, built_lanes(1), 80)};
  std::vector<std::unique_ptr<Platform>> rtl, tlm;
  for (size_t i = 0; i < cases.size(); ++i) {
    rtl.push_back(make_platform("rtl" + std::to_string(i), TargetKind::Rtl, cases[i].config, sc_time(1, SC_US), 512));
    tlm.push_back(make_platform("tlm" + std::to_string(i), TargetKind::Tlm, cases[i].config, sc_time(1, SC_US), 512));
  }
  for (size_t i = 0; i < cases.size(); ++i) {
    rtl[i]->cpu.logging = tlm[i]->cpu.logging = true;
    rtl[i]->cpu.post([&, i](HostCpu& cpu) { stimulus(cpu, cases[i], seed + 10 + i); });
    tlm[i]->cpu.post([&, i](HostCpu& cpu) { stimulus(cpu, cases[i], seed + 10 + i); });
    run_until_idle({&rtl[i]->cpu, &tlm[i]->cpu});
    const auto& a = rtl[i]->cpu.log;
    const auto& b = tlm[i]->cpu.log;
    ASSERT_GT(a.size(), 100u);
    size_t errors = 0;
    for (const Transaction& t : a) errors += t.response != tlm::TLM_OK_RESPONSE;
    EXPECT_GT(errors, 0u) << "the stimulus must include bad accesses";
    ASSERT_EQ(a.size(), b.size()) << cases[i].name;
    for (size_t j = 0; j < a.size(); ++j)
      ASSERT_EQ(a[j], b[j]) << cases[i].name << " transaction " << j << ":\n  rtl " << a[j].to_string() << "\n  tlm "
                            << b[j].to_string();
  }
}

// Every kind of malformed access gets its error response, on both targets, and the device still works after.
TEST(Sysc, MalformedAccessesGetErrorResponses) {
  const Case c = generated(test_seed(), built_lanes(2), 20);
  auto rtl = make_platform("rtl", TargetKind::Rtl, c.config);
  auto tlm = make_platform("tlm", TargetKind::Tlm, c.config);
  for (Platform* p : {rtl.get(), tlm.get()}) {
    const std::string who = target_name(p->options().target);
    p->execute([&](HostCpu& cpu) {
      cpu.load(c.memory);
      std::vector<uint8_t> b(4096, 0);
      using namespace tlm;
      const auto expect = [&](tlm_response_status want, bool wr, uint64_t a, size_t n, const char* what) {
        EXPECT_EQ(cpu.access(wr, a, b.data(), n), want) << who << ": " << what;
      };
      expect(TLM_ADDRESS_ERROR_RESPONSE, false, 0x4000'0000, 8, "no window");
      expect(TLM_ADDRESS_ERROR_RESPONSE, false, kRegBase + 0x800, 8, "no register");
      expect(TLM_BURST_ERROR_RESPONSE, false, kRegBase + kRegStatus, 4, "short register read");
      expect(TLM_BURST_ERROR_RESPONSE, false, kRegBase + 3, 8, "unaligned register");
      expect(TLM_COMMAND_ERROR_RESPONSE, true, kRegBase + kRegStatus, 8, "write to a read-only register");
      expect(TLM_COMMAND_ERROR_RESPONSE, false, kRegBase + kRegRun, 8, "read of RUN");
      expect(TLM_BURST_ERROR_RESPONSE, true, kJobBase, kJobBytes - 8, "partial descriptor");
      expect(TLM_BURST_ERROR_RESPONSE, true, kJobBase + kJobBytes, kJobBytes, "descriptor off the base");
      expect(TLM_COMMAND_ERROR_RESPONSE, false, kJobBase, kJobBytes, "read of the job window");
      expect(TLM_BURST_ERROR_RESPONSE, false, kResultBase, 20, "partial record");
      expect(TLM_COMMAND_ERROR_RESPONSE, true, kResultBase, kRecordBytes, "write to the result window");
      expect(TLM_BURST_ERROR_RESPONSE, true, kShellBase + 8, 16, "unaligned shell word");
      expect(TLM_BURST_ERROR_RESPONSE, true, kShellBase, 24, "partial shell word");
      expect(TLM_COMMAND_ERROR_RESPONSE, false, kShellBase, 16, "read of shell memory");
      expect(TLM_BURST_ERROR_RESPONSE, true, kMapBase + 4, 8, "unaligned voxmap word");
      expect(TLM_BURST_ERROR_RESPONSE, true, kMapBase + (c.config.map_depth() - 1) * kMapStride, 16,
             "voxmap write past the end");
      expect(TLM_COMMAND_ERROR_RESPONSE, false, kMapBase, 8, "read of voxmap memory");
      expect(TLM_BURST_ERROR_RESPONSE, false, kRegBase, 0, "zero length");
      // Values that do not fit: a shell coordinate beyond PW bits, a voxmap word beyond MEMW bits (none at 64),
      // a descriptor with a bad mode, a job reading past the loaded shell.
      std::fill(b.begin(), b.end(), 0);
      put_le(b.data(), uint64_t(1) << (c.config.PW - 1), 4);
      expect(TLM_GENERIC_ERROR_RESPONSE, true, kShellBase, 16, "shell coordinate too wide");
      std::fill(b.begin(), b.end(), 0);
      Job j = c.jobs.front();
      encode_job(j, b.data());
      b[0x04] = 3;
      expect(TLM_GENERIC_ERROR_RESPONSE, true, kJobBase, kJobBytes, "mode 3");
      j.shell_base = uint32_t(c.memory.shell.size());
      j.shell_count = 1;
      encode_job(j, b.data());
      expect(TLM_GENERIC_ERROR_RESPONSE, true, kJobBase, kJobBytes, "job past the loaded shell");
      EXPECT_FALSE(p->target().last_error().empty());
      // Byte enables and streaming are refused too.
      tlm_generic_payload tr;
      uint8_t be[8] = {0xff, 0xff, 0xff, 0xff, 0, 0, 0, 0};
      tr.set_command(TLM_READ_COMMAND);
      tr.set_address(kRegBase + kRegStatus);
      tr.set_data_ptr(b.data());
      tr.set_data_length(8);
      tr.set_streaming_width(8);
      tr.set_byte_enable_ptr(be);
      tr.set_byte_enable_length(8);
      sc_time d = SC_ZERO_TIME;
      cpu.socket->b_transport(tr, d);
      EXPECT_EQ(tr.get_response_status(), TLM_BYTE_ENABLE_ERROR_RESPONSE) << who;
      tr.set_byte_enable_ptr(nullptr);
      tr.set_streaming_width(4);
      tr.set_response_status(TLM_INCOMPLETE_RESPONSE);
      cpu.socket->b_transport(tr, d);
      EXPECT_EQ(tr.get_response_status(), TLM_BURST_ERROR_RESPONSE) << who;
      // Nothing was staged by the refused descriptors, and the device still runs the real jobs.
      EXPECT_EQ(cpu.read_reg(kRegStaged), 0u) << who;
      EXPECT_EQ(cpu.read_reg(kRegId), kDeviceId) << who;
      expect_stream(c.expected, cpu.run(c.jobs), who);
    });
  }
}

}  // namespace
}  // namespace voxcd::sysc

int sc_main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
