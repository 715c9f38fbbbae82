# bench_pair: pair queries against FCL on the same meshes and poses (docs/pairs.md).
find_package(fcl CONFIG QUIET)
voxcd_require_package(fcl_FOUND libfcl-dev "FCL (the peer of bench_pair)")
add_executable(bench_pair ${CMAKE_CURRENT_LIST_DIR}/bench_pair.cpp)
target_link_libraries(bench_pair PRIVATE voxcd_host fcl)
voxcd_warnings(bench_pair)
# bench_distance_error: 2-bit and distance voxmaps against exact geometry, beside FCL (docs/results.md, "Distance voxmaps").
add_executable(bench_distance_error ${CMAKE_CURRENT_LIST_DIR}/bench_distance_error.cpp)
target_link_libraries(bench_distance_error PRIVATE voxcd_host fcl)
voxcd_warnings(bench_distance_error)
# bench_differential: the corpus against FCL's exact collide in 2-bit and distance mode (docs/results.md,
# "Against exact geometry on every kind of model").
add_executable(bench_differential ${CMAKE_CURRENT_LIST_DIR}/bench_differential.cpp)
target_link_libraries(bench_differential PRIVATE voxcd_host fcl)
voxcd_warnings(bench_differential)
# bench_contacts: every contact of pair queries against FCL's exhaustive collide, one thread each: the room-and-robot
# scene and the tori (docs/pairs.md, "Speed near the machine's limit").
add_executable(bench_contacts ${CMAKE_CURRENT_LIST_DIR}/bench_contacts.cpp)
target_link_libraries(bench_contacts PRIVATE voxcd_host fcl)
voxcd_warnings(bench_contacts)
