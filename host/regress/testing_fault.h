// The testing aid of runs over ranks (docs/regress.md, "Testing aids"): an environment variable KIND:ITEM makes the
// rank that runs item ITEM fail (throw), hang or exit at once, so that tests can drive every fault a run must name.
#pragma once

#include <cstdint>
#include <string>

namespace voxcd {

// Reads `variable` (unset or empty: nothing happens). When it names `item`: "fail" throws std::runtime_error, "hang"
// never returns, "exit" ends the process with code 3. A value that is not KIND:ITEM throws std::runtime_error naming
// the variable and the form (`unit`, "SHARD" or "POINT", names ITEM in it).
void testing_fault(const std::string& variable, const std::string& unit, uint64_t item);

}  // namespace voxcd
