# Dependencies of the object pipeline (meshes, PNG pictures).
find_package(assimp CONFIG QUIET)
voxcd_require_package(assimp_FOUND libassimp-dev "assimp (mesh file formats)")
find_package(ZLIB QUIET)
voxcd_require_package(ZLIB_FOUND zlib1g-dev "zlib (PNG pictures)")
target_link_libraries(voxcd_host PUBLIC assimp::assimp ZLIB::ZLIB)
# The parity predicates are exact integer arithmetic; keep the float side free of contractions so that results
# do not depend on the compiler's choice.
set_source_files_properties(${CMAKE_CURRENT_SOURCE_DIR}/voxelize.cpp PROPERTIES COMPILE_OPTIONS "-ffp-contract=off")
