// voxcd_assert.svh: named assertions for every module of rtl/ (after lowRISC's prim_assert.sv), and the register
// with asynchronous reset they all use (after common_cells' registers.svh).
//
//   `VOXCD_FF(q, d, reset)          q takes d at every rising edge of clk_i, and reset while rst_ni is low
//   `VOXCD_ASSERT(Name, prop)       prop holds at every rising edge of clk_i while rst_ni is high, from the second
//                                   edge after reset on (so that $past in prop never reads a value from before
//                                   reset: docs/contract.md, "Reset")
//   `VOXCD_ASSERT_INIT(Name, prop)  prop holds at elaboration (parameter sanity)
//   `VOXCD_COVER(Name, prop)        a functional coverage bin: the cycles (clk_i rising, rst_ni high) in which prop
//                                   holds are counted (docs/verification.md, "Functional coverage")
//
// The module that uses them has clk_i and rst_ni. Three readings of one macro:
//   - simulation (Verilator with --assert): a concurrent assertion that names itself when it fires; a cover property
//     whose count Verilator keeps in models built with --coverage-user (the coverage models, rtl/CMakeLists.txt) and
//     ignores in the others;
//   - formal (yosys read_verilog -formal, which defines FORMAL): an immediate assert in a clocked process, which
//     `sat -prove-asserts` proves (tests/formal); covers are left out;
//   - synthesis (SYNTHESIS defined, yosys's default): nothing.
// A guarded include: rtl/voxcd.f lists this file before the modules, so a tool that reads the list defines the macros
// once, and each module that uses them includes it inside `ifndef VOXCD_ASSERT_SVH, so a module read on its own (or
// `verilator --lint-only -Wall -Irtl rtl/*.sv`, tests/rtl/CMakeLists.txt rtl.lint_glob) finds it on the include path.
// Defines outlive the file in Verilator and yosys.
`ifndef VOXCD_ASSERT_SVH
`define VOXCD_ASSERT_SVH

`ifdef FORMAL
  `define VOXCD_ASSERT(__name, __prop) \
    always @(posedge clk_i) if (rst_ni) __name: assert (__prop);
  `define VOXCD_ASSERT_INIT(__name, __prop) \
    initial __name: assert (__prop);
  `define VOXCD_COVER(__name, __prop)
`elsif SYNTHESIS
  `define VOXCD_ASSERT(__name, __prop)
  `define VOXCD_ASSERT_INIT(__name, __prop)
  `define VOXCD_COVER(__name, __prop)
`else
  `define VOXCD_ASSERT(__name, __prop) \
    __name: assert property (@(posedge clk_i) disable iff (!rst_ni || !$past(rst_ni)) (__prop)) \
      else $error("%m: assertion %s failed", `"__name`");
  `define VOXCD_ASSERT_INIT(__name, __prop) \
    if (!(__prop)) begin : __name \
      $error("elaboration check %s failed", `"__name`"); \
    end
  `define VOXCD_COVER(__name, __prop) \
    __name: cover property (@(posedge clk_i) disable iff (!rst_ni) (__prop));
`endif

`define VOXCD_FF(__q, __d, __reset) \
  always_ff @(posedge clk_i or negedge rst_ni) begin \
    if (!rst_ni) __q <= (__reset); \
    else         __q <= (__d); \
  end

`endif  // VOXCD_ASSERT_SVH
