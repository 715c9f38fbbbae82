# voxcd simulate under mpirun on 2 and 3 ranks prints the summary of one process: the same broadphase pairs, tested
# pairs, touching pairs, responses, wall bounces, lookups, hits, contacts and state hash. Scenes: the default, fast
# bodies that cross the slabs every frame, a dense scene of many contacts, distance voxmaps with continuous
# collision, another broadphase, and a scene file of three types.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)
get_filename_component(scenes ${CMAKE_CURRENT_LIST_DIR}/../../scenes ABSOLUTE)

function(summary json out_var)
  set(s "")
  foreach(key broadphase_pairs pairs_tested touching_pairs responses wall_bounces lookups hits contacts state_hash)
    string(JSON v GET "${json}" ${key})
    string(APPEND s "${key}=${v}\n")
  endforeach()
  set(${out_var} "${s}" PARENT_SCOPE)
endfunction()

# One case a list item, its arguments separated by '|'.
set(cases
  "--objects|256|--frames|60"
  "--objects|128|--speed|1.5|--frames|60"
  "--objects|300|--density|0.12|--speed|0.5|--frames|40"
  "--objects|64|--distance-bits|8|--ccd|--speed|0.8|--frames|30"
  "--objects|200|--broadphase|sap|--frames|40"
  "${scenes}/mixed.json|--frames|30")
foreach(args IN LISTS cases)
  string(REPLACE "|" ";" argv "${args}")
  run(0 one ${VOXCD} simulate ${argv} --json --threads 1)
  summary("${one}" want)
  string(JSON contacts GET "${one}" contacts)
  string(JSON responses GET "${one}" responses)
  if(contacts EQUAL 0 AND responses EQUAL 0)
    message(FATAL_ERROR "simulate ${args}: no contacts and no responses: the case tests nothing")
  endif()
  foreach(np 2 3)
    run(0 many ${MPIEXEC} --oversubscribe -np ${np} ${VOXCD} simulate ${argv} --json --threads 1)
    # Rank 0 alone prints: one summary.
    string(REGEX MATCHALL "\"state_hash\"" hashes "${many}")
    list(LENGTH hashes printed)
    if(NOT printed EQUAL 1)
      message(FATAL_ERROR "simulate ${args} on ${np} ranks printed ${printed} summaries:\n${many}")
    endif()
    summary("${many}" got)
    string(JSON ranks GET "${many}" ranks)
    if(NOT ranks EQUAL np OR NOT got STREQUAL want)
      message(FATAL_ERROR "simulate ${args}: ${np} ranks (${ranks} reported) differ from one process\n"
                          "--- one process\n${want}--- ${np} ranks\n${got}")
    endif()
  endforeach()
  message(STATUS "simulate ${args}: 1, 2 and 3 ranks agree (contacts ${contacts}, responses ${responses})")
endforeach()
