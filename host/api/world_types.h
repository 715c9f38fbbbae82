// What a World's bodies and contact events are (public: <voxcd/voxcd.h>), after Box2D v3's b2BodyDef, b2BodyId and
// contact events: a body definition of plain defaults, a stable id, and each step's contacts as structs.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "voxcd/host/api/collide.h"
#include "voxcd/host/api/object.h"
#include "voxcd/host/scene/body.h"

namespace voxcd {

// A body of a World: the slot it holds and the slot's generation. A slot is used again after its body is removed,
// with the next generation, so the id of a removed body is never valid again (World::is_valid). BodyId{} (generation
// 0) is no body's.
struct BodyId {
  uint32_t index = 0;       // the slot
  uint32_t generation = 0;  // 1 for a slot's first body, one more for each body after it
  bool is_null() const { return generation == 0; }
  friend bool operator==(BodyId a, BodyId b) { return a.index == b.index && a.generation == b.generation; }
  friend bool operator!=(BodyId a, BodyId b) { return !(a == b); }
  friend bool operator<(BodyId a, BodyId b) {
    return a.index != b.index ? a.index < b.index : a.generation < b.generation;
  }
};

// A body to add (World::add). Velocities are per unit of time: per second when the world is stepped by seconds
// (World::step(dt)), per frame when it is stepped by frames (World::step()).
struct BodyDef {
  explicit BodyDef(Object object_) : object(std::move(object_)) {}
  Object object;
  Pose pose;                                                  // world = rotation * local + translation
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // world units per unit of time
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // radians per unit of time, about the world axes
  uint64_t user_data = 0;   // the caller's: an index or a pointer's bits; every contact event carries it
  BodyKind kind = BodyKind::kDynamic;  // static: never moves (its velocities must be 0); kinematic: moves, not pushed
  bool enabled = true;      // a disabled body keeps its state but takes no part in the frames (World::set_enabled)
};

// A pair that began or stopped touching in the last step (World::begin_events, end_events). a.index < b.index. The
// ids may be of bodies removed since (an end event for a removed body); the user data are as they were.
struct ContactEvent {
  BodyId a, b;
  uint64_t user_data_a = 0, user_data_b = 0;
};

// A pair touching after the last step (World::touching): at least one hit.
struct ContactData {
  BodyId a, b;  // a.index < b.index
  uint64_t user_data_a = 0, user_data_b = 0;
  uint32_t hits = 0;      // over both directions tested (Mode::Count: the count; Mode::First: up to 1 a direction)
  size_t contacts = 0;    // contacts reported (none in Mode::Count)
  // The unit normal from A towards B the response uses: A's outward normals at A's shell points in B, minus B's at B's
  // points in A; zero when the contacts give none (Mode::Count, or normals that cancel).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  Contact deepest;        // the contact of greatest depth (its `pair` is `pair` below); all zero without contacts
  size_t pair = 0;        // its index in World::pairs() and World::contacts(), which hold every contact
};

}  // namespace voxcd
