# voxcd simulate at any object count with otherwise default options (COUNTS, comma-separated), and unless
# ERRORS is OFF: the default voxel, --resolution (and its scene-file key, which voxcd size reads too), and the
# errors for --voxel with --resolution, a resolution below 4 and a density at which the objects cannot be placed.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)

string(REPLACE "," ";" counts "${COUNTS}")
foreach(n IN LISTS counts)
  run(0 out ${VOXCD} simulate --objects ${n} --frames 2 --no-progress)
  expect("${out}" "voxcd simulate: ${n} x polytope36 in a cube of side 100 at density 0\\.025, voxel [0-9.e-]+ \\(827 shell points, voxmap 15x12x11\\)")
  expect("${out}" "state hash      [0-9a-f]+")
endforeach()

if(NOT ERRORS STREQUAL "OFF")
  # The paper's scene keeps voxel 1; 512 objects are half as large, and so is their voxel.
  run(0 out ${VOXCD} simulate --frames 2)
  expect("${out}" "64 x polytope36 in a cube of side 100 at density 0\\.025, voxel 1 \\(827 shell points, voxmap 15x12x11\\)")
  run(0 out ${VOXCD} simulate --objects 512 --frames 2)
  expect("${out}" "voxel 0\\.5 \\(827 shell points, voxmap 15x12x11\\)")
  # --resolution: voxels along the longest side (12.2568 units at 64 objects).
  run(0 out ${VOXCD} simulate --resolution 24 --frames 2 --json)
  expect("${out}" "\"voxel\": 0\\.5106")
  run(0 out ${VOXCD} simulate --objects 65536 --voxel 0.1 --frames 2)
  expect("${out}" "voxel 0\\.1 ")

  run(105 out ${VOXCD} simulate --voxel 1 --resolution 10)
  expect("${out}" "--voxel, --resolution: give the voxel size in world units \\(--voxel\\) or the voxels along an object's longest side \\(--resolution\\), not both")
  run(105 out ${VOXCD} simulate --resolution 3)
  expect("${out}" "--resolution: Value 3 not in range 4 to 1020")
  run(105 out ${VOXCD} simulate --voxel 0)
  expect("${out}" "--voxel: must be a positive number of world units")
  run(2 out ${VOXCD} simulate --density 0.3)
  expect("${out}" "voxcd: error: scene: could not place object 27 of 64 without overlapping bounding spheres: at density 0\\.3 each object's bounding sphere has radius 16\\.6[0-9]*, and even packed on a lattice only 27 such spheres fit the cube; 64 objects of this shape fit up to a density of about 0\\.12")
  # Crowded beyond random placement: the lattice places them.
  run(0 out ${VOXCD} simulate --objects 4096 --density 0.14 --frames 2)

  # Scene files: "resolution" beside "voxel", exactly one of them (or the default).
  file(WRITE ${WORK}/res.json "{\"types\": [{\"shape\": \"cube\", \"count\": 8, \"size\": 4, \"resolution\": 16}], \"environment\": {\"side\": 40}}")
  run(0 out ${VOXCD} simulate ${WORK}/res.json --frames 2)
  expect("${out}" "type cube                 voxel 0\\.25,")
  run(0 out ${VOXCD} simulate ${WORK}/res.json --frames 2 --resolution 8)
  expect("${out}" "type cube                 voxel 0\\.5,")
  run(0 out ${VOXCD} simulate ${WORK}/res.json --frames 2 --voxel 0.4)
  expect("${out}" "type cube                 voxel 0\\.4,")
  run(0 out ${VOXCD} size ${WORK}/res.json --frames 5)
  expect("${out}" "type cube: voxel 0\\.25,")
  file(WRITE ${WORK}/both.json "{\"types\": [{\"shape\": \"cube\", \"voxel\": 1, \"resolution\": 16}]}")
  run(2 out ${VOXCD} simulate ${WORK}/both.json)
  expect("${out}" "both\\.json: types\\[0\\]: give \"voxel\" \\(world units\\) or \"resolution\" \\(voxels along the longest side\\), not both")
  run(2 out ${VOXCD} size ${WORK}/both.json)
  expect("${out}" "both\\.json: types\\[0\\]: give \"voxel\"")
  file(WRITE ${WORK}/coarse.json "{\"types\": [{\"shape\": \"cube\", \"resolution\": 2}]}")
  run(2 out ${VOXCD} simulate ${WORK}/coarse.json)
  expect("${out}" "coarse\\.json: types\\[0\\]\\.resolution: 2 is outside \\[4, 1020\\]")
endif()
