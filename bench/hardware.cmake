# bench_hardware: the RTL's throughput, latency and simulation speed (docs/hardware.md, via bench/hardware.sh). Its
# latency is measured on the pins of the LANES 4 model; the rest runs on the rtl backend (its module, loaded).
if("4" IN_LIST VOXCD_RTL_LANES)
  add_executable(bench_hardware ${CMAKE_CURRENT_LIST_DIR}/bench_hardware.cpp)
  target_link_libraries(bench_hardware PRIVATE voxcd_host voxcd_rtl_models)
  add_dependencies(bench_hardware voxcd_rtl_backend)
  voxcd_warnings(bench_hardware)
else()
  message(STATUS "bench_hardware is not built: it needs the LANES 4 model (VOXCD_RTL_LANES = ${VOXCD_RTL_LANES})")
endif()
