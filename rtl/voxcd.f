// The device's RTL, in compilation order (Verilator's lint waivers, the package, the guarded headers of the assertion
// and parameter macros, then the modules; a module includes a header itself only when it is read without this list),
// one file per line relative to this list; last, the AXI top voxcd_axi (docs/hardware.md), which tools that build
// voxcd_device leave out by naming their top. The order is also the files' name order but for the modules, which may
// come in any order (`verilator -Irtl rtl/*.sv` lints them as they are). Every tool reads this list: CMake (rtl/CMakeLists.txt), the yosys
// scripts (bench/rtl_cost.sh, bench/results.sh), `voxcd size --cost`, and Verilator as `-F voxcd.f`. Lines starting
// with // are comments.
voxcd.vlt
voxcd_arch_pkg.sv
voxcd_assert.svh
voxcd_params.svh
voxcd_ram.sv
voxcd_fifo.sv
voxcd_skid.sv
voxcd_stage.sv
voxcd_ram2.sv
voxcd_bank_rounds.sv
voxcd_shell_expand.sv
voxcd_cell.sv
voxcd_brick_rows.sv
voxcd_transform.sv
voxcd_state_lookup.sv
voxcd_dist_lookup.sv
voxcd_lane.sv
voxcd_shared_banks.sv
voxcd_hit_stage.sv
voxcd_device.sv
voxcd_axi_regs.sv
voxcd_axi_jobs.sv
voxcd_axi_records.sv
voxcd_axi.sv
