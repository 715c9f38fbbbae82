# `voxcd conform` with shared voxmap banks (docs/contract.md, "Shared voxmap banks"), as users run it: files generated
# for each configuration in CONFIGS ("|"-separated "LANES l BANKS b") carry BANKS and the banked cycles, and pass
# with --cycles on every backend of BACKENDS (the Verilated banked models among them); the same files run on a
# device with a copy per lane give the same records but are refused with --cycles, and a job's cycles changed by
# one fail.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)
string(REPLACE "|" ";" configs "${CONFIGS}")
string(REPLACE "|" ";" backends "${BACKENDS}")

set(seed 51)
foreach(cfg IN LISTS configs)
  string(REPLACE " " "_" name "${cfg}")
  run(0 out ${VOXCD} conform --generate --seed ${seed} --jobs ${JOBS} --config "${cfg}" -o ${WORK}/${name}.vec)
  file(READ ${WORK}/${name}.vec text)
  string(REGEX MATCH "BANKS ([0-9]+)" banks "${cfg}")
  expect("${text}" "\nconfig [^\n]* ${banks}\n")
  foreach(backend ${backends})
    run(0 out ${VOXCD} conform --backend ${backend} --cycles ${WORK}/${name}.vec)
    expect("${out}" "1 passed, 0 failed")
  endforeach()
  # A copy per lane: the same records, other cycles.
  run(0 out ${VOXCD} conform --backend ref --banks 0 ${WORK}/${name}.vec)
  expect("${out}" "1 passed, 0 failed")
  run(1 out ${VOXCD} conform --backend ref --banks 0 --cycles ${WORK}/${name}.vec)
  expect("${out}" "cycles are for BANKS")
  math(EXPR seed "${seed} + 1")
endforeach()

# The last configuration (the most conflicts): a completion record's cycles one more than the model's fail on rtl.
list(GET configs -1 cfg)
string(REPLACE " " "_" name "${cfg}")
file(READ ${WORK}/${name}.vec text)
string(REGEX MATCH "\ndone ([0-9]+) ([0-9]+) ([0-9]+)\n" first "${text}")
if(NOT first)
  message(FATAL_ERROR "the ${cfg} file has no completion record with cycles")
endif()
math(EXPR more "${CMAKE_MATCH_3} + 1")
string(REPLACE "${first}" "\ndone ${CMAKE_MATCH_1} ${CMAKE_MATCH_2} ${more}\n" bad "${text}")
file(WRITE ${WORK}/bad.vec "${bad}")
list(GET backends -1 backend)
run(1 out ${VOXCD} conform --backend ${backend} --cycles ${WORK}/bad.vec)
expect("${out}" "0 passed, 1 failed")
