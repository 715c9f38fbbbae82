# The one way a Verilated model of the device is declared (the top-level CMakeLists.txt includes this file for rtl/,
# sysc/, bench/ and tests/).
# A model is a configuration: "NAME VALUE" pairs as DeviceConfig::to_string() writes them (the AXI top adds its own
# AxilDw, JobDw, RecDw), every parameter not named at its default. To add a model, add its pairs to the list of its
# library (docs/build.md, "Options"); nothing else changes.

# Verilator's options for every model: its own optimisation, X values resolved the fast way (the device resets
# every register it reads; the assertions check it).
set(VOXCD_VERILATOR_OPTIONS -O3 --x-assign fast --x-initial fast)

# voxcd_model_params(PAIRS OUT): the pairs as Verilator -G arguments (a list), where the configuration's DEPTH is the
# RTL's parameter Depth. A malformed entry is an error that names it.
function(voxcd_model_params pairs out)
  string(STRIP "${pairs}" pairs)
  if(NOT pairs MATCHES "^([A-Za-z][A-Za-z0-9]* -?[0-9]+( +|$))+$")
    message(FATAL_ERROR "model configuration '${pairs}': expected \"NAME VALUE\" pairs such as \"LANES 4 SB 8\"")
  endif()
  string(REGEX MATCHALL "[A-Za-z][A-Za-z0-9]* -?[0-9]+" kv "${pairs}")
  set(gargs "")
  foreach(p ${kv})
    string(REGEX REPLACE "^DEPTH " "Depth " p "${p}")
    string(REGEX REPLACE " +" "=" p "${p}")
    list(APPEND gargs "-G${p}")
  endforeach()
  set(${out} "${gargs}" PARENT_SCOPE)
endfunction()

# voxcd_model_prefix(STEM PAIRS OUT): the model's name, from its configuration, so that adding a model renames no
# other (and their compiled objects stay in ccache): "LANES 4" -> <STEM>_lanes4, "SB 8 WB 8 LANES 1" ->
# <STEM>_sb8_wb8_lanes1.
function(voxcd_model_prefix stem pairs out)
  string(STRIP "${pairs}" name)
  string(TOLOWER "${name}" name)
  string(REGEX REPLACE "([a-z0-9]+) +(-?[0-9]+)" "\\1\\2" name "${name}")
  string(REGEX REPLACE " +" "_" name "${name}")
  string(REPLACE "-" "m" name "${name}")
  set(${out} "${stem}_${name}" PARENT_SCOPE)
endfunction()

