# bench_distance: the signed distance field and the shell on the surface, against triangle count and resolution
# (docs/objects.md, "Distance fields").
add_executable(bench_distance ${CMAKE_CURRENT_LIST_DIR}/bench_distance.cpp)
target_link_libraries(bench_distance PRIVATE voxcd_host)
voxcd_warnings(bench_distance)
