# bench_memory: the memory bandwidth that bounds a frame's per-body passes at 10^6 bodies (docs/simulate.md).
add_executable(bench_memory ${CMAKE_CURRENT_LIST_DIR}/bench_memory.cpp)
target_link_libraries(bench_memory PRIVATE Threads::Threads)
voxcd_warnings(bench_memory)
