# bench_distance: the signed distance field and the shell on the surface, against triangle count and resolution
# (docs/objects.md, "Distance fields").
add_executable(bench_distance ${CMAKE_CURRENT_LIST_DIR}/bench_distance.cpp)
target_link_libraries(bench_distance PRIVATE voxcd_host)
voxcd_warnings(bench_distance)
# bench_sparse_field: sparse distance fields built brick by brick up to 4,096 voxels across: time, memory, cells,
# levels and bytes beside a dense map's (docs/objects.md, "Sparse distance field").
add_executable(bench_sparse_field ${CMAKE_CURRENT_LIST_DIR}/bench_sparse_field.cpp)
target_link_libraries(bench_sparse_field PRIVATE voxcd_host)
voxcd_warnings(bench_sparse_field)
