# Checks the device's netlist for a combinational path from an output stream's ready to anything but the output
# slice: cmake -DYOSYS=... -DRTL=<rtl dir> -DWORK=<dir> [-DPARAMS="-set NAME VALUE ..."] [-DBREAK_FROM=<text>
# -DBREAK_TO=<text>] -P ready_cone.cmake
# yosys elaborates voxcd_device (LANES 2, small memories; every source of rtl/voxcd.f but the lint waivers),
# flattens it and takes the fan-out cone of hit_ready_i and done_ready_i, stopping at flip-flops and memories.
# No wire of that cone may feed a flip-flop or memory outside the output slice (u_out_slice): the consumer's
# ready reaches no slot register, lane, RAM enable or counter. With BREAK_*, the
# device's source is changed first (a deliberate path from ready into the pipeline) and the check must fail.
file(MAKE_DIRECTORY ${WORK})
file(STRINGS ${RTL}/voxcd.f list REGEX "^[^/ \t]")
set(files "")
foreach(f ${list})
  if(NOT f MATCHES "\\.vlt$")
    file(READ ${RTL}/${f} text)
    if(f STREQUAL "voxcd_device.sv" AND DEFINED BREAK_FROM)
      string(FIND "${text}" "${BREAK_FROM}" at)
      if(at EQUAL -1)
        message(FATAL_ERROR "the mutation's text is not in voxcd_device.sv: '${BREAK_FROM}'")
      endif()
      string(REPLACE "${BREAK_FROM}" "${BREAK_TO}" text "${text}")
    endif()
    file(WRITE ${WORK}/${f} "${text}")
    list(APPEND files ${f})
  endif()
endforeach()
list(JOIN files " " files)
set(regs "$dff,$adff,$dffe,$adffe,$sdff,$sdffe,$sdffce,$aldff,$mem_v2,$mem")
set(script "read_verilog -sv ${files}; chparam -set LANES 2 -set SAW 6 -set MAW 6 ${PARAMS} voxcd_device; \
prep -flatten -top voxcd_device; \
select -set cone w:hit_ready_i w:done_ready_i %u %co*:-${regs}; \
tee -o cone.txt select -list @cone; \
select -set regs t:$*dff* t:$mem* %u c:*u_out_slice.* %d; \
tee -o inputs.txt select -list @regs %ci1 @regs %d; \
select -assert-none @cone @regs %ci1 @regs %d %i")
execute_process(COMMAND ${YOSYS} -q -l yosys.log -p "${script}" WORKING_DIRECTORY ${WORK}
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
file(STRINGS ${WORK}/cone.txt cone)
list(LENGTH cone n)
if(DEFINED BREAK_FROM)
  if(rc EQUAL 0)
    message(FATAL_ERROR "the broken device (${BREAK_TO}) passed: the check cannot see a path from ready")
  endif()
  file(READ ${WORK}/yosys.log log)
  string(FIND "${log}" "Assertion failed: selection is not empty" failed)
  if(failed EQUAL -1)
    message(FATAL_ERROR "yosys stopped on the broken device without the cone check failing (${WORK}/yosys.log)")
  endif()
  message(STATUS "broken device (${BREAK_TO}): ready reaches the pipeline, as the check says")
else()
  file(STRINGS ${WORK}/inputs.txt inputs)
  list(LENGTH inputs m)
  # The slot registers and the lanes' registers must be among the checked ones (their D inputs hold the enables).
  file(READ ${WORK}/inputs.txt text)
  string(FIND "${text}" "g_slot[0].meta_q" has_slots)
  string(FIND "${text}" "u_lane." has_lanes)
  if(NOT rc EQUAL 0 OR n LESS 3 OR has_slots EQUAL -1 OR has_lanes EQUAL -1)
    message(FATAL_ERROR "the consumer's ready reaches a register outside the output slice, or the netlist is not "
                        "what the check expects (exit ${rc}, a cone of ${n}, ${m} register inputs); see "
                        "${WORK}/yosys.log and ${WORK}/cone.txt")
  endif()
  message(STATUS "the consumer's ready reaches ${n} objects, none of the ${m} inputs of registers outside the "
                 "output slice")
endif()
