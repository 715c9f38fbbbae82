# Runs a testbench and checks its exit status and output (ctest runs it with cmake -P):
#   -DTB=<executable> -DARGS="+a=1|+b=2" -DRC=<expected exit status> -DEXPECT="<regex>|<regex>..."
# Lists are separated by "|" so that an argument may hold spaces and ';'.
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)
string(REPLACE "|" ";" args "${ARGS}")
run(${RC} out ${TB} ${args})
string(REPLACE "|" ";" patterns "${EXPECT}")
foreach(p IN LISTS patterns)
  expect("${out}" "${p}")
endforeach()
message("${out}")
