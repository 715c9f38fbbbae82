# bench_against_cpu: the device's cycles on the room and the tori for every lane count and depth, and the cpu backend's
# lookups per second on one core and on every core; bench/against_cpu.sh makes docs/hardware.md's "Against the CPU"
# from it and `voxcd simulate`.
add_executable(bench_against_cpu ${CMAKE_CURRENT_LIST_DIR}/bench_against_cpu.cpp)
target_link_libraries(bench_against_cpu PRIVATE voxcd_host)
voxcd_warnings(bench_against_cpu)
if(VOXCD_TESTS)
  # The script's quick run into a file of its own, and its table checked: a row per lane count, points per cycle in
  # (0, LANES] (bench/against_cpu_check.py).
  set(out ${CMAKE_CURRENT_BINARY_DIR}/against_cpu_quick.md)
  add_test(NAME bench.against_cpu_quick
           COMMAND bash -c "bash bench/against_cpu.sh --quick --build '${CMAKE_BINARY_DIR}' --out '${out}' && /usr/bin/python3 bench/against_cpu.py check '${out}' --lanes 4,8,16,32,64"
           WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(bench.against_cpu_quick PROPERTIES LABELS "bench" TIMEOUT 600)
endif()
