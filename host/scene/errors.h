// The errors of a run's settings, scenes and recordings (public, <voxcd/host/api/errors.h> lists them all).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "voxcd/ref/error.h"

namespace voxcd {

// A scene file, or a setting read from one, that cannot be used: the message starts with where, the file then the
// JSON path of the key ("mixed.json: types[1].voxel: -1 is outside (0, 1e+12]").
struct SceneFileError : Error {
  using Error::Error;
};

// A setting given in code or as an option that cannot be used (a WorldDef field, World::scene's or Python's keyword,
// the tool's option): `options` names it, or the settings in conflict, as Python's keywords do ("mode"; "voxel",
// "resolution"), `message` says what is wrong; what() is "mode: 'X' is not ALL, FIRST or COUNT" (the names joined
// by ", ", a colon, the message) and where() the names joined.
struct OptionError : Error {
  OptionError(std::vector<std::string> options_, const std::string& message_);
  std::vector<std::string> options;
  std::string message;
};
// The name this error had when only `voxcd simulate` threw it.
using SimulateOptionError [[deprecated("use voxcd::OptionError")]] = OptionError;

// Bodies that do not fit the cube: even the densest lattice at the closest spacing has too few sites (`capacity`).
struct PlacementError : Error {
  PlacementError(uint32_t t, uint64_t k, uint64_t cap, double r)
      : Error("could not place instance " + std::to_string(k) + " of type " + std::to_string(t) +
                  ": bounding spheres of radius " + std::to_string(r) + " fit at most " + std::to_string(cap) +
                  " in the cube",
              "type " + std::to_string(t) + " instance " + std::to_string(k)),
        type(t), instance(k), capacity(cap), radius(r) {}
  uint32_t type;
  uint64_t instance;  // the first body the lattice has no site for
  uint64_t capacity;  // sites of the densest lattice for spheres of `radius`
  double radius;      // the largest bounding radius
};

// A recording that cannot be written or read: says which file, what is wrong and at which byte.
struct RecordError : Error {
  using Error::Error;
};

}  // namespace voxcd
