# Which backends can run, as `voxcd --version` lists them, and what a backend whose device models are missing says
# (docs/build.md, "The device models"): the models are never linked, the library loads them when first used.
#   cmake -DVOXCD=tool -DLIB=libvoxcd.so -DREF_LIB=libvoxcd_ref.so -DSTALE=fake-module.so -DMODELS=ON|OFF
#         -DWORK=dir -P cli_backends.cmake
# MODELS: whether the build configured the device models (and built them, as `cmake --build` does).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/../../cli_helpers.cmake)

run(0 out ${VOXCD} --version)
expect("${out}" "^voxcd [0-9]+\\.[0-9]+\nbackends:\n  ref +ready\n  cpu +ready\n  rtl +[^\n]+\n  sysc-rtl +[^\n]+\n  sysc-tlm +[^\n]+\n?$")
if(MODELS)
  # Every backend of a full build can run.
  expect("${out}" "\n  rtl +ready\n  sysc-rtl +ready\n  sysc-tlm +ready")
else()
  set(off "not ready: this build was configured without the device models \\(-DVOXCD_DEVICE_MODELS=OFF\\)")
  expect("${out}" "\n  rtl +${off}\n  sysc-rtl +${off}\n  sysc-tlm +${off}")
  run(2 out ${VOXCD} simulate --objects 4 --frames 1 --backend rtl)
  expect("${out}" "voxcd: error: rtl: this build was configured without the device models")
  run(2 out ${VOXCD} simulate --objects 4 --frames 1 --backend sysc-tlm)
  expect("${out}" "voxcd: error: sysc-tlm: this build was configured without the device models")
endif()

# A module that cannot be loaded, one that is not a module, and one built from other sources: each named, with
# the command that rebuilds the models (the build directory of the library in use).
set(ENV{VOXCD_RTL_MODULE} ${WORK}/no/such/module.so)
run(0 out ${VOXCD} --version)
expect("${out}" "\n  rtl +not ready: cannot load the RTL models' module ${WORK}/no/such/module\\.so: [^\n]*No such file")
run(2 out ${VOXCD} simulate --objects 4 --frames 1 --backend rtl)
expect("${out}" "voxcd: error: rtl: cannot load the RTL models' module ${WORK}/no/such/module\\.so: .*No such file or directory \\(build them with `cmake --build [^`]+ --target voxcd_models`\\)")
set(ENV{VOXCD_RTL_MODULE} ${REF_LIB})
run(2 out ${VOXCD} simulate --objects 4 --frames 1 --backend rtl)
expect("${out}" "voxcd: error: rtl: [^\n]*libvoxcd_ref[^\n]* is not an RTL models' module \\(no voxcd_rtl_module entry points\\)")
set(ENV{VOXCD_RTL_MODULE} ${STALE})
run(2 out ${VOXCD} simulate --objects 4 --frames 1 --backend rtl)
expect("${out}" "voxcd: error: rtl: the RTL models' module [^\n]*fake_rtl_module[^\n]* was built from other sources than this library \\(build them with `cmake --build [^`]+ --target voxcd_models`\\)")
# The tool's other backends are not affected.
run(0 out ${VOXCD} simulate --objects 4 --frames 1 --backend cpu)
expect("${out}" "state hash")
unset(ENV{VOXCD_RTL_MODULE})

if(MODELS)
  # The library in a directory of its own: a build tree without the models built, then an installation without
  # them. The message names the command for that build tree, or says how to install the models.
  get_filename_component(lib_name ${LIB} NAME)
  file(GLOB libs ${LIB}*)
  file(MAKE_DIRECTORY ${WORK}/tree)
  file(COPY ${libs} DESTINATION ${WORK}/tree)
  file(TOUCH ${WORK}/tree/CMakeCache.txt)
  set(ENV{LD_LIBRARY_PATH} ${WORK}/tree)
  run(0 out ${VOXCD} --version)
  expect("${out}" "\n  rtl +not ready: the RTL models are not built \\(build them with `cmake --build ${WORK}/tree --target voxcd_models`\\)")
  expect("${out}" "\n  sysc-rtl +not ready: the SystemC platform server is not built \\(build it with `cmake --build ${WORK}/tree --target voxcd_models`\\)")
  run(2 out ${VOXCD} pair cube cube --resolution 8 --backend sysc-rtl)
  expect("${out}" "voxcd: error: sysc-rtl: the SystemC platform server is not built")
  file(REMOVE ${WORK}/tree/CMakeCache.txt)
  run(0 out ${VOXCD} --version)
  expect("${out}" "\n  rtl +not ready: this installation has no RTL models \\(build them with `cmake --build BUILD --target voxcd_models` before `cmake --install BUILD`\\)")
  unset(ENV{LD_LIBRARY_PATH})
endif()
