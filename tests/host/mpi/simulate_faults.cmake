# A distributed voxcd simulate whose rank fails, exits or hangs (VOXCD_TESTING_FRAME_FAULT, docs/scale.md) ends with
# an error naming the rank, within the timeout: never a hang, never a summary as if nothing happened.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(faulty fault pattern)
  string(TIMESTAMP t0 "%s")
  execute_process(COMMAND ${MPIEXEC} --oversubscribe -x VOXCD_TESTING_FRAME_FAULT=${fault} -np 3 ${VOXCD} simulate
                          --objects 128 --frames 30 --json --threads 1 --mpi-timeout 4
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  string(TIMESTAMP t1 "%s")
  math(EXPR took "${t1} - ${t0}")
  if(rc EQUAL 0 OR "${out}" MATCHES "state_hash")
    message(FATAL_ERROR "fault ${fault}: the run succeeded (rc ${rc}):\n${out}\n${err}")
  endif()
  if(NOT "${out}${err}" MATCHES "${pattern}")
    message(FATAL_ERROR "fault ${fault}: expected a message matching '${pattern}', got (rc ${rc}):\n${out}\n${err}")
  endif()
  message(STATUS "fault ${fault}: rc ${rc} after ${took} s")
endfunction()

# Rank 1 throws at frame 5: it names itself and ends every rank.
faulty(fail:1:5 "voxcd simulate: rank 1 of 3: planted fault")
# Rank 2 hangs at frame 7: ranks 0 and 1 wait 4 s, then (the first of them) name rank 2 and its slab.
faulty(hang:2:7 "rank [01] of 3: no outcomes of frame 7 within 4 s \\(--mpi-timeout\\) from rank 2 \\(slab 2 of 3")
# Rank 1 exits at frame 3 without a word: mpirun (or rank 0's deadline) ends the run naming it.
faulty(exit:1:3 "Process name: \\[\\[[0-9]+,[0-9]+\\],1\\]")
