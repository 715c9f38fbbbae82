# Proves a cell's properties with yosys: cmake -DYOSYS=... -DRTL=<rtl dir> -DCHECK=<harness .sv> -DCELL=<name>
#   -DTOP=<harness module> -DWORK=<dir> [-DBREAK_FROM=<text> -DBREAK_TO=<text>] -P run_formal.cmake
# Without BREAK_*: the proof (k-induction from the reset state, every assertion of the cell and the harness) must
# succeed. With them: the cell's source with BREAK_FROM replaced by BREAK_TO (a deliberate bug) must fail to prove,
# which shows the properties can fail.
file(MAKE_DIRECTORY ${WORK})
file(READ ${RTL}/voxcd_${CELL}.sv source)
if(DEFINED BREAK_FROM)
  string(FIND "${source}" "${BREAK_FROM}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "the mutation's text is not in voxcd_${CELL}.sv: '${BREAK_FROM}'")
  endif()
  string(REPLACE "${BREAK_FROM}" "${BREAK_TO}" source "${source}")
endif()
file(WRITE ${WORK}/voxcd_${CELL}.sv "${source}")
set(script "read_verilog -formal -sv ${RTL}/voxcd_assert.svh ${WORK}/voxcd_${CELL}.sv ${CHECK}; \
prep -top ${TOP}; memory; flatten; async2sync; opt_clean; \
sat -tempinduct -prove-asserts -set-init-zero -maxsteps 24 -verify")
execute_process(COMMAND ${YOSYS} -l ${WORK}/yosys.log -q -p "${script}"
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
file(READ ${WORK}/yosys.log log)
string(FIND "${log}" "Induction step proven: SUCCESS!" proven)
if(DEFINED BREAK_FROM)
  if(rc EQUAL 0 OR NOT proven EQUAL -1)
    message(FATAL_ERROR "the broken ${CELL} (${BREAK_TO}) was proven: the properties cannot catch it (${WORK}/yosys.log)")
  endif()
  string(FIND "${log}" "model found for base case: FAIL!" failed)
  if(failed EQUAL -1)
    message(FATAL_ERROR "yosys stopped on the broken ${CELL} without a counterexample (${WORK}/yosys.log)")
  endif()
  message(STATUS "broken ${CELL} (${BREAK_TO}): a reachable state violates an assertion, as it must")
else()
  if(NOT rc EQUAL 0 OR proven EQUAL -1)
    message(FATAL_ERROR "the proof of ${CELL} failed (exit ${rc}); see ${WORK}/yosys.log")
  endif()
  message(STATUS "${CELL}: every assertion proven by induction (yosys sat -tempinduct)")
endif()
