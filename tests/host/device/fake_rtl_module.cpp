// A stand-in for the rtl backend's module (host/device/detail/rtl_module.h) built from other sources than the
// library: its digest is not the library's, so the library must refuse it by name (tests/host/cli/cli_backends.cmake).
extern "C" const char* voxcd_rtl_module_abi() { return "0.0 a module of another voxcd"; }
extern "C" const void* voxcd_rtl_module() { return nullptr; }
