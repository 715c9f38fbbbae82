# bench_sysc: simulation speed of sysc-rtl and sysc-tlm beside rtl and ref (docs/systemc.md).
add_executable(bench_sysc ${CMAKE_CURRENT_LIST_DIR}/bench_sysc.cpp)
target_link_libraries(bench_sysc PRIVATE voxcd_host)
voxcd_warnings(bench_sysc)
