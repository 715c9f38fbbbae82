// Which forms an object's voxmap, shell and distance field are kept in (docs/objects.md, "Sparse objects"). A plain
// type of the public API (ObjectDef::storage).
#pragma once

namespace voxcd {

// Which forms make_object builds. kDense: the dense voxmap and shell, as before sparse forms existed (the library's
// default). kSparse: the sparse voxmap and shell. kAuto: each of the two in whichever form takes fewer bytes of device
// memory with the default widths (a dense voxmap only while it fits kMaxDenseDim per axis, a dense shell while its
// grid fits 4096). An object with a distance field keeps its voxmap and its shell on the surface dense (up to
// kMaxDenseDim per axis); kSparse stores its field sparse with refined bricks, kAuto in the smaller form.
enum class ObjectStorage { kDense, kSparse, kAuto };

// "dense", "sparse" or "auto" (as voxcd voxelize --storage takes them).
inline const char* storage_name(ObjectStorage s) {
  return s == ObjectStorage::kSparse ? "sparse" : s == ObjectStorage::kAuto ? "auto" : "dense";
}

}  // namespace voxcd
