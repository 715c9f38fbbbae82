// <voxcd/voxcd.h>: the public API of the host library (voxcd::host), in the order a user meets it (docs/api.md):
// objects, one pair query, a world the caller steps, devices. Everything else of the library is internal: not
// included here, not installed, free to change. The device contract's own headers (<voxcd/ref/...>: the
// specification, its cycle model, conformance vectors) and the SystemC models (<voxcd/sysc/...>) are doors of
// their own (docs/api.md).
#pragma once

#include "voxcd/version.h"

// The device contract's configuration and records.
#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

// Errors: voxcd::Error and every error the API throws, by name.
#include "voxcd/host/api/errors.h"

// Objects: from a mesh file, arrays, a built-in shape or an object file.
#include "voxcd/host/api/object.h"

// One pair query: collide(a, pose_a, b, pose_b, options) -> Contacts.
#include "voxcd/host/api/collide.h"

// A world the caller steps.
#include "voxcd/host/api/world.h"

// Names: the built-in shapes, broadphases and job modes.
#include "voxcd/host/api/names.h"

// Devices: backends by name, conformance vectors, the smallest device for a scene.
#include "voxcd/host/api/devices.h"
