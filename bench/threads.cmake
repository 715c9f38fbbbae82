# bench_threads: 1 against 2 threads (or any list) in one run, simulate and large pair queries (docs/scale.md).
add_executable(bench_threads ${CMAKE_CURRENT_LIST_DIR}/bench_threads.cpp)
target_link_libraries(bench_threads PRIVATE voxcd_host)
voxcd_warnings(bench_threads)
