# bench_hardware: the RTL's throughput, latency and simulation speed (docs/hardware.md, via bench/hardware.sh).
add_executable(bench_hardware ${CMAKE_CURRENT_LIST_DIR}/bench_hardware.cpp)
target_link_libraries(bench_hardware PRIVATE voxcd_host voxcd_rtl_models)
voxcd_warnings(bench_hardware)
