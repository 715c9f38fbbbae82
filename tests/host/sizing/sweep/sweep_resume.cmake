# A sweep stopped part way resumes from its results file and ends with every point run once: stopped by
# --stop-after, by a rank that exits (Open MPI ends the job), or cut in the middle of a line; the table is the
# uninterrupted run's. Faults end the run naming the rank and the point; bad sweep and results files are refused.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/sweep_common.cmake)

run(0 whole ${VOXCD} sweep ${sweep} --results ${WORK}/whole.jsonl --csv ${WORK}/whole.csv)
expect("${whole}" "0 of ${points} points from the results file")
check_exactly_once(${WORK}/whole.jsonl)

# --stop-after 3 (exit code 3: incomplete), then the rest on 3 ranks: 3 read back, 5 run now.
run(3 part ${VOXCD} sweep ${sweep} --results ${WORK}/stop.jsonl --stop-after 3)
expect("${part}" "incomplete: 3 of ${points} points")
run(0 rest ${mpirun} -np 3 ${VOXCD} sweep ${sweep} --results ${WORK}/stop.jsonl --csv ${WORK}/stop.csv)
expect("${rest}" "3 of ${points} points from the results file")
check_exactly_once(${WORK}/stop.jsonl)
same_file(${WORK}/whole.csv ${WORK}/stop.csv)

# A rank that exits on point 5 ends the job; what finished is in the file, and a rerun runs only the others.
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_TESTING_SWEEP_FAULT=exit:5
                        ${mpirun} -x VOXCD_TESTING_SWEEP_FAULT -np 3 ${VOXCD} sweep ${sweep}
                        --results ${WORK}/kill.jsonl
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "a sweep whose rank exited reported success")
endif()
file(STRINGS ${WORK}/kill.jsonl killed)
list(LENGTH killed n_killed)
math(EXPR n_killed "${n_killed} - 1")
if(n_killed GREATER_EQUAL points)
  message(FATAL_ERROR "the killed sweep finished all ${n_killed} points (point 5 should be missing)")
endif()
run(0 resumed ${mpirun} -np 3 ${VOXCD} sweep ${sweep} --results ${WORK}/kill.jsonl --csv ${WORK}/kill.csv)
expect("${resumed}" "${n_killed} of ${points} points from the results file")
check_exactly_once(${WORK}/kill.jsonl)
same_file(${WORK}/whole.csv ${WORK}/kill.csv)

# A writer stopped in the middle of a line: the half line is dropped and its point runs again.
file(STRINGS ${WORK}/whole.jsonl lines)
list(SUBLIST lines 0 5 head)  # the header and 4 points
list(GET lines 5 fifth)
string(SUBSTRING "${fifth}" 0 25 half)
list(JOIN head "\n" text)
file(WRITE ${WORK}/half.jsonl "${text}\n${half}")
run(0 after ${VOXCD} sweep ${sweep} --results ${WORK}/half.jsonl --csv ${WORK}/half.csv)
expect("${after}" "4 of ${points} points from the results file")
check_exactly_once(${WORK}/half.jsonl)
same_file(${WORK}/whole.csv ${WORK}/half.csv)

# Faults: a rank that throws, a rank that hangs past --timeout; both name the rank and the point, neither hangs. The
# timeout leaves a point that does not hang time to finish on a loaded machine under the sanitizers (seconds each).
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_TESTING_SWEEP_FAULT=fail:4
                        ${mpirun} -x VOXCD_TESTING_SWEEP_FAULT -np 2 ${VOXCD} sweep ${sweep}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect("${rc}" "^[1-9]")
expect("${err}" "voxcd: error: rank [01] failed on point 4 \\(lanes 2, depth 0, voxel x1, distance bits 0, accuracy 0.02\\): planted fault")
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_TESTING_SWEEP_FAULT=hang:2
                        ${mpirun} -x VOXCD_TESTING_SWEEP_FAULT -np 2 ${VOXCD} sweep ${sweep} --timeout 30
                        --results ${WORK}/hang.jsonl
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
expect("${rc}" "^[1-9]")
expect("${err}" "voxcd: error: rank [01] (sent no result for|did not finish) point 2 \\(lanes 1, depth 0, voxel x2, distance bits 0, accuracy 0.02\\) within 30 s")
expect("${err}" "hang.jsonl; rerun with it to resume")

# Bad input: a sweep file with a bad key or value, a bad list, another sweep's results file.
file(WRITE ${WORK}/bad.json "{\"lanes\": [1, 3]}")
run(2 bad ${VOXCD} sweep ${SCENES}/small.json --sweep ${WORK}/bad.json)
expect("${bad}" "bad.json with the options: lanes\\[1\\]: 3 is not a power of two from 1 to 64")
file(WRITE ${WORK}/unknown.json "{\"lane\": [1]}")
run(2 bad ${VOXCD} sweep ${SCENES}/small.json --sweep ${WORK}/unknown.json)
expect("${bad}" "unknown.json: lane: unknown key")
file(WRITE ${WORK}/notjson.json "{\"lanes\": [1,")
run(2 bad ${VOXCD} sweep ${SCENES}/small.json --sweep ${WORK}/notjson.json)
expect("${bad}" "notjson.json: not JSON")
run(2 bad ${VOXCD} sweep ${SCENES}/small.json --distance-bits 0,5)
expect("${bad}" "distance_bits\\[1\\]: 5 is not 0 \\(2-bit states\\), 4, 8 or 16")
run(2 bad ${VOXCD} sweep ${SCENES}/small.json --accuracy 0.01,x)
expect("${bad}" "--accuracy: 'x' is not a number")
run(2 bad ${VOXCD} sweep ${SCENES}/small.json --lanes 1 --accuracy 0.05 --results ${WORK}/whole.jsonl)
expect("${bad}" "whole.jsonl holds the results of another sweep")
