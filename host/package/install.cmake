# cmake --install build --prefix P:
#   P/include/voxcd/       the public headers (<voxcd/voxcd.h> and what it includes, <voxcd/ref/...>, <voxcd/sysc/...>)
#   P/lib/                 libvoxcd (voxcd::host), libvoxcd_ref (voxcd::ref), libvoxcd_ref_fast (voxcd::fast),
#                          libvoxcd_util (voxcd::util: the thread pool of the last two; its header is internal),
#                          libvoxcd_sysc (voxcd::sysc), libvoxcd_dpi (voxcd::dpi) and the Verilated models they load;
#                          P/lib/voxcd/voxcd_rtl_backend.so, the rtl backend's module (it loads libvoxcd_rtl_models)
#   P/lib/cmake/voxcd/     the CMake package: find_package(voxcd CONFIG REQUIRED)
#   P/lib/pkgconfig/       voxcd.pc
#   P/bin/voxcd            the tool; P/libexec/voxcd/voxcd_sysc_server, the sysc backends' platform
#   P/share/voxcd/rtl/     the RTL, its file list voxcd.f and the DPI package voxcd_dpi_pkg.sv
#   P/share/voxcd/timing.tsv  the timing table of bench/timing.sh (the library has it compiled in)
#   P/share/voxcd/energy.tsv  the energy table of bench/energy.sh (the library has it compiled in)
#   P/lib/python3/dist-packages/  the Python module (import voxcd) and its type stubs voxcd.pyi (host/python)
# Included last by the top-level CMakeLists.txt, when every target exists.
include(CMakePackageConfigHelpers)

# Public headers, and only those (docs/api.md): the umbrella <voxcd/voxcd.h> and what it includes (the public API of
# host/api/ and the few plain types it names), the device contract's own headers (the ref door), and the SystemC
# models' (the sysc door). Every other header is internal: not installed. tests/install/consumers.sh checks that each
# installed header includes only installed headers and compiles on its own.
set(VOXCD_PUBLIC_HEADERS
  host/api/object.h host/api/collide.h host/api/world.h host/api/world_def.h host/api/world_types.h host/api/devices.h
  host/api/errors.h host/api/names.h
  host/mesh/errors.h host/object/errors.h host/pairs/errors.h host/device/errors.h host/scene/errors.h
  host/sizing/errors.h
  host/sizing/size_options.h
  host/mesh/mesh.h host/object/storage.h host/object/frame.h host/pairs/contact.h host/scene/body.h
  host/device/device.h host/device/conform.h host/device/clock.h
  ref/error.h ref/config.h ref/types.h ref/fixed.h ref/pipeline.h ref/timing.h ref/vectors.h ref/vector_gen.h
  ref/float_model.h ref/address_map.h ref/fast/fast.h ref/fast/hits.h)
if(TARGET voxcd_sysc)
  list(APPEND VOXCD_PUBLIC_HEADERS sysc/address_map.h sysc/axi_target.h sysc/clocked_target.h sysc/host_cpu.h
                                   sysc/platform.h sysc/rtl_target.h sysc/target.h sysc/tlm_target.h)
endif()
foreach(h ${VOXCD_PUBLIC_HEADERS})
  get_filename_component(dir ${h} DIRECTORY)
  install(FILES ${PROJECT_SOURCE_DIR}/${h} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxcd/${dir})
endforeach()
install(FILES ${PROJECT_SOURCE_DIR}/host/voxcd.h ${VOXCD_INCLUDE_ROOT}/voxcd/version.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/voxcd)

# The Verilated models are loaded by voxcd::host and voxcd::sysc but never linked by a consumer: their usage
# requirements (Verilator's headers, the build tree's generated headers) stay in the build tree.
function(voxcd_build_only_interface target)
  foreach(prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES INTERFACE_LINK_LIBRARIES
               INTERFACE_COMPILE_DEFINITIONS)
    get_target_property(values ${target} ${prop})
    if(values)
      set(wrapped "")
      foreach(v ${values})
        list(APPEND wrapped "$<BUILD_INTERFACE:${v}>")
      endforeach()
      set_property(TARGET ${target} PROPERTY ${prop} "${wrapped}")
    endif()
  endforeach()
endfunction()

# The device models are not built with the tool (docs/build.md): an install of a build that has them configured
# but not built says so and how, before it copies anything.
if(TARGET voxcd_models)
  install(CODE "
    foreach(f \"$<TARGET_FILE:voxcd_rtl_backend>\" \"$<TARGET_FILE:voxcd_sysc_server>\")
      if(NOT EXISTS \"\${f}\")
        message(FATAL_ERROR \"the device models are not built (\${f} is missing): run \"
                            \"cmake --build ${CMAKE_BINARY_DIR} (everything) or \"
                            \"cmake --build ${CMAKE_BINARY_DIR} --target voxcd_models first\")
      endif()
    endforeach()")
endif()

get_property(voxcd_targets GLOBAL PROPERTY VOXCD_EXPORTED_TARGETS)
# voxcd::sysc links the SystemC models: they are installed with it (the C++ models only the rtl module loads).
if(TARGET voxcd_sysc_models)
  voxcd_build_only_interface(voxcd_sysc_models)
  list(APPEND voxcd_targets voxcd_sysc_models)
endif()
if(TARGET voxcd_rtl_backend)
  install(TARGETS voxcd_rtl_models LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(TARGETS voxcd_rtl_backend LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/voxcd)
endif()
set(VOXCD_HAVE_SYSC_PACKAGE OFF)
if(TARGET voxcd_sysc)
  set(VOXCD_HAVE_SYSC_PACKAGE ON)
endif()
install(TARGETS ${voxcd_targets} EXPORT voxcdTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT voxcdTargets NAMESPACE voxcd:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/voxcd)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/voxcd-config.cmake.in
  ${CMAKE_BINARY_DIR}/package/voxcd-config.cmake INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/voxcd
  PATH_VARS CMAKE_INSTALL_DATADIR)
write_basic_package_version_file(${CMAKE_BINARY_DIR}/package/voxcd-config-version.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/package/voxcd-config.cmake ${CMAKE_BINARY_DIR}/package/voxcd-config-version.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/voxcd)

# pkg-config: the host library and what its headers need (Eigen).
configure_file(${CMAKE_CURRENT_LIST_DIR}/voxcd.pc.in ${CMAKE_BINARY_DIR}/package/voxcd.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/package/voxcd.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The tool and the sysc backends' server.
install(TARGETS voxcd RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET voxcd_sysc_server)
  install(TARGETS voxcd_sysc_server RUNTIME DESTINATION ${CMAKE_INSTALL_LIBEXECDIR}/voxcd)
endif()

# The RTL with its file list (and the DPI package, ref/dpi/CMakeLists.txt adds it).
install(FILES ${PROJECT_SOURCE_DIR}/rtl/voxcd.f ${PROJECT_SOURCE_DIR}/rtl/coverage.waivers ${VOXCD_RTL_SOURCES} DESTINATION ${CMAKE_INSTALL_DATADIR}/voxcd/rtl)
# The timing table `voxcd size --target` chooses a depth from (compiled in; here for reading and for --timing-table).
install(FILES ${PROJECT_SOURCE_DIR}/host/device/timing.tsv DESTINATION ${CMAKE_INSTALL_DATADIR}/voxcd)
# The energy per lookup `voxcd size` reports a frame's energy from (compiled in; here for reading).
install(FILES ${PROJECT_SOURCE_DIR}/host/sizing/energy.tsv DESTINATION ${CMAKE_INSTALL_DATADIR}/voxcd)
