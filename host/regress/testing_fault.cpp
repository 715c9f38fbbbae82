#include "voxcd/host/regress/testing_fault.h"

namespace voxcd {

namespace {
FaultTestingHook hook = nullptr;
}  // namespace

void set_fault_testing_hook(FaultTestingHook h) { hook = h; }

void testing_fault(const std::string& unit, uint64_t item) {
  if (hook) hook(unit, item);
}

}  // namespace voxcd
