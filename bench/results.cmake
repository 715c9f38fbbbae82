# bench_results: the paper's pair-wise evaluation (Table 1, Figs. 11-13), speed against error per voxel size with
# FCL and Bullet narrow phases on the same poses, and fixed-point widths against exact arithmetic
# (docs/results.md, made by bench/results.sh).
find_package(fcl CONFIG QUIET)
voxcd_require_package(fcl_FOUND libfcl-dev "FCL (exact geometry and a peer of bench_results)")
pkg_check_modules(BULLET QUIET IMPORTED_TARGET bullet)
voxcd_require_package(BULLET_FOUND libbullet-dev "Bullet (a peer of bench_results)")
add_executable(bench_results ${CMAKE_CURRENT_LIST_DIR}/bench_results.cpp)
target_link_libraries(bench_results PRIVATE voxcd_host fcl PkgConfig::BULLET)
voxcd_warnings(bench_results)
