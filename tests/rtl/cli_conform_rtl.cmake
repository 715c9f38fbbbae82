# `voxcd conform --backend rtl` as a user runs it: vectors generated for L lanes pass with --cycles on the model
# built for L lanes; --print shows the RTL's own stream with its measured cycles; cycles for another lane count
# are refused.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)

# LANES: the lane counts the build has RTL models of (VOXCD_RTL_LANES, 4 among them).
foreach(lanes ${LANES})
  run(0 out ${VOXCD} conform --generate --seed 3${lanes} --jobs 300 --lanes ${lanes} -o ${WORK}/l${lanes}.vec)
  run(0 out ${VOXCD} conform --backend rtl --lanes ${lanes} --cycles ${WORK}/l${lanes}.vec)
  expect("${out}" "1 passed, 0 failed")
endforeach()

# --print: the RTL's stream, every completion record with its measured cycles, equal to the file's.
run(0 out ${VOXCD} conform --backend rtl --print ${WORK}/l4.vec)
file(READ ${WORK}/l4.vec text)
string(REGEX MATCHALL "\n(hit|done) [^\n]*" printed "\n${out}")
string(REGEX MATCHALL "\n(hit|done) [^\n]*" expected "${text}")
if(NOT printed STREQUAL expected)
  message(FATAL_ERROR "--print on rtl differs from the file's expectations")
endif()
expect("${out}" "\ndone [0-9]+ [0-9]+ [0-9]+")

# Cycles of a file generated for 4 lanes are not those of 8.
run(1 out ${VOXCD} conform --backend rtl --lanes 8 --cycles ${WORK}/l4.vec)
expect("${out}" "cycles are for LANES 4, not --lanes 8")
# A changed cycle count is caught.
string(REGEX MATCH "\ndone ([0-9]+) ([0-9]+) ([0-9]+)" first "${text}")
math(EXPR c "${CMAKE_MATCH_3} + 1")
string(REPLACE "${first}" "\ndone ${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${c}" bad "${text}")
file(WRITE ${WORK}/badcycles.vec "${bad}")
run(1 out ${VOXCD} conform --backend rtl --cycles ${WORK}/badcycles.vec)
expect("${out}" "0 passed, 1 failed")
run(0 out ${VOXCD} conform --backend rtl ${WORK}/badcycles.vec)
