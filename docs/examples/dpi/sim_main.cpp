// Runs the Verilated testbench tb_voxcd_dpi: drives its clock until it finishes and exits with 1 when it failed
// ($fatal, a failed assertion in the device) and 0 when it passed. Plusargs go to the testbench (+seed=S ...).
// Verilated with --coverage, it writes the design's coverage counts to +coverage=FILE (default coverage.dat), which
// `voxcd regress --coverage DIR` merges and reports (docs/verification.md, "Your own RTL").
#include <verilated.h>
#if VM_COVERAGE
#include <verilated_cov.h>
#endif

#include <memory>

#include "Vtb_voxcd_dpi.h"
// The prototypes Verilator derives from voxcd_dpi_pkg.sv's imports, then the library's own declarations: a
// function whose SystemVerilog and C signatures disagree does not compile.
#include "Vtb_voxcd_dpi__Dpi.h"
#include "voxcd_dpi.h"

int main(int argc, char** argv) {
  const auto ctx = std::make_unique<VerilatedContext>();
  ctx->commandArgs(argc, argv);
  ctx->fatalOnError(false);  // $fatal ends the run with an error status instead of abort()
  const auto tb = std::make_unique<Vtb_voxcd_dpi>(ctx.get(), "tb");
  tb->clk_i = 0;
  tb->eval();
  while (!ctx->gotFinish()) {
    ctx->timeInc(1);
    tb->clk_i = !tb->clk_i;
    tb->eval();
  }
  tb->final();
#if VM_COVERAGE
  const char* file = ctx->commandArgsPlusMatch("coverage=");
  ctx->coveragep()->write(*file ? file + 10 : "coverage.dat");  // the match is "+coverage=FILE"
#endif
  return ctx->gotError() ? 1 : 0;
}
