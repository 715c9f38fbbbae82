# bench_sysc: simulation speed of sysc-rtl and sysc-tlm beside rtl and ref (docs/systemc.md).
add_executable(bench_sysc ${CMAKE_CURRENT_LIST_DIR}/bench_sysc.cpp)
target_link_libraries(bench_sysc PRIVATE voxcd_host)
voxcd_warnings(bench_sysc)
# bench_sysc_platform: one target batch after batch inside one platform (no server process); needs sysc/.
if(TARGET voxcd_sysc)
  add_executable(bench_sysc_platform ${CMAKE_CURRENT_LIST_DIR}/bench_sysc_platform.cpp)
  target_link_libraries(bench_sysc_platform PRIVATE voxcd_sysc voxcd_host)
  voxcd_warnings(bench_sysc_platform)
endif()