# voxcd_model(LIBRARY PREFIX [PARAMS pairs] [TOP module] [SOURCES files...] [SYSTEMC] [TRACE_FST] [NOASSERT]
#             [DIRECTORY dir] [ARGS verilator-args...])
# Verilates one model into LIBRARY (made by voxcd_model_library, which compiles Verilator's runtime once for all its
# models), in DIRECTORY (default <binary dir>/<PREFIX>), its headers on LIBRARY's public include path. TOP defaults to
# voxcd_device, SOURCES to rtl/voxcd.f's files; assertions are compiled in unless NOASSERT.
# Verilator runs at build time only, never when CMake configures: the model's code is compiled as two units of known
# names (rtl/model_units.cmake), its every-cycle code optimised as the build type says, the rest at -O1.
function(voxcd_model library prefix)
  cmake_parse_arguments(M "SYSTEMC;TRACE_FST;NOASSERT" "TOP;PARAMS;DIRECTORY" "SOURCES;ARGS" ${ARGN})
  if(M_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "voxcd_model(${prefix}): unknown arguments ${M_UNPARSED_ARGUMENTS}")
  endif()
  if(NOT M_TOP)
    set(M_TOP voxcd_device)
  endif()
  if(NOT M_SOURCES)
    set(M_SOURCES ${VOXCD_RTL_SOURCES})
  endif()
  set(gargs "")
  if(M_PARAMS)
    voxcd_model_params("${M_PARAMS}" gargs)
  endif()
  set(kind --cc)
  if(M_SYSTEMC)
    set(kind --sc)
  endif()
  set(trace "")
  if(M_TRACE_FST)
    set(trace --trace-fst)
  endif()
  set(assert --assert)
  if(M_NOASSERT)
    set(assert --noassert)
  endif()
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/${prefix})
  if(M_DIRECTORY)
    set(dir ${M_DIRECTORY})
  endif()
  set(units ${dir}/${prefix}__fast.cpp ${dir}/${prefix}__slow.cpp)
  add_custom_command(OUTPUT ${units} ${dir}/${prefix}.h
    COMMAND ${VERILATOR_BIN} --compiler gcc ${kind} --prefix ${prefix} --Mdir ${dir} --top-module ${M_TOP} ${trace}
            ${assert} ${gargs} ${VOXCD_VERILATOR_OPTIONS} ${M_ARGS} ${M_SOURCES}
    COMMAND ${CMAKE_COMMAND} -DDIR=${dir} -DPREFIX=${prefix} -P ${VOXCD_MODEL_UNITS}
    DEPENDS ${M_SOURCES} ${VERILATOR_BIN} ${VOXCD_MODEL_UNITS}
    WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}
    COMMENT "Verilating ${prefix}"
    VERBATIM)
  target_sources(${library} PRIVATE ${units})
  set_source_files_properties(${dir}/${prefix}__slow.cpp PROPERTIES COMPILE_OPTIONS -O1)
  target_include_directories(${library} SYSTEM PUBLIC ${dir})
endfunction()
set(VOXCD_MODEL_UNITS ${CMAKE_CURRENT_LIST_DIR}/model_units.cmake)

# voxcd_model_library(NAME [STATIC] [SYSTEMC] [TRACE_FST] [DPI] [COVERAGE]): an empty library for models (SHARED
# unless STATIC), with Verilator's runtime for them (tracing to FST when one of its models traces, DPI-C when its
# models import functions, coverage counts when its models are Verilated with --coverage-*: then VM_COVERAGE is 1 for
# the library and for what links it), Verilator's headers as system headers (our targets compile with -Werror) and
# what the runtime links.
function(voxcd_model_library name)
  cmake_parse_arguments(L "SYSTEMC;STATIC;TRACE_FST;DPI;COVERAGE" "" "" ${ARGN})
  if(L_STATIC)
    add_library(${name} STATIC)
  else()
    add_library(${name} SHARED)
  endif()
  set(inc ${VERILATOR_ROOT}/include)
  target_sources(${name} PRIVATE ${inc}/verilated.cpp ${inc}/verilated_threads.cpp)
  if(L_TRACE_FST)
    target_sources(${name} PRIVATE ${inc}/verilated_fst_c.cpp)
    if(L_SYSTEMC)
      target_sources(${name} PRIVATE ${inc}/verilated_fst_sc.cpp)
    endif()
  endif()
  if(L_DPI)
    target_sources(${name} PRIVATE ${inc}/verilated_dpi.cpp)
  endif()
  if(L_COVERAGE)
    target_sources(${name} PRIVATE ${inc}/verilated_cov.cpp)
  endif()
  target_compile_definitions(${name} PUBLIC VM_COVERAGE=$<BOOL:${L_COVERAGE}>)
  target_compile_definitions(${name} PRIVATE VM_TRACE_VCD=0 VM_SC=$<BOOL:${L_SYSTEMC}>
                                             VM_TRACE=$<BOOL:${L_TRACE_FST}> VM_TRACE_FST=$<BOOL:${L_TRACE_FST}>)
  target_include_directories(${name} SYSTEM PUBLIC ${inc} ${inc}/vltstd)
  target_link_libraries(${name} PUBLIC ZLIB::ZLIB Threads::Threads)
  if(L_SYSTEMC)
    target_link_libraries(${name} PUBLIC PkgConfig::SYSTEMC)
  endif()
endfunction()
