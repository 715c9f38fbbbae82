// The RTL's named assertions run in the Verilated model: a violation of the device's rules stops it with the
// assertion's message. Each test breaks one rule on purpose, through the pins.
#include <gtest/gtest.h>
#include <verilated.h>

#include <memory>

#include VOXCD_PIN_MODEL_HEADER  // the first lane count of VOXCD_RTL_LANES (tests/rtl/CMakeLists.txt)

namespace voxcd {
namespace {

struct Bench {
  std::unique_ptr<VerilatedContext> ctx = std::make_unique<VerilatedContext>();
  std::unique_ptr<VOXCD_PIN_MODEL> m;
  Bench() {
    ctx->fatalOnError(false);
    m = std::make_unique<VOXCD_PIN_MODEL>(ctx.get(), "voxcd");
    m->clk_i = 0;
    m->rst_ni = 0;
    m->hit_ready_i = 1;
    m->done_ready_i = 1;
    m->eval();
    tick();
    m->rst_ni = 1;
    tick();  // the assertions are checked from the second edge after reset (docs/contract.md, "Reset")
  }
  ~Bench() { m->final(); }
  void tick() {
    m->clk_i = 1;
    m->eval();
    m->clk_i = 0;
    m->eval();
  }
  void submit_job(uint32_t count) {
    m->job_valid_i = 1;
    m->job_mode_i = 0;
    m->job_mask_i = 6;
    m->job_shell_base_i = 0;
    m->job_shell_count_i = count;
    m->job_map_base_i = 0;
    m->job_nx_i = m->job_ny_i = m->job_nz_i = 4;
    m->job_m00_i = m->job_m11_i = m->job_m22_i = 1u << 16;
  }
};

TEST(RtlAssertions, ValidRunRaisesNone) {
  Bench b;
  b.submit_job(40);
  for (int i = 0; i < 60; ++i) {
    b.tick();
    b.m->job_valid_i = 0;
  }
  EXPECT_FALSE(b.ctx->gotError());
  EXPECT_FALSE(b.m->busy_o);
}

TEST(RtlAssertions, MemoryWriteWhileBusyIsCaught) {
  Bench b;
  b.submit_job(40);
  b.tick();
  b.m->job_valid_i = 0;
  b.tick();
  ASSERT_TRUE(b.m->busy_o);
  b.m->map_we_i = 1;
  b.tick();
  EXPECT_TRUE(b.ctx->gotError());
}

TEST(RtlAssertions, InvalidModeIsCaught) {
  Bench b;
  b.submit_job(4);
  b.m->job_mode_i = 3;
  b.tick();
  EXPECT_TRUE(b.ctx->gotError());
}

TEST(RtlAssertions, ZeroSizedMapIsCaught) {
  Bench b;
  b.submit_job(4);
  b.m->job_ny_i = 0;
  b.tick();
  EXPECT_TRUE(b.ctx->gotError());
}

}  // namespace
}  // namespace voxcd
