// A world the caller steps (public: <voxcd/voxcd.h>), after Box2D v3's world and Jolt's PhysicsSystem: bodies of
// objects added from a BodyDef and named by stable BodyIds, their poses and velocities set and read between steps,
// removed; each step a broadphase, pair tests on a device, by default the cube's walls and the built-in response,
// and the contacts as events (pairs that began and stopped touching) and as the pairs touching now. A world with
// WorldDef::walls and WorldDef::response false only detects and reports. Made from a WorldDef and bodies, or from the
// built-in scene or a scene file (World::scene). docs/simulate.md describes a frame; docs/api.md shows it in use.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "voxcd/host/api/collide.h"
#include "voxcd/host/api/errors.h"
#include "voxcd/host/api/object.h"
#include "voxcd/host/api/world_def.h"
#include "voxcd/host/api/world_types.h"
#include "voxcd/host/scene/body.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// WorldDef (how a world runs: the cube, its walls, the response, the broadphase, the device) is in
// voxcd/host/api/world_def.h.
class World {
 public:
  explicit World(const WorldDef& def = {});
  // The scene `voxcd simulate` runs: the built-in one with its defaults, or a scene file (docs/scenes.md) with its
  // own settings. Stepped as many frames, it has the tool's state hash (`voxcd simulate [scene_file]`). An error
  // (std::invalid_argument, std::runtime_error) names the file and the key for a scene file that cannot be used.
  static World scene();
  static World scene(const std::string& scene_file);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;

  // Bodies. Every function taking a BodyId throws BodyError for an id that names no body (removed, or never made).
  // Adds a body (it takes part from the next step); BodyError naming the field for a pose or velocity that is not
  // finite, a rotation that is not a unit quaternion, or velocities given to a static body.
  BodyId add(const BodyDef& def);
  // Removes a body; the pairs it touched end (end_events() of the next step).
  void remove(BodyId id);
  bool is_valid(BodyId id) const;  // the id names a body of this world (not removed)
  Pose pose(BodyId id) const;
  Eigen::Vector3d velocity(BodyId id) const;          // world units per unit of time
  Eigen::Vector3d angular_velocity(BodyId id) const;  // radians per unit of time, about the world axes
  uint64_t user_data(BodyId id) const;
  BodyKind kind(BodyId id) const;
  const Object& object(BodyId id) const;
  // Between steps: a pose moves the body there (a teleport: no motion in between); BodyError as add's.
  void set_pose(BodyId id, const Pose& pose);
  void set_velocity(BodyId id, const Eigen::Vector3d& velocity);
  void set_angular_velocity(BodyId id, const Eigen::Vector3d& angular_velocity);
  void set_user_data(BodyId id, uint64_t user_data);
  // A disabled body keeps its state and id but takes no part in the steps (its pairs end, as at removal).
  void set_enabled(BodyId id, bool enabled);
  bool is_enabled(BodyId id) const;

  // Adds a body of `object` at `pose`, moving by `velocity` world units and turning by `spin` radians (about the
  // world axes) per frame; its index in bodies() while no body has been removed or disabled (its BodyId's index).
  // The form before BodyDef: World::add takes every setting of a body and gives a BodyId.
  [[deprecated("use World::add(BodyDef), which returns a BodyId")]]
  uint32_t add_body(const Object& object, const Pose& pose, const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero(),
                    const Eigen::Vector3d& spin = Eigen::Vector3d::Zero());

  // One frame, each velocity taken as per frame: integrate, walls, broadphase, pair tests, response, events. `voxcd
  // simulate` steps a scene this way (its state hashes). OptionError, or std::invalid_argument for options the bodies
  // cannot have (ccd without distance fields, a broadphase or backend that does not exist).
  const FrameStats& step();
  // A step of `dt` seconds, each velocity taken as per second: the frame step's arithmetic with every motion scaled
  // by dt (step() is step(1)). OptionError "dt: ..." for a dt that is negative or not finite.
  const FrameStats& step(double dt);

  // Contact events of the last step (Box2D's begin and end touch events), each pair by its bodies' ids (a.index <
  // b.index) with their user data, in the order of the pairs' indices: pairs that began touching in it, and pairs
  // that stopped (with those of bodies removed or disabled since the step before it). Kept until the next step.
  const std::vector<ContactEvent>& begin_events() const;
  const std::vector<ContactEvent>& end_events() const;
  // Every pair touching after the last step, with its contact count, normal and deepest contact, in the same order.
  const std::vector<ContactData>& touching() const;

  // The bodies taking part (not disabled), in the order of their ids' indices: their states now (Body::type indexes
  // the world's objects) and ids. size() counts them.
  size_t size() const;
  const std::vector<Body>& bodies() const;
  const std::vector<BodyId>& ids() const;
  const Object& object(uint32_t type) const;
  uint64_t frame() const;                  // frames stepped
  // The last step's pairs tested on the device (indices into bodies() and ids(), first < second) and their
  // contacts, in one order; empty once a body has been added, removed, enabled or disabled after it.
  const std::vector<std::pair<uint32_t, uint32_t>>& pairs() const;
  const std::vector<Contacts>& contacts() const;
  const FrameStats& stats() const;         // the last frame's
  uint64_t state_hash() const;             // of every body's state: equal runs, equal hash
  // Records every frame from now on into `path` (docs/view.md; `voxcd view` replays it); stop_recording closes it.
  // A recording holds the bodies it began with: adding, removing, enabling or disabling a body while recording is a
  // RecordError (stop first; a new recording may follow).
  void record(const std::string& path);
  void stop_recording();

 private:
  struct Impl;
  explicit World(std::unique_ptr<Impl> impl);
  friend struct ApiAccess;  // the world of a run configuration (internal: host/api/access.h)
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxcd
