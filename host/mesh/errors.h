// The error of meshes (public, <voxcd/host/api/errors.h> lists them all): a mesh that cannot be used.
#pragma once

#include "voxcd/ref/error.h"

namespace voxcd {

// Bad mesh input: says what is wrong and where (file and line, triangle or edge index).
struct MeshError : Error {
  using Error::Error;
};

}  // namespace voxcd
