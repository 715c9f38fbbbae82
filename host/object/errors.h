// The errors of objects (public, <voxcd/host/api/errors.h> lists them all): a mesh that cannot be used, a file
// that is not an object file.
#pragma once

#include "voxcd/ref/error.h"

namespace voxcd {

// Bad mesh input: says what is wrong and where (file and line, triangle or edge index).
struct MeshError : Error {
  using Error::Error;
};

// A file that is not a valid object file, or one that cannot be written: says which file, what is wrong and at
// which byte offset.
struct ObjectFileError : Error {
  using Error::Error;
};

}  // namespace voxcd
