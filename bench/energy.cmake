# bench_energy: vector files of real scenes' jobs for bench/energy.sh (docs/hardware.md, "Energy per lookup"); it runs
# them on the rtl backend itself (voxcd conform --backend rtl --trace).
add_executable(bench_energy ${CMAKE_CURRENT_LIST_DIR}/bench_energy.cpp)
target_link_libraries(bench_energy PRIVATE voxcd_host)
voxcd_warnings(bench_energy)
