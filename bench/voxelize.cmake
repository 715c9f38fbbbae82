# bench_voxelize: voxelisation and point-shell time against triangles and resolution, shell sizes against voxel
# size, and defective meshes against OpenVDB (docs/voxelize.md).
# OpenVDB's CMake module (shipped by libopenvdb-dev) needs Boost.Iostreams, which the Debian package does not pull.
find_package(Boost QUIET COMPONENTS iostreams)
voxcd_require_package(Boost_FOUND libboost-iostreams-dev "Boost.Iostreams (OpenVDB's CMake module needs it)")
list(APPEND CMAKE_MODULE_PATH /usr/lib/x86_64-linux-gnu/cmake/OpenVDB)
find_package(OpenVDB QUIET)
voxcd_require_package(OpenVDB_FOUND libopenvdb-dev "OpenVDB (the peer of bench_voxelize)")
add_executable(bench_voxelize ${CMAKE_CURRENT_LIST_DIR}/bench_voxelize.cpp)
target_link_libraries(bench_voxelize PRIVATE voxcd_host OpenVDB::openvdb)
voxcd_warnings(bench_voxelize)
