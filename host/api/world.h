// A world the caller steps (public: <voxcd/voxcd.h>): bodies of objects in a cube with walls, a broadphase and pair
// tests on a device each frame, a response. Made from a WorldDef and bodies, or from the built-in scene or a scene
// file (World::scene). docs/simulate.md describes a frame.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "voxcd/host/api/collide.h"
#include "voxcd/host/api/object.h"
#include "voxcd/host/scene/body.h"
#include "voxcd/ref/types.h"

namespace voxcd {

struct RunConfig;  // a run's configuration, as `voxcd simulate` takes it (internal: host/scene/run_config.h)
class World;
namespace detail {
// The world of a checked run configuration (the tool's and the Python module's door; no compatibility promise).
World world_of(const RunConfig& config);
}  // namespace detail

// WorldDef (how a world runs) is in voxcd/host/scene/body.h.
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

  // Adds a body of `object` at `pose`, moving by `velocity` world units and turning by `spin` radians (about the
  // world axes) per frame; its index. A body added after a frame joins from the next frame.
  uint32_t add_body(const Object& object, const Pose& pose, const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero(),
                    const Eigen::Vector3d& spin = Eigen::Vector3d::Zero());
  // One frame: integrate, walls, broadphase, pair tests, response. std::invalid_argument for options the bodies
  // cannot have (ccd without distance fields, a broadphase or backend that does not exist).
  const FrameStats& step();

  size_t size() const;                     // bodies
  const std::vector<Body>& bodies() const; // their state now; Body::type indexes the world's objects
  const Object& object(uint32_t type) const;
  uint64_t frame() const;                  // frames stepped
  // The last frame's pairs tested on the device (body indices, first < second) and their contacts, in one order.
  const std::vector<std::pair<uint32_t, uint32_t>>& pairs() const;
  const std::vector<Contacts>& contacts() const;
  const FrameStats& stats() const;         // the last frame's
  uint64_t state_hash() const;             // of every body's state: equal runs, equal hash
  // Records every frame from now on into `path` (docs/view.md; `voxcd view` replays it); stop_recording closes it.
  void record(const std::string& path);
  void stop_recording();

 private:
  struct Impl;
  explicit World(std::unique_ptr<Impl> impl);
  friend World detail::world_of(const RunConfig& config);
  std::unique_ptr<Impl> impl_;
};

}  // namespace voxcd
