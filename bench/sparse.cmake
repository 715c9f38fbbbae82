# bench_sparse: sparse devices' throughput and latency on the RTL (docs/hardware.md, via bench/sparse.sh).
add_executable(bench_sparse ${CMAKE_CURRENT_LIST_DIR}/bench_sparse.cpp)
target_link_libraries(bench_sparse PRIVATE voxcd_host voxcd_rtl_models)
add_dependencies(bench_sparse voxcd_rtl_backend)
voxcd_warnings(bench_sparse)
