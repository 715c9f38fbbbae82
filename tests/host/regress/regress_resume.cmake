# A campaign stopped part way resumes from its results file and ends with every shard in the file exactly once:
# stopped by --stop-after, by a rank that exits mid-campaign (Open MPI ends the job), or cut in the middle of a
# line. Faults end the run with an error naming the rank and the shard; bad campaign and results files are refused.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)
set(campaign --seeds 1-4 --lanes 1,3 --backends ref,cpu --jobs-per-shard 30)
set(shards 16)
set(mpirun ${MPIEXEC} --oversubscribe)

# The shard indices of a results file's lines, and a check that they are 0..shards-1, each once.
function(check_exactly_once file)
  file(STRINGS ${file} lines)
  list(POP_FRONT lines header)
  if(NOT header MATCHES "voxcd_regress_results")
    message(FATAL_ERROR "${file} has no header: ${header}")
  endif()
  set(seen "")
  foreach(line IN LISTS lines)
    string(JSON s GET "${line}" shard)
    list(APPEND seen ${s})
  endforeach()
  list(LENGTH seen n)
  list(REMOVE_DUPLICATES seen)
  list(LENGTH seen unique)
  list(SORT seen COMPARE NATURAL)
  math(EXPR last "${shards} - 1")
  set(all "")
  foreach(i RANGE ${last})
    list(APPEND all ${i})
  endforeach()
  if(NOT n EQUAL shards OR NOT seen STREQUAL all)
    message(FATAL_ERROR "${file}: ${n} shard lines (${unique} distinct: ${seen}); expected 0..${last} once each")
  endif()
endfunction()

# The reference: one uninterrupted run.
run(0 whole ${VOXCD} regress ${campaign} --results ${WORK}/whole.jsonl)
string(REGEX MATCH "jobs: [0-9]+  lookups: [0-9]+  records: [0-9]+" counts "${whole}")
expect("${whole}" "shards: ${shards} of ${shards} \\(0 from the results file")
check_exactly_once(${WORK}/whole.jsonl)

# --stop-after: 5 shards now (exit code 3: incomplete), then the rest on 2 ranks.
run(3 part ${VOXCD} regress ${campaign} --results ${WORK}/stop.jsonl --stop-after 5)
expect("${part}" "shards: 5 of ${shards} .*incomplete: --stop-after 5")
run(0 rest ${mpirun} -np 2 ${VOXCD} regress ${campaign} --results ${WORK}/stop.jsonl)
expect("${rest}" "shards: ${shards} of ${shards} \\(5 from the results file, 11 run now on 2 ranks")
expect("${rest}" "${counts}")
check_exactly_once(${WORK}/stop.jsonl)

# A rank that exits on shard 9 ends the job (Open MPI); what was finished is in the file, and a rerun finishes.
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_TESTING_FAULT=exit:9
                        ${mpirun} -x VOXCD_TESTING_FAULT -np 3 ${VOXCD} regress ${campaign} --results ${WORK}/kill.jsonl
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
if(rc EQUAL 0)
  message(FATAL_ERROR "a campaign whose rank exited reported success")
endif()
file(STRINGS ${WORK}/kill.jsonl killed)
list(LENGTH killed n_killed)
math(EXPR n_killed "${n_killed} - 1")
if(n_killed GREATER_EQUAL shards)
  message(FATAL_ERROR "the killed campaign finished all ${n_killed} shards (shard 9 should be missing)")
endif()
run(0 resumed ${mpirun} -np 3 ${VOXCD} regress ${campaign} --results ${WORK}/kill.jsonl)
expect("${resumed}" "shards: ${shards} of ${shards} \\(${n_killed} from the results file")
expect("${resumed}" "${counts}")
check_exactly_once(${WORK}/kill.jsonl)

# A writer stopped in the middle of a line: the half line is dropped and its shard runs again.
file(STRINGS ${WORK}/whole.jsonl lines)
list(SUBLIST lines 0 8 head)           # the header and 7 shards
list(GET lines 8 eighth)
string(SUBSTRING "${eighth}" 0 25 half)
list(JOIN head "\n" text)
file(WRITE ${WORK}/half.jsonl "${text}\n${half}")
run(0 after ${VOXCD} regress ${campaign} --results ${WORK}/half.jsonl)
expect("${after}" "\\(7 from the results file, 9 run now")
expect("${after}" "${counts}")
check_exactly_once(${WORK}/half.jsonl)

