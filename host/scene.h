// N-body scenes: instances of object types with rigid state, and the paper's simulation environment (a cube of side
// 100 at a density of 2.5%, random momentum, Euler integration, wall and object-object response), stepped frame by
// frame with a broadphase and pair tests on a device backend. docs/simulate.md describes it.
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/broadphase.h"
#include "host/collide.h"
#include "host/object_type.h"

namespace voxcd {

struct Body {
  uint32_t type = 0;
  RigidPose pose;                                    // world = rotation * local + translation
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // world units per frame
  Eigen::Vector3d spin = Eigen::Vector3d::Zero();      // angular velocity, radians per frame, world axes
};

struct Scene {
  double side = 100;  // the environment: the cube [0, side]^3, walls on its faces
  std::vector<std::shared_ptr<const ObjectType>> types;
  std::vector<Body> bodies;
};

// The paper's environment (Section 7): `objects` copies of one shape (a built-in name or a mesh file) scaled so
// that they fill `density` of the cube, voxelised at `voxel` world units (the paper's accuracy: one unit), placed
// at random without overlapping bounding spheres, with random orientations, random velocities of up to `speed`
// times the object's bounding radius per frame and random spins of up to `spin` radians per frame.
struct SceneSpec {
  std::string shape = "polytope36";
  size_t objects = 64;
  double side = 100;
  double density = 0.025;
  double speed = 0.1;
  double spin = 0.02;
  double voxel = 1.0;
  uint64_t seed = 1;
};

// Throws std::invalid_argument naming the field for a value out of range (no objects, density outside (0, 0.3],
// a voxel size that makes the object larger than 2^10 voxels or smaller than 2 across), MeshError for the shape.
Scene make_scene(const SceneSpec& spec);

struct SimOptions {
  std::string pruning = "grid";  // a broadphase name (host/broadphase.h): the fastest at every N measured
  std::string backend = "cpu";   // a device backend
  int lanes = 4;                 // lanes of the modelled device
  // The device's whole configuration (e.g. one `voxcd size` derived); it replaces `lanes` and the memories grown
  // to fit. Unset: the default widths with `lanes`.
  std::optional<DeviceConfig> device;
  Mode mode = Mode::All;         // ALL reports every contact; FIRST only tells whether a pair touches
  bool both_directions = false;  // also test B's shell in A's voxmap
  unsigned threads = 0;          // cpu backend threads (0: all); results never depend on it
  // Before the device, drop broadphase pairs whose oriented boxes (each type's contact bounds in its own frame,
  // grown by one voxel) are disjoint: such a pair can have no hit, so results never depend on it.
  bool midphase = true;
  // Submit only the shell points whose clusters can land in the other object's voxmap (PairOptions::cull):
  // results never depend on it, lookups and device cycles do.
  bool cull = true;
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
  uint64_t device_cycles = 0;  // of the frame's job stream (measured on rtl, the timing model on ref and cpu)
  // Seconds per stage.
  double t_integrate = 0, t_bounds = 0, t_broadphase = 0, t_narrow = 0, t_response = 0;
  double seconds() const { return t_integrate + t_bounds + t_broadphase + t_narrow + t_response; }
};

class Simulation {
 public:
  // The device is configured from the scene: only its object types are loaded, with memories grown to fit them.
  Simulation(Scene scene, const SimOptions& opt);
  // One frame: integrate, bounce off the walls, bounds, broadphase, pair tests, response.
  FrameStats step();
  const Scene& scene() const { return scene_; }
  const Broadphase& broadphase() const { return *broadphase_; }
  const DeviceConfig& device_config() const { return collider_->device().config(); }
  uint64_t frame() const { return frame_; }
  // A hash of every body's state (bit patterns of positions, orientations and velocities): equal runs, equal hash.
  uint64_t state_hash() const;

 private:
  void compute_bounds();

  Scene scene_;
  SimOptions opt_;
  std::unique_ptr<Broadphase> broadphase_;
  std::unique_ptr<PairCollider> collider_;
  std::vector<BodyBounds> bounds_;
  // Each body's rotation matrix and the world centre of its contact box, this frame (for the mid-phase).
  std::vector<Eigen::Matrix3d> rot_;
  std::vector<Eigen::Vector3d> box_centre_;
  std::vector<bool> moved_;
  std::vector<PairRequest> requests_;
  std::vector<uint32_t> tested_;  // the broadphase index of each request
  std::vector<PairResult> results_;
  uint64_t frame_ = 0;
};

// Places counts[i] bodies of scene.types[i] in the cube [0, scene.side]^3, type by type, appending them to
// scene.bodies: random non-overlapping enclosing spheres (up to 10,000 tries each), random orientations, velocities
// of up to `speed` times the type's radius per frame in a random direction and spins of up to `spin` radians per
// frame. Deterministic for a seed. PlacementError names the body that found no place.
struct PlacementError : std::runtime_error {
  PlacementError(uint32_t t, uint64_t k)
      : std::runtime_error("could not place instance " + std::to_string(k) + " of type " + std::to_string(t)),
        type(t), instance(k) {}
  uint32_t type;
  uint64_t instance;
};
void place_bodies(Scene& scene, const std::vector<uint64_t>& counts, double speed, double spin, uint64_t seed);

// The scenes' random draws (a uniform rotation; a uniform unit direction), one definition so that scene files
// place bodies exactly as the built-in scene does.
Eigen::Quaterniond scene_rotation(std::mt19937_64& rng);
Eigen::Vector3d scene_direction(std::mt19937_64& rng);

// A body's world bounds: its type's smallest enclosing sphere and the world box of its type's local box.
BodyBounds body_bounds(const ObjectType& t, const Body& b);
// The same, given R = b's rotation matrix and c = R * (t.lo + t.hi) / 2 + b's translation (its box's centre).
BodyBounds body_bounds(const ObjectType& t, const Body& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& c);

}  // namespace voxcd
