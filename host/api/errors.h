// Every error the public API throws, by name (public: <voxcd/voxcd.h>). Each derives from voxcd::Error (what(),
// where()), itself a std::runtime_error; the Python module raises a class of the same name (docs/python.md).
//   Error            ref/error.h          the base: catch it for every one below
//   RangeError       ref/error.h          a value that does not fit its fixed-point format, or is not finite (a pose)
//   ConfigError      ref/error.h          a device configuration no device can have
//   JobError         ref/error.h          a job the device cannot run
//   VectorError      ref/error.h          a malformed conformance vector file
//   MeshError        host/mesh/errors.h   a mesh (file, arrays or shape) that cannot be used
//   ObjectFileError  host/object/errors.h a file that is not an object file, or cannot be written
//   CapacityError    host/pairs/errors.h  objects that do not fit a device's memories or formats
//   DeviceError      host/device/errors.h a backend that cannot be made or cannot run
//   SceneFileError   host/scene/errors.h  a scene file, or one of its keys, that cannot be used
//   OptionError      host/scene/errors.h  a setting given in code (WorldDef, SizeOptions) that cannot be used
//   PlacementError   host/scene/errors.h  bodies that do not fit the cube
//   RecordError      host/scene/errors.h  a recording that cannot be written or read
//   SizeError        host/sizing/errors.h a request no device can meet
//   BodyError        host/api/errors.h    a body id that names no body of the world, or a value a body cannot have
#pragma once

#include <string>
#include <utility>

#include "voxcd/host/api/world_types.h"
#include "voxcd/host/device/errors.h"
#include "voxcd/host/object/errors.h"
#include "voxcd/host/pairs/errors.h"
#include "voxcd/host/scene/errors.h"
#include "voxcd/host/sizing/errors.h"
#include "voxcd/ref/error.h"

namespace voxcd {

// A body of a World that cannot be used, or a value it cannot have: an id of a body removed (its slot has moved on to
// another generation) or never made; a pose, velocity or angular velocity that is not finite, a rotation that is not
// a unit quaternion, a velocity given to a static body. what() is "body 3: velocity: (nan, 0, 0) is not finite"
// (the body named by its slot, "the new body" in World::add), where() "body 3"; `body` is the id given (null for a
// new body), `field` the value ("pose", "velocity", "angular_velocity"; "" for an id that names no body).
struct BodyError : Error {
  BodyError(BodyId body_, std::string field_, const std::string& place, const std::string& message)
      : Error(place + ": " + (field_.empty() ? "" : field_ + ": ") + message, place), body(body_),
        field(std::move(field_)) {}
  BodyId body;
  std::string field;
};

}  // namespace voxcd
