// Every error the public API throws, by name (public: <voxcd/voxcd.h>). Each derives from voxcd::Error (what(),
// where()), itself a std::runtime_error; the Python module raises a class of the same name (docs/python.md).
//   Error            ref/error.h          the base: catch it for every one below
//   RangeError       ref/error.h          a value that does not fit its fixed-point format, or is not finite (a pose)
//   ConfigError      ref/error.h          a device configuration no device can have
//   JobError         ref/error.h          a job the device cannot run
//   VectorError      ref/error.h          a malformed conformance vector file
//   MeshError        host/object/errors.h a mesh (file, arrays or shape) that cannot be used
//   ObjectFileError  host/object/errors.h a file that is not an object file, or cannot be written
//   CapacityError    host/pairs/errors.h  objects that do not fit a device's memories or formats
//   DeviceError      host/device/errors.h a backend that cannot be made or cannot run
//   SceneFileError   host/scene/errors.h  a scene file, or one of its keys, that cannot be used
//   OptionError      host/scene/errors.h  a setting given in code (WorldDef, SizeOptions) that cannot be used
//   PlacementError   host/scene/errors.h  bodies that do not fit the cube
//   RecordError      host/scene/errors.h  a recording that cannot be written or read
//   SizeError        host/sizing/errors.h a request no device can meet
#pragma once

#include "voxcd/host/device/errors.h"
#include "voxcd/host/object/errors.h"
#include "voxcd/host/pairs/errors.h"
#include "voxcd/host/scene/errors.h"
#include "voxcd/host/sizing/errors.h"
#include "voxcd/ref/error.h"
