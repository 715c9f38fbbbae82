# voxcd size reports a frame's energy and the power at the requested rate: text lines that say what the lookups are
# and where the energy per lookup comes from (an estimate for small.json's derived configuration), and JSON fields.
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)
set(scene ${SCENES}/small.json)

run(0 out ${VOXCD} size ${scene})
expect("${out}" "\nenergy          [0-9.]+ [pnum]?J a frame \\(the mean frame's [0-9.]+ lookups x 581\\.02 pJ a lookup at 0\\.18 um; estimate: 581\\.02 pJ a lookup measured for LANES 4 DEPTH 0 \\(simulate scene\\), not for LANES 1 [^\n]*, docs/hardware\\.md\\)\n")
expect("${out}" "\npower           [0-9.]+ [pnum]?W at 2000 frames/s ")
expect("${out}" "\nprojection      [0-9.]+ [pnum]?J a frame, [0-9.]+ [pnum]?W at 7 nm \\(1\\.053 pJ a lookup: a projection")

run(0 out ${VOXCD} size ${scene} --json)
foreach(key energy_per_frame_j power_w energy_per_frame_7nm_j power_7nm_w energy_pj_per_lookup energy_lookups_per_frame)
  string(JSON type TYPE "${out}" ${key})
  if(NOT type STREQUAL "NUMBER")
    message(FATAL_ERROR "${key} is ${type}, not a number:\n${out}")
  endif()
endforeach()
string(JSON estimate GET "${out}" energy_estimate)
string(JSON source GET "${out}" energy_source)
string(JSON of GET "${out}" energy_lookups_of)
string(JSON pj GET "${out}" energy_pj_per_lookup)
if(NOT estimate OR NOT source MATCHES "^estimate: 581.02 pJ a lookup measured for LANES 4 DEPTH 0 \\(simulate scene\\), not for "
   OR NOT of STREQUAL "mean frame" OR NOT pj EQUAL 581.02)
  message(FATAL_ERROR "estimate ${estimate}, source '${source}', lookups of '${of}', ${pj} pJ:\n${out}")
endif()
