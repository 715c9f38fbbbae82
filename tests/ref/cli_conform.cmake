# voxcd conform as a user runs it: generate, pass; break one expectation, fail with the file, tag and point;
# a truncated file fails with its line; the summary line and the exit code say so.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)

run(0 out ${VOXCD} conform --generate --seed 7 --jobs 150 --lanes 4 -o ${WORK}/good.vec)
run(0 out ${VOXCD} conform ${WORK}/good.vec)
expect("${out}" "1 passed, 0 failed")

# Change the first expected hit's voxel x coordinate.
file(READ ${WORK}/good.vec text)
string(REGEX MATCH "\nhit ([0-9]+) ([0-9]+) ([0-9]+) " first "${text}")
if(NOT first)
  message(FATAL_ERROR "generated file has no hit record")
endif()
set(tag ${CMAKE_MATCH_1})
set(point ${CMAKE_MATCH_2})
math(EXPR x "${CMAKE_MATCH_3} + 1")
string(REPLACE "${first}" "\nhit ${tag} ${point} ${x} " bad "${text}")
file(WRITE ${WORK}/bad.vec "${bad}")
run(1 out ${VOXCD} conform ${WORK}/good.vec ${WORK}/bad.vec)
expect("${out}" "1 passed, 1 failed")
expect("${out}" "FAIL ${WORK}/bad.vec: job tag ${tag} .*point ${point}: expected 'hit ${tag} ${point} ${x} ")

# Truncate inside the shell section.
string(SUBSTRING "${text}" 0 400 head)
string(FIND "${head}" "\n" last_nl REVERSE)
math(EXPR keep "${last_nl} + 1")
string(SUBSTRING "${head}" 0 ${keep} head)
file(WRITE ${WORK}/trunc.vec "${head}")
run(1 out ${VOXCD} conform ${WORK}/trunc.vec)
expect("${out}" "FAIL ${WORK}/trunc.vec:[0-9]+: truncated: the shell section at line [0-9]+ declares")
expect("${out}" "0 passed, 1 failed")

# --print writes the backend's own stream, which is the file's expectations.
run(0 out ${VOXCD} conform --print ${WORK}/good.vec)
string(REGEX MATCHALL "\n(hit|done) [^\n]*" printed "\n${out}")
string(REGEX MATCHALL "\n(hit|done) [^\n]*" expected "${text}")
list(LENGTH printed np)
list(LENGTH expected ne)
if(NOT np EQUAL ne OR np EQUAL 0)
  message(FATAL_ERROR "--print gave ${np} records, the file expects ${ne}")
endif()
