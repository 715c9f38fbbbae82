# voxcd size --target chooses the pipeline depth for the clock from the timing table and says why (from the rows of
# the configuration's lanes, or those that stand in for them, saying so), with the latency, the area and the block RAMs; a clock no depth meets is refused naming the fastest depth (exit 3); a timing table
# that cannot be used is refused naming the file, the line and the column; voxcd sweep takes the depth as an axis.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)
set(scene ${SCENES}/small.json)
set(fast --frames 3)

# A clock the iCE40 HX8K's depth 0 meets: depth 0, and why.
run(0 out ${VOXCD} size ${scene} ${fast} --clock 20 --target ice40-hx8k)
expect("${out}" "\ndepth           0 on ice40-hx8k for 20 MHz \\(depth 0: [0-9.]+ MHz >= 20; nextpnr-ice40, median of 3 seeds, host/device/timing\\.tsv \\(built in\\)\\)\n")
expect("${out}" "\nlatency         8 cycles \\(400 ns\\) from a job's acceptance to its first record on the pins, at depth 0\n")
expect("${out}" "\narea            [0-9.e+-]+ mm\\^2 of standard cells at 0\\.18 um at depth 0 for the timing table's configuration \\(PW 24 [^\n]*LANES 4[^\n]*; RAMs not included\\); --cost synthesises this one\n")
expect("${out}" "\nblock RAMs      [0-9]+ SB_RAM40_4K \\(4 kbit\\) on ice40-hx8k \\([0-9]+ x shell bank [0-9]+ x [0-9]+ bit, [0-9]+ x voxmap copy [0-9]+ x 64 bit\\); (the part has|more than the part's) 32\n")
run(0 out ${VOXCD} size ${scene} ${fast} --clock 20 --target xilinx-7 --json)
string(JSON depth GET "${out}" depth_choice depth)
string(JSON target GET "${out}" target)
string(JSON estimate GET "${out}" depth_choice estimate)
string(JSON unit GET "${out}" depth_choice block_rams unit)
string(JSON latency GET "${out}" latency_cycles)
if(NOT depth EQUAL 0 OR NOT target STREQUAL "xilinx-7" OR NOT estimate STREQUAL "ON" OR NOT unit STREQUAL "RAMB36"
   OR NOT latency EQUAL 8)
  message(FATAL_ERROR "depth ${depth}, target ${target}, estimate ${estimate}, unit ${unit}, latency ${latency}:\n${out}")
endif()
# LANES 1 on the ASIC: the LANES 4 rows stand in, and the choice says so.
run(0 out ${VOXCD} size ${scene} ${fast} --clock 20 --target asic-osu018)
expect("${out}" "\ndepth           0 on asic-osu018 for 20 MHz \\(depth 0: [0-9.]+ MHz >= 20; the clocks of LANES 4, none measured at LANES 1; OpenSTA, OSU 0\\.18 um, host/device/timing\\.tsv \\(built in\\)\\)\n")
run(0 out ${VOXCD} size ${scene} ${fast} --clock 20 --target asic-osu018 --json)
string(JSON stand_in GET "${out}" depth_choice stand_in)
expect("${stand_in}" "^the clocks of LANES 4, none measured at LANES 1$")
# Without a target: the default depth's latency, no choice.
run(0 out ${VOXCD} size ${scene} ${fast} --json)
string(JSON type TYPE "${out}" depth_choice)
if(NOT type STREQUAL "NULL")
  message(FATAL_ERROR "a depth choice without --target:\n${out}")
endif()

# A clock no depth meets: exit 3, the fastest depth named.
run(3 out ${VOXCD} size ${scene} ${fast} --clock 100000 --target asic-osu018)
expect("${out}" "cannot be met: clock: no depth meets 100000 MHz on asic-osu018 \\(host/device/timing\\.tsv \\(built in\\)\\): the fastest is depth [0-9]+ at [0-9.]+ MHz \\(OpenSTA, OSU 0\\.18 um; the clocks of LANES 4, none measured at LANES 1\\); 100000 MHz is [0-9.e+]+ times faster")

# A table of one's own: chosen from, and named.
set(header "target\tdepth\tmhz\tsource\tlanes\tarea_mm2\tluts\tffs\tdsps\tbrams\tlut_levels\tconfig\n")
file(WRITE ${WORK}/mine.tsv "${header}asic-osu018\t0\t30\tOpenSTA, my run\t4\t2.5\t-\t-\t-\t8\t-\tPW 24\n")
run(0 out ${VOXCD} size ${scene} ${fast} --clock 25 --target asic-osu018 --timing-table ${WORK}/mine.tsv)
expect("${out}" "depth           0 on asic-osu018 for 25 MHz \\(depth 0: 30 MHz >= 25; the clocks of LANES 4, none measured at LANES 1; OpenSTA, my run, [^\n]*mine\\.tsv\\)")
expect("${out}" "area            2\\.5 mm\\^2 of standard cells")
# Tables that cannot be used, and options that do not go together.
file(WRITE ${WORK}/bad.tsv "${header}asic-osu018\t0\tfast\tOpenSTA\t4\t-\t-\t-\t-\t-\t-\tPW 24\n")
run(2 out ${VOXCD} size ${scene} ${fast} --clock 25 --target asic-osu018 --timing-table ${WORK}/bad.tsv)
expect("${out}" "voxcd: error: [^\n]*bad\\.tsv:2: mhz: 'fast' is not a number >= 0")
file(WRITE ${WORK}/short.tsv "target\tdepth\tmhz\n")
run(2 out ${VOXCD} size ${scene} ${fast} --clock 25 --target asic-osu018 --timing-table ${WORK}/short.tsv)
expect("${out}" "short\\.tsv:1: the header is 'target depth mhz', expected the tab-separated columns")
run(105 out ${VOXCD} size ${scene} ${fast} --timing-table ${WORK}/mine.tsv)
expect("${out}" "--timing-table: needs --target")
run(105 out ${VOXCD} size ${scene} ${fast} --target asic-tsmc7)
expect("${out}" "--target: asic-tsmc7 not in")

# voxcd sweep: depth is an axis with a column of its own; a depth the device does not offer is refused naming it.
run(0 out ${VOXCD} sweep ${scene} --lanes 1 --depth 0 --frames 2 --sample-frames 1 --csv ${WORK}/sweep.csv)
expect("${out}" "1 points \\(1 lanes x 1 depths x 1 voxel scales")
file(STRINGS ${WORK}/sweep.csv rows)
list(GET rows 0 header)
list(GET rows 1 row)
expect("${header}" "^point,lanes,depth,voxel_scale,[^\n]*,latency_cycles,max_cycles,")
expect("${row}" "^0,1,0,1,")
foreach(bad 999 -1)
  run(2 out ${VOXCD} sweep ${scene} --lanes 1 --depth ${bad} --frames 2)
  expect("${out}" "voxcd: error: the sweep options: depth\\[0\\]: ")
endforeach()
