// The AXI top (rtl/voxcd_axi.sv) in the SystemC platform: the host processor's TLM transactions become AXI4-Lite
// writes and AXI4-Stream beats at the top's pins (sysc/axi_target.h), and the records that come back are ref/'s.
// One SystemC elaboration per process: one test here. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/sysc/axi_target.h"
#include "voxcd/sysc/platform.h"
#include "tests/seed.h"

namespace voxcd::sysc {
namespace {

using namespace sc_core;

TEST(SyscAxi, GeneratedVectorsThroughThePlatform) {
  const uint64_t seed = test::seed(4242);
  PlatformOptions opt;
  opt.target = TargetKind::RtlAxi;
  opt.config = axi_target_config();
  Platform p("platform", opt);
  auto& axi = dynamic_cast<AxiRtlTarget&>(p.target());
  // Two batches, each after loading its own memories: the second load happens between batches, while idle.
  uint64_t jobs_total = 0, writes = 1;  // RUN once
  for (int round = 0; round < 2; ++round) {
    const GeneratedVectors g = generate_vectors({seed + uint64_t(round), 80, 600, opt.config, {}});
    std::vector<Record> got;
    p.execute([&](HostCpu& cpu) {
      cpu.load(g.memory);
      got = cpu.run(g.jobs);
    });
    const std::vector<Record> want = run_stream(opt.config, g.memory, g.jobs);
    ASSERT_EQ(got.size(), want.size()) << "round " << round << ", seed " << seed;
    for (size_t i = 0; i < want.size(); ++i)
      ASSERT_TRUE(got[i].same_as(want[i], false)) << "round " << round << ", record " << i << ": got "
                                                   << got[i].to_string() << ", want " << want[i].to_string()
                                                   << ", seed " << seed;
    EXPECT_GT(std::count_if(got.begin(), got.end(), [](const Record& r) { return r.kind == Record::Hit; }), 100)
        << "round " << round << ": too few hit records to say much";
    jobs_total += g.jobs.size();
    writes += 2 * g.memory.shell.size() + g.memory.map.size();
    uint64_t done = 0;
    p.execute([&](HostCpu& cpu) { done = cpu.read_reg(kRegJobsDone); });
    EXPECT_EQ(done, jobs_total);
  }
  // Every memory word went over AXI4-Lite (two writes per shell word, one per voxmap word), and RUN once.
  EXPECT_EQ(axi.lite_writes(), writes);
  EXPECT_EQ(p.target().last_error(), "");
}

}  // namespace
}  // namespace voxcd::sysc

int sc_main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
