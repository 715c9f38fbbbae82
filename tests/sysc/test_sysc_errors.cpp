// The SystemC platform's errors that test_sysc.cpp does not reach: the RTL target after a failed assertion, the
// BusError of HostCpu's register and memory helpers, reserved bytes in shell words and job descriptors, and a
// voxmap word above MEMW on a TLM target with MEMW < 64. Each names what was refused and where, and keeps what the
// device held before. One SystemC elaboration per test process (gtest_discover_tests runs each test alone): every
// platform of a test is made before it first simulates.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/sysc/platform.h"
#include "voxcd/sysc/rtl_target.h"
#include "tests/error_text.h"
#include "tests/origin_stimulus.h"
#include "tests/sysc/built_lanes.h"

namespace voxcd::sysc {
namespace {

// The text of the BusError fn throws (tests/error_text.h).
template <class Fn>
std::string bus_error(Fn&& fn) {
  return test::error_text<BusError>(std::forward<Fn>(fn));
}

using namespace sc_core;
using namespace tlm;

std::unique_ptr<Platform> make_platform(const std::string& name, TargetKind k, const DeviceConfig& cfg) {
  PlatformOptions o;
  o.target = k;
  o.config = cfg;
  return std::make_unique<Platform>(name.c_str(), o);
}

using test::origin_job;
using test::origin_memory;

void expect_stream(const std::vector<Record>& want, const std::vector<Record>& got, const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (size_t i = 0; i < want.size(); ++i)
    EXPECT_TRUE(got[i].same_as(want[i], false)) << what << " record " << i << ": " << got[i].to_string();
}

// The only RTL platform of its process: Verilator reports a failed assertion to the thread's current context,
// which is the context of the RTL target made last (docs/robustness.md).
TEST(SyscErrors, FaultedRtlTargetAnswersOnlyItsRegisters) {
  DeviceConfig cfg;
  cfg.LANES = built_lanes(2);
  const DeviceMemory mem = origin_memory(cfg, 600);
  auto p = make_platform("rtl", TargetKind::Rtl, cfg);
  dynamic_cast<RtlTarget&>(p->target()).start_writes_while_busy();
  const std::vector<Job> first = {origin_job(1, Mode::All, 8)};
  p->execute([&](HostCpu& cpu) {
    cpu.load(mem);
    expect_stream(run_stream(cfg, mem, first), cpu.run(first), "before the fault");
    // A job of 300 cycles, and a voxmap write 10 cycles into it: the RTL's assertion fails.
    uint8_t d[kJobBytes];
    encode_job(origin_job(2, Mode::Count, 600), d);
    ASSERT_EQ(cpu.access(true, kJobBase, d, kJobBytes), TLM_OK_RESPONSE);
    cpu.write_reg(kRegRun, 1);
    cpu.compute(sc_time(100, SC_NS));
    uint8_t w[8] = {};
    EXPECT_EQ(cpu.access(true, kMapBase, w, 8), TLM_OK_RESPONSE) << "the write itself completes";
    // The target sees the failure at a clock edge after the one that wrote the word.
    cpu.compute(sc_time(50, SC_NS));
    // The registers still answer, with the fault and the counters of what was done before it.
    EXPECT_EQ(cpu.read_reg(kRegStatus) & kStatusFault, kStatusFault);
    EXPECT_EQ(cpu.read_reg(kRegJobsDone), 1u);
    EXPECT_EQ(cpu.read_reg(kRegHits), 8u);
    EXPECT_EQ(cpu.read_reg(kRegShellWords), 600u);
    EXPECT_EQ(cpu.read_reg(kRegId), kDeviceId);
    // Everything else is refused, each with the same reason.
    const std::string reason = "rtl.device: the RTL has failed an assertion";
    EXPECT_EQ(bus_error([&] { cpu.write_reg(kRegRun, 1); }),
              "rtl.cpu: register write at address 56 got TLM_GENERIC_ERROR_RESPONSE");
    EXPECT_EQ(p->target().last_error(), reason);
    EXPECT_EQ(bus_error([&] { cpu.load(mem); }),
              "rtl.cpu: shell write at address 268435456 got TLM_GENERIC_ERROR_RESPONSE");
    EXPECT_EQ(bus_error([&] { cpu.run(first); }), "rtl.cpu: job write at address 65536 got TLM_GENERIC_ERROR_RESPONSE");
    uint8_t r[kRecordBytes];
    EXPECT_EQ(cpu.access(false, kResultBase, r, kRecordBytes), TLM_GENERIC_ERROR_RESPONSE);
    EXPECT_EQ(p->target().last_error(), reason);
    // A register that does not exist is still that, not the fault.
    EXPECT_EQ(bus_error([&] { cpu.read_reg(0x800); }),
              "rtl.cpu: register read at address 2048 got TLM_ADDRESS_ERROR_RESPONSE");
  });
}

// read_reg, write_reg and load throw BusError naming the access, its address and the response; the target's
// last_error says why. A refused load burst writes nothing, and the bursts before it stay loaded.
TEST(SyscErrors, HostCpuHelpersRaiseBusErrorsNamingTheAccess) {
  DeviceConfig cfg;
  cfg.LANES = built_lanes(cfg.LANES);
  auto rtl = make_platform("rtl", TargetKind::Rtl, cfg);
  auto tlm = make_platform("tlm", TargetKind::Tlm, cfg);
  for (Platform* p : {rtl.get(), tlm.get()}) {
    const std::string who = target_name(p->options().target);
    p->execute([&](HostCpu& cpu) {
      EXPECT_EQ(bus_error([&] { cpu.read_reg(0x800); }),
                who + ".cpu: register read at address 2048 got TLM_ADDRESS_ERROR_RESPONSE");
      EXPECT_EQ(p->target().last_error(), who + ".device: no register at this offset");
      EXPECT_EQ(bus_error([&] { cpu.read_reg(kRegRun); }),
                who + ".cpu: register read at address 56 got TLM_COMMAND_ERROR_RESPONSE");
      EXPECT_EQ(p->target().last_error(), who + ".device: RUN is write-only");
      EXPECT_EQ(bus_error([&] { cpu.write_reg(kRegStatus, 1); }),
                who + ".cpu: register write at address 32 got TLM_COMMAND_ERROR_RESPONSE");
      EXPECT_EQ(p->target().last_error(), who + ".device: register is read-only");
      // Shell words go in bursts of 256 (4096 bytes): word 700 is word 188 of the burst at word 512.
      DeviceMemory mem = origin_memory(cfg, 1000);
      mem.shell[700].y = int64_t{1} << (cfg.PW - 1);
      EXPECT_EQ(bus_error([&] { cpu.load(mem); }),
                who + ".cpu: shell write at address " + std::to_string(kShellBase + 512 * kShellStride) +
                    " got TLM_GENERIC_ERROR_RESPONSE");
      EXPECT_EQ(p->target().last_error(), who + ".device: shell word 188 does not fit PW bits");
      EXPECT_EQ(cpu.read_reg(kRegShellWords), 512u);
      EXPECT_EQ(cpu.read_reg(kRegMapWords), 0u) << "the voxmap comes after the shell";
      // What was loaded before the refused burst is used: load the voxmap alone and run on the first 512 points.
      DeviceMemory map_only;
      map_only.map = mem.map;
      cpu.load(map_only);
      const std::vector<Job> jobs = {origin_job(1, Mode::All, 512), origin_job(2, Mode::Count, 500)};
      expect_stream(run_stream(cfg, origin_memory(cfg, 512), jobs), cpu.run(jobs), who + " after the refused burst");
    });
  }
}

// A shell word's bytes 12..15 and a descriptor's byte 7 and bytes 0x6c..0x7f are reserved: a non-zero one refuses the
// whole write, names the word or descriptor and the byte, and stages or writes nothing of it. The sparse byte (6) and
// the brick fields (0x44, 0x68) are refused as validate_job refuses them: sparse bits 2..7, a sparse map on a dense
// device, brick fields on a dense map.
TEST(SyscErrors, NonZeroReservedBytesAreRefusedWhole) {
  DeviceConfig cfg;
  cfg.LANES = built_lanes(cfg.LANES);
  auto rtl = make_platform("rtl", TargetKind::Rtl, cfg);
  auto tlm = make_platform("tlm", TargetKind::Tlm, cfg);
  const DeviceMemory mem = origin_memory(cfg, 64);
  for (Platform* p : {rtl.get(), tlm.get()}) {
    const std::string who = target_name(p->options().target);
    p->execute([&](HostCpu& cpu) {
      cpu.load(mem);
      // Two shell words after the loaded ones; the second has a reserved byte set.
      uint8_t s[2 * kShellStride] = {};
      s[kShellStride + 13] = 1;
      EXPECT_EQ(cpu.access(true, kShellBase + 64 * kShellStride, s, sizeof s), TLM_GENERIC_ERROR_RESPONSE) << who;
      EXPECT_EQ(p->target().last_error(), who + ".device: shell word 1: reserved bytes not zero");
      EXPECT_EQ(cpu.read_reg(kRegShellWords), 64u) << who << ": nothing of the refused write is loaded";
      // Two descriptors, the second with one reserved byte set: neither is staged.
      const std::pair<size_t, std::string> refusals[] = {
          {0x07, "reserved descriptor byte 7 is not zero"},
          {0x6c, "reserved descriptor byte 108 is not zero"},
          {0x7f, "reserved descriptor byte 127 is not zero"},
          {0x06, "job tag 2: sparse = 128 has bits other than 1 (map) and 2 (shell)"},
          {0x44, "job tag 2: brick_base 0 and brick_units 128 of a dense map: both must be 0"},
          {0x68, "job tag 2: brick_base 128 and brick_units 0 of a dense map: both must be 0"}};
      for (const auto& [byte, why] : refusals) {
        uint8_t d[2 * kJobBytes];
        encode_job(origin_job(1, Mode::All, 64), d);
        encode_job(origin_job(2, Mode::All, 64), d + kJobBytes);
        d[kJobBytes + byte] = 0x80;
        EXPECT_EQ(cpu.access(true, kJobBase, d, sizeof d), TLM_GENERIC_ERROR_RESPONSE) << who << " byte " << byte;
        EXPECT_EQ(p->target().last_error(), who + ".device: descriptor 1: " + why);
        EXPECT_EQ(cpu.read_reg(kRegStaged), 0u) << who << " byte " << byte;
      }
      // A sparse map on this device (BL 0).
      uint8_t d[kJobBytes];
      encode_job(origin_job(1, Mode::All, 64), d);
      d[0x06] = kSparseMap;
      EXPECT_EQ(cpu.access(true, kJobBase, d, sizeof d), TLM_GENERIC_ERROR_RESPONSE) << who;
      EXPECT_EQ(p->target().last_error(), who + ".device: descriptor 0: job tag 1: a sparse map on a device without "
                                                "sparse maps and shells (BL = 0)");
      const std::vector<Job> jobs = {origin_job(3, Mode::All, 64)};
      expect_stream(run_stream(cfg, mem, jobs), cpu.run(jobs), who + " after the refused writes");
    });
  }
}

// With MEMW 32 a voxmap word holds 16 voxels; a word with a bit at 32 or above is refused whole, naming the word
// (counted from the write's first word), and through HostCpu::load the burst's address.
TEST(SyscErrors, VoxmapWordAboveMemwIsRefusedOnANarrowTlmTarget) {
  DeviceConfig cfg;
  cfg.MEMW = 32;
  auto p = make_platform("tlm", TargetKind::Tlm, cfg);
  const DeviceMemory mem = origin_memory(cfg, 16);
  ASSERT_EQ(mem.map.size(), 4u);
  p->execute([&](HostCpu& cpu) {
    cpu.load(mem);
    uint8_t w[3 * kMapStride] = {};
    put_le(w + kMapStride, 0xffffffffull, 8);       // fits
    put_le(w + 2 * kMapStride, 0x100000000ull, 8);  // bit 32
    EXPECT_EQ(cpu.access(true, kMapBase + 4 * kMapStride, w, sizeof w), TLM_GENERIC_ERROR_RESPONSE);
    EXPECT_EQ(p->target().last_error(), "tlm.device: voxmap word 2 has bits above MEMW");
    EXPECT_EQ(cpu.read_reg(kRegMapWords), 4u) << "nothing of the refused write is loaded";
    DeviceMemory bad = mem;
    bad.map[3] |= uint64_t{1} << 63;
    EXPECT_EQ(bus_error([&] { cpu.load(bad); }),
              "tlm.cpu: voxmap write at address " + std::to_string(kMapBase) + " got TLM_GENERIC_ERROR_RESPONSE");
    EXPECT_EQ(p->target().last_error(), "tlm.device: voxmap word 3 has bits above MEMW");
    // The shell of that load went in; the voxmap loaded before is still there.
    const std::vector<Job> jobs = {origin_job(1, Mode::All, 16)};
    expect_stream(run_stream(cfg, mem, jobs), cpu.run(jobs), "after the refused voxmap");
  });
}

}  // namespace
}  // namespace voxcd::sysc
