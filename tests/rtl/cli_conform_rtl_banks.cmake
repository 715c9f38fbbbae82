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
  expect_conform_cycles(${VOXCD} ${WORK}/${name}.vec "${backends}")
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
list(GET backends -1 backend)
expect_cycle_off_by_one_fails(${VOXCD} ${WORK}/${name}.vec ${WORK} ${backend})
