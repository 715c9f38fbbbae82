# `voxcd conform` on sparse devices (docs/contract.md, "Sparse voxmaps and shells"), as users run it: version-3 files
# generated for each configuration in CONFIGS ("|"-separated, each with BL) carry BL, sparse maps and shells among
# dense jobs, and the cycles of that device, and pass with --cycles on every backend of BACKENDS (the Verilated sparse
# models among them); a job's cycles changed by one fail.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)
string(REPLACE "|" ";" configs "${CONFIGS}")
string(REPLACE "|" ";" backends "${BACKENDS}")

set(seed 81)
foreach(cfg IN LISTS configs)
  string(REPLACE " " "_" name "${cfg}")
  run(0 out ${VOXCD} conform --generate --seed ${seed} --jobs ${JOBS} --config "${cfg}" -o ${WORK}/${name}.vec)
  file(READ ${WORK}/${name}.vec text)
  expect("${text}" "^[^\n]*\nvoxcd-vectors 3\nconfig [^\n]* BL [2-4]( TX 1)?\n")
  expect("${text}" "\njob [^\n]* [123] [0-9]+ [0-9]+\n")  # a sparse job: its sparse, brick_base, brick_units
  expect_conform_cycles(${VOXCD} ${WORK}/${name}.vec "${backends}")
  math(EXPR seed "${seed} + 1")
endforeach()

list(GET configs -1 cfg)
string(REPLACE " " "_" name "${cfg}")
list(GET backends -1 backend)
expect_cycle_off_by_one_fails(${VOXCD} ${WORK}/${name}.vec ${WORK} ${backend})
