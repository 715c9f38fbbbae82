# bench_record: a recording's size per frame at 256 and 65,536 objects and its cost to the run (docs/view.md).
add_executable(bench_record ${CMAKE_CURRENT_LIST_DIR}/bench_record.cpp)
target_link_libraries(bench_record PRIVATE voxcd_host)
voxcd_warnings(bench_record)
