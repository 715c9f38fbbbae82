// The rtl backend's checks on a device that misbehaves: a failed RTL assertion, no progress, and records or
// activity after the last completion record. A correct device and host never do these, so all but the timeout are
// made with the test-only RtlFaults of host/device/detail/rtl.h (the timeout only needs consumers that are never ready).
// Each error must say what happened, leave the caller's records as they were, and belong to the device that failed.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <string>
#include <utility>

#include "voxcd/host/device/device.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/ref/pipeline.h"
#include "tests/error_text.h"
#include "tests/origin_stimulus.h"
#include "tests/rtl/built_lanes.h"

namespace voxcd {
namespace {

// The text of the DeviceError fn throws (tests/error_text.h).
template <class Fn>
std::string device_error(Fn&& fn) {
  return test::error_text<DeviceError>(std::forward<Fn>(fn));
}

using test::origin_job;
using test::origin_memory;

// What a caller holds from an earlier batch; no failed run may touch it.
const std::vector<Record> kEarlier = {Record::hit(7, 1, 2, 3, 0, 1), Record::done(7, 1, 42)};

void expect_untouched(const std::vector<Record>& out) {
  ASSERT_EQ(out.size(), kEarlier.size());
  for (size_t i = 0; i < out.size(); ++i) EXPECT_TRUE(out[i].same_as(kEarlier[i], true)) << out[i].to_string();
}

const std::regex kAssertion(R"(rtl: an assertion in the RTL failed at cycle \d+ \(its message is printed above\))");

TEST(RtlFaults, FailedAssertionIsADeviceErrorOfTheDeviceThatFailed) {
  DeviceConfig cfg;
  cfg.LANES = built_rtl_lanes(2);
  const DeviceMemory mem = origin_memory(cfg, 64);
  const std::vector<Job> jobs = {origin_job(1, Mode::All, 64)};
  RtlFaults faults;
  faults.write_while_busy = true;
  auto bad = make_rtl_device(cfg, {}, faults);
  bad->load(mem);
  // Made after the failing device, so its context is the thread's current one when the failing device runs:
  // the failure must still be the failing device's, not this one's.
  auto good = make_device("rtl", cfg);
  good->load(mem);

  std::vector<Record> out = kEarlier;
  const std::string e = device_error([&] { bad->run_into(jobs, out); });
  EXPECT_TRUE(std::regex_match(e, kAssertion)) << e;
  expect_untouched(out);
  // The failed device stays failed: every later load or run says so again.
  EXPECT_TRUE(std::regex_match(device_error([&] { bad->run(jobs); }), kAssertion));
  EXPECT_TRUE(std::regex_match(device_error([&] { bad->load(mem); }), kAssertion));

  // The other device is untouched by it.
  const std::vector<Record> want = run_stream(cfg, mem, jobs);
  const std::vector<Record> got = good->run(jobs);
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_TRUE(got[i].same_as(want[i], false)) << got[i].to_string();
}

TEST(RtlFaults, NoProgressIsADeviceErrorAfterTheBackendsPatience) {
  // The smallest shell memory this build has a model for: the patience is 1000 + 64 * 2^SAW cycles, 64 times the
  // second term on a sparse device (a shell word there makes up to 64 points).
  DeviceConfig cfg;
  for (const DeviceConfig& c : rtl_configs())
    if (c.SAW < cfg.SAW) cfg = c;
  std::printf("config %s\n", cfg.to_string().c_str());
  DeviceOptions opt;
  opt.hit_stall_prob = 1.0;  // neither stream is ever taken
  opt.done_stall_prob = 1.0;
  auto dev = make_rtl_device(cfg, opt);
  dev->load(origin_memory(cfg, 16));
  const std::vector<Job> jobs = {origin_job(1, Mode::All, 16), origin_job(2, Mode::Count, 16),
                                 origin_job(3, Mode::First, 16)};
  std::vector<Record> out = kEarlier;
  const uint64_t idle = 1000 + 64 * (uint64_t{1} << cfg.SAW) * (cfg.sparse() ? 64 : 1) + 1;
  EXPECT_EQ(device_error([&] { dev->run_into(jobs, out); }),
            "rtl: no record for " + std::to_string(idle) + " cycles after 0 of 3 jobs completed");
  expect_untouched(out);
}

TEST(RtlFaults, RecordAfterTheLastCompletionIsADeviceError) {
  // The run takes the first job's completion for the last one; the second job's hit at point 0 comes after it.
  DeviceConfig cfg;
  RtlFaults faults;
  faults.miss_last_completion = true;
  auto dev = make_rtl_device(cfg, {}, faults);
  dev->load(origin_memory(cfg, 64));
  std::vector<Record> out = kEarlier;
  EXPECT_EQ(device_error([&] { dev->run_into({origin_job(1, Mode::All, 64), origin_job(2, Mode::All, 8)}, out); }),
            "rtl: a record came after the last completion record");
  expect_untouched(out);
}

TEST(RtlFaults, BusyAfterTheLastCompletionIsADeviceError) {
  // The same with a second job that counts 1000 points: no record for 250 cycles, longer than the pipeline.
  DeviceConfig cfg;
  RtlFaults faults;
  faults.miss_last_completion = true;
  auto dev = make_rtl_device(cfg, {}, faults);
  dev->load(origin_memory(cfg, 1000));
  std::vector<Record> out = kEarlier;
  EXPECT_EQ(
      device_error([&] { dev->run_into({origin_job(1, Mode::All, 8), origin_job(2, Mode::Count, 1000)}, out); }),
      "rtl: the device is still busy after the last completion record");
  expect_untouched(out);
}

}  // namespace
}  // namespace voxcd
