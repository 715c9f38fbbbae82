// The error of pair tests (public, <voxcd/host/api/errors.h> lists them all).
#pragma once

#include "voxcd/ref/error.h"

namespace voxcd {

// Object types that do not fit the device's memories or formats; names the type and the sizes.
struct CapacityError : Error {
  using Error::Error;
};

}  // namespace voxcd
