// A body of a world and what one frame of a world did (public: <voxcd/voxcd.h>). How a world runs, WorldDef, is the
// API's (host/api/world_def.h).
#pragma once

#include <Eigen/Core>
#include <cstdint>

#include "voxcd/host/object/frame.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// How a body moves (Box2D's b2BodyType, Jolt's EMotionType). A static body never moves; a kinematic one moves by its
// velocities alone (no wall or response changes them); a dynamic one bounces off the walls and other bodies. The
// response pushes only dynamic bodies, and a pair of which neither is dynamic is not tested.
enum class BodyKind : uint8_t { kDynamic, kStatic, kKinematic };

// Velocities are per unit of time: per frame for a frame step (World::step(), `voxcd simulate`), per second for a
// step of dt seconds (World::step(dt)).
struct Body {
  uint32_t type = 0;
  BodyKind kind = BodyKind::kDynamic;                // (in the padding after `type`: a Body is as large as before)
  Pose pose;                                         // world = rotation * local + translation
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // world units per unit of time
  Eigen::Vector3d spin = Eigen::Vector3d::Zero();      // angular velocity, radians per unit of time, world axes
  bool moves() const { return kind != BodyKind::kStatic; }
  bool pushed() const { return kind == BodyKind::kDynamic; }  // by the walls and the response
};

struct FrameStats {
  uint64_t frame = 0;
  uint64_t pairs = 0;       // from the broadphase
  uint64_t tested = 0;      // of those, tested on the device (the others' oriented boxes are disjoint)
  uint64_t touching = 0;    // pairs with at least one hit
  uint64_t responses = 0;   // pairs whose velocities the response changed (they were approaching)
  uint64_t wall_hits = 0;   // body-wall bounces
  uint64_t lookups = 0;     // shell points submitted
  uint64_t hits = 0;
  uint64_t contacts = 0;
  uint64_t device_cycles = 0;  // of the frame's job streams (measured on rtl, the timing model on ref and cpu);
                               // distributed: of the busiest rank's
  // Continuous collision (WorldDef::ccd; all 0 without it): advancement steps, pair queries, distinct pairs whose
  // bound cut a step short, time-of-impact events (pair responses and wall reflections, also counted in responses
  // and wall_hits), bodies whose remaining motion the iteration cap dropped, shell points the queries submitted.
  uint64_t ccd_iterations = 0, ccd_queries = 0, ccd_limited = 0, ccd_toi = 0, ccd_dropped = 0, ccd_lookups = 0;
  // Seconds per stage.
  double t_integrate = 0, t_bounds = 0, t_broadphase = 0, t_narrow = 0, t_response = 0;
  double seconds() const { return t_integrate + t_bounds + t_broadphase + t_narrow + t_response; }
};

}  // namespace voxcd
