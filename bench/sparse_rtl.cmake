# bench_sparse_rtl: sparse devices' throughput and latency on the RTL (docs/hardware.md, via bench/sparse_rtl.sh).
add_executable(bench_sparse_rtl ${CMAKE_CURRENT_LIST_DIR}/bench_sparse_rtl.cpp)
target_link_libraries(bench_sparse_rtl PRIVATE voxcd_host voxcd_rtl_models)
add_dependencies(bench_sparse_rtl voxcd_rtl_backend)
voxcd_warnings(bench_sparse_rtl)
