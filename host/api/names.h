// The names an ObjectDef, a WorldDef and CollideOptions take (public: <voxcd/voxcd.h>): built-in shapes, broadphases
// and job modes, each listed as the library knows them (the backends are devices.h's device_backends()).
#pragma once

#include <string>
#include <vector>

namespace voxcd {

std::vector<std::string> shape_names();       // what Object::load takes besides files: polytope36, ..., torus, cube
std::vector<std::string> broadphase_names();  // WorldDef::broadphase: grid (the default), sap, ...
const std::vector<std::string>& mode_names();  // Mode's names: ALL, FIRST, COUNT (ref/types.h parse_mode)

}  // namespace voxcd
