# bench_cosim: co-simulation speed of the Verilated device under Verilator and harness options (docs/hardware.md,
# "Co-simulation speed"). Four LANES 4 models of the same source, each with one more option than the one before:
# the rtl backend's own options (FST tracing compiled in, --assert, the default memory depths), no tracing, the
# memories sized to what the benchmark loads (SAW 12, MAW 13), and --noassert. Their own library: Verilator's
# runtime compiled once for the four.
voxcd_model_library(voxcd_cosim_models STATIC TRACE_FST)
voxcd_model(voxcd_cosim_models Vcosim_base PARAMS "LANES 4" TRACE_FST)
voxcd_model(voxcd_cosim_models Vcosim_notrace PARAMS "LANES 4")
voxcd_model(voxcd_cosim_models Vcosim_sized PARAMS "LANES 4 SAW 12 MAW 13")
voxcd_model(voxcd_cosim_models Vcosim_noassert PARAMS "LANES 4 SAW 12 MAW 13" NOASSERT)
add_executable(bench_cosim ${CMAKE_CURRENT_LIST_DIR}/bench_cosim.cpp)
target_link_libraries(bench_cosim PRIVATE voxcd_cosim_models voxcd_ref)
voxcd_warnings(bench_cosim)
