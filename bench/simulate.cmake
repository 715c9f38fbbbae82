# bench_simulate: whole-frame rates of the paper's environment per broadphase (docs/simulate.md).
add_executable(bench_simulate ${CMAKE_CURRENT_LIST_DIR}/bench_simulate.cpp)
target_link_libraries(bench_simulate PRIVATE voxcd_host)
voxcd_warnings(bench_simulate)
