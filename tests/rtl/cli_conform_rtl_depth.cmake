# `voxcd conform` at every pipeline depth (DeviceConfig::depth, docs/conformance.md "DEPTH"), as users run it: files
# generated for each configuration in CONFIGS ("|"-separated "LANES l DEPTH d", with BANKS or SB where given) carry
# DEPTH and the cycles of that depth, and pass with --cycles on every backend of BACKENDS (the Verilated depth models
# among them); the same files run at depth 0 give the same records but are refused with --cycles; a file without
# DEPTH (depth 0, as every file before it) runs at --depth D with the same records; a job's cycles changed by one
# fail, and a depth past the deepest is refused.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)
string(REPLACE "|" ";" configs "${CONFIGS}")
string(REPLACE "|" ";" backends "${BACKENDS}")

set(seed 71)
foreach(cfg IN LISTS configs)
  string(REPLACE " " "_" name "${cfg}")
  run(0 out ${VOXCD} conform --generate --seed ${seed} --jobs ${JOBS} --config "${cfg}" -o ${WORK}/${name}.vec)
  file(READ ${WORK}/${name}.vec text)
  string(REGEX MATCH "DEPTH ([0-9]+)" depth "${cfg}")
  set(d ${CMAKE_MATCH_1})
  expect("${text}" "\nconfig [^\n]* ${depth}\n")
  expect_conform_cycles(${VOXCD} ${WORK}/${name}.vec "${backends}")
  # Depth 0: the same records, other cycles.
  run(0 out ${VOXCD} conform --backend ref --depth 0 ${WORK}/${name}.vec)
  expect("${out}" "1 passed, 0 failed")
  run(1 out ${VOXCD} conform --backend ref --depth 0 --cycles ${WORK}/${name}.vec)
  expect("${out}" "cycles are for DEPTH ${d}")
  math(EXPR seed "${seed} + 1")
endforeach()

# A file without DEPTH keeps its meaning (depth 0) and runs at another depth with the same records.
list(GET configs 0 cfg)
string(REGEX REPLACE " *DEPTH [0-9]+" "" plain "${cfg}")
string(REGEX MATCH "DEPTH ([0-9]+)" depth "${cfg}")
set(d ${CMAKE_MATCH_1})
run(0 out ${VOXCD} conform --generate --seed 5 --jobs ${JOBS} --config "${plain}" -o ${WORK}/plain.vec)
file(READ ${WORK}/plain.vec text)
if(text MATCHES "DEPTH")
  message(FATAL_ERROR "a depth-0 file names DEPTH:\n${text}")
endif()
list(GET backends -1 backend)
run(0 out ${VOXCD} conform --backend ${backend} --cycles ${WORK}/plain.vec)
expect("${out}" "1 passed, 0 failed")
run(0 out ${VOXCD} conform --backend ${backend} --depth ${d} ${WORK}/plain.vec)
expect("${out}" "1 passed, 0 failed")
run(1 out ${VOXCD} conform --backend ${backend} --depth ${d} --cycles ${WORK}/plain.vec)
expect("${out}" "cycles are for DEPTH 0, not --depth ${d}")

# The last configuration: a completion record's cycles one more than the model's fail.
list(GET configs -1 cfg)
string(REPLACE " " "_" name "${cfg}")
expect_cycle_off_by_one_fails(${VOXCD} ${WORK}/${name}.vec ${WORK} ${backend})

# Depths past the deepest: on the command line and in a file.
run(105 out ${VOXCD} conform --backend ref --depth 6 ${WORK}/plain.vec)
expect("${out}" "--depth")
file(READ ${WORK}/plain.vec text)
string(REGEX REPLACE "\nconfig ([^\n]*)\n" "\nconfig \\1 DEPTH 6\n" deep "${text}")
file(WRITE ${WORK}/deep.vec "${deep}")
run(1 out ${VOXCD} conform --backend ref ${WORK}/deep.vec)
expect("${out}" "DEPTH = 6 is outside 0..5")
