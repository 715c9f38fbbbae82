// The error of sizing a device (public, <voxcd/host/api/errors.h> lists them all).
#pragma once

#include <string>

#include "voxcd/ref/error.h"

namespace voxcd {

// A request no device can meet. `constraint` is "accuracy", "contact", "rate", "memory", "extent" or "clock" (no
// pipeline depth meets the clock on the target); what() is "<constraint>: <what>" and says by how much it fails
// (`factor`: how many times finer, faster or larger than the best device allows).
struct SizeError : Error {
  SizeError(const std::string& constraint_, double factor_, const std::string& what)
      : Error(constraint_ + ": " + what), constraint(constraint_), factor(factor_) {}
  // The same error, its message after `prefix` ("mixed.json: cannot be met: accuracy: ...").
  SizeError prefixed(const std::string& prefix) const { return SizeError(prefix + this->what(), constraint, factor); }
  std::string constraint;
  double factor = 0;

 private:
  SizeError(const std::string& what, const std::string& constraint_, double factor_)
      : Error(what), constraint(constraint_), factor(factor_) {}
};

}  // namespace voxcd
