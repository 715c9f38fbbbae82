# bench_device: lookup speed of the cpu backend against ref (docs/device-speed.md).
add_executable(bench_device ${CMAKE_CURRENT_LIST_DIR}/bench_device.cpp)
target_link_libraries(bench_device PRIVATE voxcd_host)
voxcd_warnings(bench_device)
