# voxcd conform on sparse devices (vector format 3, docs/conformance.md), as users run it: generated files (BL 3:
# 2-bit, distance with shared banks, a deeper pipeline) are version 3 with BL on their config line and the sparse
# fields on every job line, and pass on every backend named in BACKENDS with their cycles; a cycle count one off
# fails; a sparse job in a file whose config has no BL is refused naming it; selftest runs sparse devices on ref and
# cpu, and on the Verilated backends of SELFTEST_RTL ("|"-separated: those with models of both its sparse devices).
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)

foreach(cfg "BL 3" "BL 3 SB 8 WB 8 BANKS 2" "BL 3 LANES 2 DEPTH 3")
  string(REPLACE " " "_" name "${cfg}")
  run(0 out ${VOXCD} conform --generate --seed 17 --jobs 250 --config "${cfg}" -o ${WORK}/${name}.vec)
  expect("${out}" "wrote .*: 250 jobs, [0-9]+ shell words, [0-9]+ map words, [0-9]+ lookups, seed 17")
  expect_conform_cycles(${VOXCD} ${WORK}/${name}.vec "${BACKENDS}")
endforeach()

file(READ ${WORK}/BL_3.vec text)
expect("${text}" "^# generated[^\n]*\nvoxcd-vectors 3\nconfig [^\n]* BL 3\n")
# Job lines end THRESHOLD SPARSE BRICK_BASE BRICK_UNITS: sparse maps (1), sparse shells (2) and both (3) occur.
foreach(sparse 1 2 3)
  expect("${text}" "\njob [^\n]* ${sparse} [0-9]+ [0-9]+\n")
endforeach()
foreach(backend ${BACKENDS})
  expect_cycle_off_by_one_fails(${VOXCD} ${WORK}/BL_3_SB_8_WB_8_BANKS_2.vec ${WORK} ${backend})
endforeach()

# The same file with BL taken off its config line: its sparse jobs are refused.
string(REPLACE " BL 3\n" "\n" dense "${text}")
file(WRITE ${WORK}/no_bl.vec "${dense}")
run(1 out ${VOXCD} conform ${WORK}/no_bl.vec --backend ref)
expect("${out}" "FAIL ${WORK}/no_bl.vec:[0-9]+: .*a sparse (map|shell) on a device without sparse maps and shells")

run(0 out ${VOXCD} selftest --jobs 60)
string(REPLACE "|" ";" selftest_rtl "${SELFTEST_RTL}")
foreach(backend ref cpu ${selftest_rtl})
  expect("${out}" "\n${backend} +BL 3 +60 +[0-9]+ +[0-9]+ +[0-9.]+ +ok\n")
  expect("${out}" "\n${backend} +BL 3 SB 8 +60 +[0-9]+ +[0-9]+ +[0-9.]+ +ok\n")
endforeach()
expect("${out}" "\n[0-9]+ passed, 0 failed")
