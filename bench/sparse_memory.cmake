# bench_sparse_memory: sparse voxmaps and shells against dense ones and OpenVDB's bool grid (docs/voxelize.md, "Sparse
# voxmaps"; bench/sparse_memory.sh runs it with the real models and voxcd voxelize at 4,096 voxels across). OpenVDB is found
# by voxelize.cmake, which comes first.
add_executable(bench_sparse_memory ${CMAKE_CURRENT_LIST_DIR}/bench_sparse_memory.cpp)
target_link_libraries(bench_sparse_memory PRIVATE voxcd_host OpenVDB::openvdb)
voxcd_warnings(bench_sparse_memory)
