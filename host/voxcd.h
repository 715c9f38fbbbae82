// <voxcd/voxcd.h>: the whole public API of the host library (voxcd::host) and the reference (voxcd::ref), in the
// order of the data's path: the device contract, objects, devices, pair tests, broadphases, scenes, sizing.
// The SystemC models (voxcd::sysc) have headers of their own under <voxcd/sysc/>. docs/api.md shows each part in use.
#pragma once

#include "voxcd/version.h"

// The device contract (ref/): configuration, records, fixed point, the pipeline, its cycle model, vectors.
#include "voxcd/ref/config.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"

// Objects: meshes, repair, shapes, voxmaps, point shells, object files and types.
#include "voxcd/host/object/bounds.h"
#include "voxcd/host/object/convex.h"
#include "voxcd/host/object/frame.h"
#include "voxcd/host/object/mesh.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/png.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"

// Devices: the interface and the backend registry (device_backends, make_device), conformance vectors on them.
#include "voxcd/host/device/clock.h"
#include "voxcd/host/device/conform.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/regress/campaign.h"
#include "voxcd/host/regress/journal.h"
#include "voxcd/host/regress/report.h"
#include "voxcd/host/regress/results_file.h"
#include "voxcd/host/regress/shard.h"

// Pair tests: poses, the device image, contacts.
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/pairs/pose.h"

// Broadphases, scenes and scene files, sizing.
#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/scene/ccd.h"
#include "voxcd/host/scene/distance_bound.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/scene/simulate.h"
#include "voxcd/host/sizing/contact_bound.h"
#include "voxcd/host/sizing/size.h"

// Where the installed package keeps its RTL and programs.
#include "voxcd/host/package/paths.h"
