// The error of devices (public, <voxcd/host/api/errors.h> lists them all).
#pragma once

#include "voxcd/ref/error.h"

namespace voxcd {

// A backend that cannot be made or cannot run what it was given; the message says why.
struct DeviceError : Error {
  using Error::Error;
};

}  // namespace voxcd
