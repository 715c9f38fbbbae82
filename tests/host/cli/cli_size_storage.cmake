# voxcd size chooses dense or sparse storage: a scene of large objects takes a sparse device (BL 3) whose
# configuration voxcd simulate runs with the types stored sparse, with the largest frame size measured; --storage
# dense fixes it; a storage that is not one is refused naming the option or the scene file's key.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)
set(scene ${SCENES}/large.json)

run(0 out ${VOXCD} size ${scene})
expect("${out}" "\nconfiguration   PW 24 [^\n]* BL 3\n")
expect("${out}" "\nstorage         sparse \\(BL 3\\), the types stored sparse \\(voxcd simulate --storage sparse\\): the smaller device memory: [0-9]+ bytes of device memory against [0-9]+ stored dense\n")
expect("${out}" "\n  dense         PW [^\n]*: LANES [0-9]+, largest frame [0-9]+ cycles; shell [0-9]+ words in 2\\^[0-9]+ x [0-9]+ bit, voxmap [0-9]+ words in 2\\^[0-9]+ x 64 bit x 1 copy; ")
expect("${out}" "\n  type torus: dense voxmap [0-9]+ words, shell [0-9]+; sparse table [0-9]+ \\+ bricks [0-9]+ words, shell [0-9]+\n")
expect("${out}" "\n  block RAMs    estimate: counted from the memories' shapes by host/sizing/block_rams\\.cpp, not synthesised")
expect("${out}" "\n  sparse split  table memory [0-9]+ x 64 bit x 1 \\([^)]*\\): [0-9.]+ RAMB36, [0-9.]+ EBR; brick memory ")

run(0 out ${VOXCD} size ${scene} --json)
string(JSON chosen GET "${out}" storage chosen)
string(JSON bl GET "${out}" config BL)
string(JSON config GET "${out}" config_text)
string(JSON max GET "${out}" cycles_per_frame max)
string(JSON frames GET "${out}" frames)
string(JSON sparse_bytes GET "${out}" storage sparse memory_bytes)
string(JSON dense_bytes GET "${out}" storage dense memory_bytes)
string(JSON fixed TYPE "${out}" storage fixed_by)
if(NOT chosen STREQUAL "sparse" OR NOT bl EQUAL 3 OR NOT sparse_bytes LESS dense_bytes OR NOT fixed STREQUAL "NULL"
   OR max EQUAL 0)
  message(FATAL_ERROR "chosen ${chosen}, BL ${bl}, ${sparse_bytes} against ${dense_bytes} bytes, fixed ${fixed}, "
                      "largest frame ${max}:\n${out}")
endif()

# The derived configuration runs the scene with the types stored sparse, and its largest frame is the one measured.
run(0 sim ${VOXCD} simulate ${scene} --storage sparse --config "${config}" --frames ${frames} --json)
string(JSON sim_max GET "${sim}" device_cycles_max_frame)
if(NOT sim_max EQUAL max)
  message(FATAL_ERROR "voxcd simulate's largest frame ${sim_max} cycles, voxcd size measured ${max}:\n${sim}")
endif()

# --storage dense fixes the storage; the sparse layout is still reported.
run(0 out ${VOXCD} size ${scene} --storage dense --json)
string(JSON chosen GET "${out}" storage chosen)
string(JSON fixed GET "${out}" storage fixed_by)
string(JSON bl GET "${out}" config BL)
string(JSON met GET "${out}" storage sparse met)
if(NOT chosen STREQUAL "dense" OR NOT fixed STREQUAL "--storage" OR NOT bl EQUAL 0 OR NOT met)
  message(FATAL_ERROR "chosen ${chosen}, fixed by ${fixed}, BL ${bl}, sparse met ${met}:\n${out}")
endif()

# Storages that are not one.
run(105 out ${VOXCD} size ${scene} --storage thin)
expect("${out}" "--storage: thin not in \\{auto,dense,sparse\\}")
file(READ ${scene} text)
string(REPLACE "\"frames\": 50" "\"frames\": 50, \"storage\": \"thin\"" text "${text}")
file(WRITE ${WORK}/thin.json "${text}")
run(2 out ${VOXCD} size ${WORK}/thin.json)
expect("${out}" "voxcd: error: [^\n]*thin\\.json: storage: 'thin' is not one of auto, dense, sparse")
