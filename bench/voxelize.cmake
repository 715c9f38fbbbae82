# bench_voxelize: voxelisation and point-shell time against triangles and resolution, shell sizes against voxel
# size (docs/voxelize.md).
add_executable(bench_voxelize ${CMAKE_CURRENT_LIST_DIR}/bench_voxelize.cpp)
target_link_libraries(bench_voxelize PRIVATE voxcd_host)
voxcd_warnings(bench_voxelize)
