// The API's internals, for the library's own folders, the tool and the Python module (internal: not installed, no
// compatibility promise). The installed headers name no internal type: an Object holds an opaque Object::Impl and a
// World an opaque World::Impl, both friends of ApiAccess, which this header defines.
#pragma once

#include <memory>
#include <utility>

#include "voxcd/host/api/object.h"
#include "voxcd/host/api/world.h"
#include "voxcd/host/object/object_type.h"

namespace voxcd {

struct RunConfig;  // host/scene/run_config.h

// What an Object is inside the library: its ObjectType, shared by every copy of the Object.
struct Object::Impl {
  std::shared_ptr<const ObjectType> type;
};

struct ApiAccess {
  // The library's form of an object, for its internal interfaces.
  static const std::shared_ptr<const ObjectType>& type_of(const Object& object) { return object.impl_->type; }
  // An Object of the library's form of one (the Python module's objects, a scene's types).
  static Object object_of(std::shared_ptr<const ObjectType> type) {
    return Object(std::make_shared<const Object::Impl>(Object::Impl{std::move(type)}));
  }
  // The world of a checked run configuration (the tool's and the Python module's door; host/api/world.cpp).
  static World world_of(const RunConfig& config);
};

}  // namespace voxcd
