# Command-line errors as users meet them: each names the option (or the pair) and what is wrong, with CLI11's exit
# codes for argument errors (105 a bad value, 106 no subcommand, 109 an unknown option) and 2 for an error the
# subcommand raised. docs/robustness.md lists them.
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../cli_helpers.cmake)

run(106 out ${VOXCD})
expect("${out}" "A subcommand is required")
run(109 out ${VOXCD} info --frob ${WORK}/x.vox)
expect("${out}" "not expected: --frob")

run(105 out ${VOXCD} conform)
expect("${out}" "conform needs FILE\\.\\.\\. \\(or --generate\\)")
run(105 out ${VOXCD} conform --generate --seed 1 --jobs 4)
expect("${out}" "--generate needs -o FILE")
run(105 out ${VOXCD} conform --lanes 0 ${WORK}/x.vec)
expect("${out}" "--lanes: Value 0 not in range 1 to 64")
run(105 out ${VOXCD} simulate --lanes 65)
expect("${out}" "--lanes: Value 65 not in range 1 to 64")
run(105 out ${VOXCD} simulate --objects 0)
expect("${out}" "--objects: Value 0 not in range 1 to 1048576")

# A bad --config names the option, then the key or the rule; nothing is written.
run(2 out ${VOXCD} conform --generate --seed 1 --jobs 4 --config "MEMW 48" -o ${WORK}/cfg.vec)
expect("${out}" "voxcd: error: --config: invalid device configuration: MEMW = 48 is not a power of two")
run(2 out ${VOXCD} conform --generate --seed 1 --jobs 4 --config "FOO 1" -o ${WORK}/cfg.vec)
expect("${out}" "voxcd: error: --config: unknown config parameter 'FOO'")
if(EXISTS ${WORK}/cfg.vec)
  message(FATAL_ERROR "a refused --config still wrote ${WORK}/cfg.vec")
endif()

run(105 out ${VOXCD} pair cube cube --pose 1,2)
expect("${out}" "--pose: '1,2' has 2 numbers; give tx,ty,tz or tx,ty,tz,rx,ry,rz")
run(105 out ${VOXCD} pair cube cube --pose 1,x,3)
expect("${out}" "--pose: 'x' in '1,x,3' is not a number")
run(105 out ${VOXCD} pair cube cube --mode SOME)
expect("${out}" "--mode: 'SOME' is not ALL, FIRST or COUNT")
run(105 out ${VOXCD} simulate --mode SOME)
expect("${out}" "--mode: 'SOME' is not ALL, FIRST or COUNT")

# Poses that parse but cannot be tested: the error names the pair, its objects and the value.
run(2 out ${VOXCD} pair cube cube --voxel 0.25 --pose nan,0,0)
expect("${out}" "voxcd: error: pair 0 \\(cube, cube\\): pose of B is not finite \\(NaN or infinite rotation or translation\\)")
run(2 out ${VOXCD} pair cube cube --voxel 0.25 --pose 0,inf,0)
expect("${out}" "voxcd: error: pair 0 \\(cube, cube\\): pose of B is not finite")
run(2 out ${VOXCD} pair cube cube --voxel 0.25 --pose 1e9,0,0)
expect("${out}" "voxcd: error: pair 0 \\(cube, cube\\): T0 = -3999999999\\.[0-9]+ does not fit signed 48-bit with 24 fraction bits")
if(out MATCHES "contacts")
  message(FATAL_ERROR "a refused pose still printed a result:\n${out}")
endif()

# Files that cannot be written whole: generated vectors on a disk that fills up (a file-size limit stands in for
# it), a --trace path that cannot be opened. Nothing is left behind, no temporary and no partial output.
run(2 out sh -c "trap '' XFSZ && ulimit -f 4 && exec '${VOXCD}' conform --generate --seed 1 --jobs 200 -o '${WORK}/full.vec'")
expect("${out}" "voxcd: error: write error on ${WORK}/full\\.vec\\.tmp \\(nothing written to ${WORK}/full\\.vec\\)")
if(EXISTS ${WORK}/full.vec OR EXISTS ${WORK}/full.vec.tmp)
  message(FATAL_ERROR "a failed write left ${WORK}/full.vec or its temporary behind")
endif()
file(MAKE_DIRECTORY ${WORK}/vec_in_the_way)
run(2 out ${VOXCD} conform --generate --seed 1 --jobs 4 -o ${WORK}/vec_in_the_way)
expect("${out}" "voxcd: error: cannot rename ${WORK}/vec_in_the_way\\.tmp into place as ${WORK}/vec_in_the_way")
if(EXISTS ${WORK}/vec_in_the_way.tmp OR NOT IS_DIRECTORY ${WORK}/vec_in_the_way)
  message(FATAL_ERROR "a failed rename left its temporary behind or touched the directory")
endif()
if(HAVE_RTL)
  run(0 out ${VOXCD} conform --generate --seed 1 --jobs 4 -o ${WORK}/four.vec)
  run(1 out ${VOXCD} conform --backend rtl --trace ${WORK}/no/such/dir/t.fst ${WORK}/four.vec)
  expect("${out}" "FAIL ${WORK}/four\\.vec: rtl: cannot open trace file ${WORK}/no/such/dir/t\\.fst")
endif()
