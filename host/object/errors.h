// The errors of objects (public, <voxcd/host/api/errors.h> lists them all): a mesh that cannot be used, a file
// that is not an object file.
#pragma once

#include "voxcd/host/mesh/errors.h"  // MeshError
#include "voxcd/ref/error.h"

namespace voxcd {

// A file that is not a valid object file, or one that cannot be written: says which file, what is wrong and at
// which byte offset.
struct ObjectFileError : Error {
  using Error::Error;
};

}  // namespace voxcd
