// The testing aid of runs over ranks (docs/regress.md, "Testing aids"): a hook that the test build's tool
// (build/voxcd_testing, tests/testing/) sets so that the rank that runs a given shard or sweep point fails, hangs or
// exits, and tests can drive every fault a run must name. Empty in the shipped library and tool, which read no
// environment variable for it.
#pragma once

#include <cstdint>
#include <string>

namespace voxcd {

// Called as a run reaches item `item` of `unit` ("SHARD" of a campaign, "POINT" of a sweep). It may throw, never
// return or end the process.
using FaultTestingHook = void (*)(const std::string& unit, uint64_t item);

// Sets the hook (nullptr: none, the default). Set it before a run starts; it is not synchronised.
void set_fault_testing_hook(FaultTestingHook hook);

// The hook's call at item `item` (nothing without a hook).
void testing_fault(const std::string& unit, uint64_t item);

}  // namespace voxcd
