# Coverage of an implementation by voxcd's vectors: the DPI testbench (docs/examples/dpi) around another device,
# Verilated with coverage, runs random jobs under back-pressure and writes the design's counts; `voxcd regress
# --coverage DIR` merges them and reports line, branch and functional coverage by file, the other implementation's
# file among them.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${TB} +seed=9 +jobs=500 +stall=30 +coverage=${WORK}/dut.dat
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "tb_voxcd_dpi: PASS")
  message(FATAL_ERROR "the testbench failed (${rc}):\n${out}${err}")
endif()
if(NOT EXISTS ${WORK}/dut.dat)
  message(FATAL_ERROR "+coverage=FILE wrote no ${WORK}/dut.dat")
endif()
execute_process(COMMAND ${VOXCD} regress --coverage ${WORK} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "voxcd regress --coverage exited with ${rc}")
endif()
foreach(want "1 coverage data files merged" "line +[0-9.]+%" "voxcd_device_regslice.sv +[0-9.]+" "functional +[0-9.]+%")
  if(NOT out MATCHES "${want}")
    message(FATAL_ERROR "the report has no '${want}'")
  endif()
endforeach()
