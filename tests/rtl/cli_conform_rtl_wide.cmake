# `voxcd conform` on wide devices (docs/hardware.md, "Wide devices"), as users run it: files generated for each
# configuration in CONFIGS ("|"-separated, each of 16 lanes or more) carry its LANES and that device's cycles, and pass
# with --cycles on every backend of BACKENDS (the Verilated wide models among them); a job's cycles changed by one
# fail.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)
string(REPLACE "|" ";" configs "${CONFIGS}")
string(REPLACE "|" ";" backends "${BACKENDS}")

set(seed 91)
foreach(cfg IN LISTS configs)
  string(REPLACE " " "_" name "${cfg}")
  run(0 out ${VOXCD} conform --generate --seed ${seed} --jobs ${JOBS} --config "${cfg}" -o ${WORK}/${name}.vec)
  file(READ ${WORK}/${name}.vec text)
  string(REGEX MATCH "LANES ([0-9]+)" lanes "${cfg}")
  expect("${text}" "\nconfig [^\n]* ${lanes}[ \n]")
  expect_conform_cycles(${VOXCD} ${WORK}/${name}.vec "${backends}")
  math(EXPR seed "${seed} + 1")
endforeach()

list(GET configs -1 cfg)
string(REPLACE " " "_" name "${cfg}")
list(GET backends -1 backend)
expect_cycle_off_by_one_fails(${VOXCD} ${WORK}/${name}.vec ${WORK} ${backend})
