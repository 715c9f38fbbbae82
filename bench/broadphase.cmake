# bench_broadphase: every box broadphase against Bullet (axis sweep, dbvt) and FCL (dynamic AABB tree, SaP) on
# the paper's scene, N = 64 to 65536 (docs/broadphase.md).
find_package(fcl CONFIG QUIET)
voxcd_require_package(fcl_FOUND libfcl-dev "FCL (a peer of bench_broadphase)")
pkg_check_modules(BULLET QUIET IMPORTED_TARGET bullet)
voxcd_require_package(BULLET_FOUND libbullet-dev "Bullet (a peer of bench_broadphase)")
add_executable(bench_broadphase ${CMAKE_CURRENT_LIST_DIR}/bench_broadphase.cpp)
target_link_libraries(bench_broadphase PRIVATE voxcd_host fcl PkgConfig::BULLET)
voxcd_warnings(bench_broadphase)
