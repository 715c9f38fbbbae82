# The quick coverage campaign: the AXI tests on the AXI tops' coverage models (AXI_COV, test_axi_cov), then
# tests/host/regress/coverage_quick.json on the device's coverage models with random back-pressure, merged: both must
# pass, and every functional bin of BINS (tests/host/regress/coverage_bins.txt, the bins it hit when the list was
# made) must still be hit; a bin that is no longer hit fails the test by name. Run with -DUPDATE=ON to rewrite the
# list from this run (docs/verification.md, "Functional coverage").
cmake_minimum_required(VERSION 3.13)  # IN_LIST
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_COVERAGE_DIR=${WORK} ${AXI_COV}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the AXI tests on the coverage models failed (${rc}):\n${out}${err}")
endif()
execute_process(COMMAND ${VOXCD} regress --campaign ${CAMPAIGN} --coverage ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "voxcd regress --coverage exited with ${rc}")
endif()
foreach(f merged.dat coverage.info bins.txt summary.txt html/index.html)
  if(NOT EXISTS ${WORK}/${f})
    message(FATAL_ERROR "voxcd regress --coverage wrote no ${f}")
  endif()
endforeach()
if(NOT out MATCHES "line +[0-9.]+%" OR NOT out MATCHES "branch +[0-9.]+%" OR NOT out MATCHES "functional +[0-9.]+%")
  message(FATAL_ERROR "the report gives no line, branch and functional coverage")
endif()
file(STRINGS ${WORK}/bins.txt lines)
set(hit "")
foreach(l ${lines})
  if(l MATCHES "^([^ ]+) ([0-9]+)$" AND NOT CMAKE_MATCH_2 EQUAL 0)
    list(APPEND hit "${CMAKE_MATCH_1}")
  endif()
endforeach()
if(UPDATE)
  list(SORT hit)
  string(REPLACE ";" "\n" text "${hit}")
  file(WRITE ${BINS} "# The functional bins tests/host/regress/coverage_quick.json hits (docs/verification.md): written by "
                    "tests/host/regress/coverage_quick.cmake -DUPDATE=ON\n${text}\n")
  return()
endif()
file(STRINGS ${BINS} want REGEX "^[^#]")
set(lost "")
foreach(b ${want})
  if(NOT b IN_LIST hit)
    list(APPEND lost "${b}")
  endif()
endforeach()
list(LENGTH want n)
if(lost)
  string(REPLACE ";" "\n  " lost "${lost}")
  message(FATAL_ERROR "functional bins the quick campaign used to hit are no longer hit:\n  ${lost}")
endif()
message("all ${n} bins of ${BINS} hit")

# Coverage-directed stimulus: a report whose only holes are face.x.n (a template aims at it) and an RTL bin (none
# does); --aim-at-holes aims at the first and hits it.
set(aimed ${WORK}/aimed)
file(MAKE_DIRECTORY ${aimed})
file(WRITE ${aimed}/bins.txt "u_hit_stage.CoverFullSlot 0\nface.x.n 0\nface.x.0 5\n")
execute_process(COMMAND ${VOXCD} regress --seeds 7 --configs default --lanes 4 --backends rtl --jobs-per-shard 20
                        --cycles --coverage ${aimed} --aim-at-holes
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "aiming every second job at 1 stimulus bins: face.x.n\n")
  message(FATAL_ERROR "--aim-at-holes did not aim at face.x.n alone (exit ${rc})")
endif()
file(STRINGS ${aimed}/bins.txt face REGEX "^face.x.n ")
if(NOT face MATCHES "^face.x.n [1-9][0-9]*$")
  message(FATAL_ERROR "the aimed campaign did not hit face.x.n: '${face}'")
endif()

# Two MPI ranks write into one directory; rank 0 merges every shard's counts.
set(ranks ${WORK}/ranks)
execute_process(COMMAND ${MPIEXEC} -np 2 ${VOXCD} regress --seeds 1-3 --configs "default;BL 3" --lanes 4 --backends rtl
                        --jobs-per-shard 30 --cycles --coverage ${ranks}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0 OR NOT out MATCHES "run now on 2 ranks" OR NOT out MATCHES "6 coverage data files merged")
  message(FATAL_ERROR "two ranks did not write and merge the 6 shards' coverage (exit ${rc})")
endif()