# Faults: a rank that throws, a rank that hangs past --timeout. Both name the rank and the shard, neither hangs.
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_TESTING_FAULT=fail:6
                        ${mpirun} -x VOXCD_TESTING_FAULT -np 2 ${VOXCD} regress ${campaign}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
expect("${rc}" "^[1-9]")
expect("${err}"
       "voxcd: error: rank [01] failed on shard 6 \\(seed 2, config default, lanes 3, backend ref\\): planted fault")
string(TIMESTAMP t0 "%s")
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_TESTING_FAULT=hang:3
                        ${mpirun} -x VOXCD_TESTING_FAULT -np 2 ${VOXCD} regress ${campaign} --timeout 2
                        --results ${WORK}/hang.jsonl
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
string(TIMESTAMP t1 "%s")
math(EXPR took "${t1} - ${t0}")
expect("${rc}" "^[1-9]")
string(CONCAT timed_out "voxcd: error: rank [01] (sent no result for|did not finish) shard 3 "
                        "\\(seed 1, config default, lanes 3, backend cpu\\) within 2 s")
expect("${err}" "${timed_out}")
file(STRINGS ${WORK}/hang.jsonl hung)
list(LENGTH hung n_hung)
if(n_hung LESS 2 OR took GREATER 60)
  message(FATAL_ERROR "the hung campaign kept ${n_hung} lines and took ${took} s")
endif()
# The same on one rank without mpirun (rank 0's own shard).
execute_process(COMMAND ${CMAKE_COMMAND} -E env VOXCD_TESTING_FAULT=hang:0 ${VOXCD} regress ${campaign} --timeout 1
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
expect("${rc}" "^2$")
expect("${err}" "rank 0 did not finish shard 0 \\(seed 1, config default, lanes 1, backend ref\\) within 1 s")

# Refused: a results file of another campaign, a file that is not one, bad campaign files and lists.
run(2 out ${VOXCD} regress --seeds 1-5 --lanes 1,3 --backends ref,cpu --jobs-per-shard 30 --results ${WORK}/whole.jsonl)
expect("${out}"
       "whole.jsonl holds the results of another campaign \\(.*\"seeds\":\"1-4\".*this one is .*\"seeds\":\"1-5\"")
file(WRITE ${WORK}/notes.txt "my notes\n")
run(2 out ${VOXCD} regress ${campaign} --results ${WORK}/notes.txt)
expect("${out}" "notes.txt is not a voxcd regress results file")
file(STRINGS ${WORK}/notes.txt kept)
expect("${kept}" "^my notes$")
file(WRITE ${WORK}/bad_key.json "{\"seeds\": \"1-2\", \"lane\": [1]}")
run(2 out ${MPIEXEC} -np 2 ${VOXCD} regress --campaign ${WORK}/bad_key.json)
expect("${out}" "bad_key.json: unknown key \"lane\"")
file(WRITE ${WORK}/bad_json.json "{\"seeds\": \"1-2\",\n \"lanes\": [1,\n")
run(2 out ${VOXCD} regress --campaign ${WORK}/bad_json.json)
expect("${out}" "bad_json.json: not JSON: .*line 3")
file(WRITE ${WORK}/bad_seeds.json "{\"seeds\": \"9-2\"}")
run(2 out ${VOXCD} regress --campaign ${WORK}/bad_seeds.json)
expect("${out}" "bad_seeds.json: key \"seeds\": the range '9-2' runs backwards")
file(WRITE ${WORK}/bad_config.json "{\"seeds\": [1], \"configs\": [\"PW 99\"]}")
run(2 out ${VOXCD} regress --campaign ${WORK}/bad_config.json)
expect("${out}" "bad_config.json: key \"configs\"")
file(WRITE ${WORK}/bad_backend.json "{\"seeds\": [1], \"backends\": [\"gpu\"]}")
run(2 out ${VOXCD} regress --campaign ${WORK}/bad_backend.json)
expect("${out}" "bad_backend.json: key \"backends\": backend 'gpu' is not a backend .the backends: ref, cpu, rtl, sysc-rtl, sysc-tlm.")
run(2 out ${VOXCD} regress --seeds 1,2,1)
expect("${out}" "--seeds: seed 1 is given twice")
run(2 out ${VOXCD} regress --seeds 1 --lanes 0)
expect("${out}" "key \"lanes\": 0 is not a lane count 1..64")
run(105 out ${VOXCD} regress --campaign ${WORK}/bad_key.json --seeds 3)
expect("${out}" "--seeds cannot be given with --campaign")
