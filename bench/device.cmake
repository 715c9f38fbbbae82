# bench_device: lookup speed of the cpu backend against ref (docs/device-speed.md).
add_executable(bench_device ${CMAKE_CURRENT_LIST_DIR}/bench_device.cpp)
target_link_libraries(bench_device PRIVATE voxcd_host)
voxcd_warnings(bench_device)
# bench_kernel: the lookup kernels alone, 2-bit and distance, in and out of cache; bench/kernel_revisions.sh builds it
# beside the kernels of other git revisions (docs/device-speed.md).
add_executable(bench_kernel ${CMAKE_CURRENT_LIST_DIR}/bench_kernel.cpp)
target_link_libraries(bench_kernel PRIVATE voxcd_ref_fast)
voxcd_warnings(bench_kernel)
