# `voxcd conform --backend sysc-rtl|sysc-tlm` as a user runs it: several files in one process (one SystemC server
# per Device), every lane count, cycles compared; a changed cycle count is caught; a config the RTL models were
# not built for is refused with a message, while the TLM model takes it.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)

# LANES: the lane counts the build has SystemC RTL models of (VOXCD_SYSC_LANES).
set(files)
foreach(lanes ${LANES})
  run(0 out ${VOXCD} conform --generate --seed 5${lanes} --jobs 120 --lanes ${lanes} -o ${WORK}/l${lanes}.vec)
  list(APPEND files ${WORK}/l${lanes}.vec)
endforeach()
list(LENGTH files n)
foreach(backend sysc-tlm sysc-rtl)
  run(0 out ${VOXCD} conform --backend ${backend} --cycles ${files})
  expect("${out}" "${n} passed, 0 failed")
endforeach()

# --print gives the stream with cycles, equal to the file's.
list(GET files 0 first_file)
run(0 out ${VOXCD} conform --backend sysc-tlm --print ${first_file})
file(READ ${first_file} text)
string(REGEX MATCHALL "\n(hit|done) [^\n]*" printed "\n${out}")
string(REGEX MATCHALL "\n(hit|done) [^\n]*" expected "${text}")
if(NOT printed STREQUAL expected)
  message(FATAL_ERROR "--print on sysc-tlm differs from the file's expectations")
endif()

string(REGEX MATCH "\ndone ([0-9]+) ([0-9]+) ([0-9]+)" first "${text}")
math(EXPR c "${CMAKE_MATCH_3} + 1")
string(REPLACE "${first}" "\ndone ${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${c}" bad "${text}")
file(WRITE ${WORK}/badcycles.vec "${bad}")
foreach(backend sysc-tlm sysc-rtl)
  run(1 out ${VOXCD} conform --backend ${backend} --cycles ${WORK}/badcycles.vec)
  expect("${out}" "0 passed, 1 failed")
endforeach()

run(0 out ${VOXCD} conform --generate --seed 9 --jobs 40 --config "PW 14 PF 3 MW 10 MF 8 TW 24 DW 7 MEMW 16"
    -o ${WORK}/narrow.vec)
run(0 out ${VOXCD} conform --backend sysc-tlm --cycles ${WORK}/narrow.vec)
expect("${out}" "1 passed, 0 failed")
run(1 out ${VOXCD} conform --backend sysc-rtl ${WORK}/narrow.vec)
expect("${out}" "default widths")
