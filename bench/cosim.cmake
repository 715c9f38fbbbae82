# bench_cosim: co-simulation speed of the Verilated device under Verilator and harness options (docs/hardware.md,
# "Co-simulation speed"). Four LANES 4 models of the same source, each with one more option than the one before:
# the rtl backend's own options (FST tracing compiled in, --assert, the default memory depths), no tracing, the
# memories sized to what the benchmark loads (SAW 12, MAW 13), and --noassert. Their own library: Verilator's
# runtime compiled once for the four.
add_library(voxcd_cosim_models STATIC)
set(cosim_common -GLANES=4 -O3 --x-assign fast --x-initial fast)
foreach(variant "base;TRACE_FST;--assert" "notrace;;--assert" "sized;;--assert;-GSAW=12;-GMAW=13"
                "noassert;;--noassert;-GSAW=12;-GMAW=13")
  list(GET variant 0 name)
  list(GET variant 1 trace)
  list(SUBLIST variant 2 -1 args)
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/Vcosim_${name})
  verilate(voxcd_cosim_models
    SOURCES ${VOXCD_RTL_SOURCES}
    TOP_MODULE voxcd_device
    PREFIX Vcosim_${name}
    DIRECTORY ${dir}
    ${trace}
    VERILATOR_ARGS ${args} ${cosim_common})
  target_include_directories(voxcd_cosim_models SYSTEM PUBLIC ${dir})
endforeach()
target_include_directories(voxcd_cosim_models SYSTEM PUBLIC ${VERILATOR_ROOT}/include ${VERILATOR_ROOT}/include/vltstd)
target_link_libraries(voxcd_cosim_models PUBLIC ZLIB::ZLIB Threads::Threads)
add_executable(bench_cosim ${CMAKE_CURRENT_LIST_DIR}/bench_cosim.cpp)
target_link_libraries(bench_cosim PRIVATE voxcd_cosim_models voxcd_ref)
voxcd_warnings(bench_cosim)
