#include "voxcd/host/api/world.h"

#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd {

struct World::Impl {
  Scene scene;                       // the bodies until the first frame (then the simulation's)
  RunConfig options;                 // how it runs (the scene is `scene`)
  std::vector<Object> objects;       // in type order
  std::unique_ptr<Simulation> sim;
  bool stale = true;                 // bodies were added since the simulation was made
  uint64_t frames = 0;
  FrameStats last;
  bool from_scene = false;           // made from a scene: a recording's run settings are the run's (else "{}")
  std::unique_ptr<RecordWriter> rec;

  // The simulation of the bodies now, made anew when bodies were added (their states carry over).
  Simulation& simulation() {
    if (sim && !stale) return *sim;
    // add_body copied the simulation's bodies into `scene` before adding: it holds every body's state now.
    sim.reset();
    sim = std::make_unique<Simulation>(scene, options);
    stale = false;
    return *sim;
  }
};

World::World(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>()) {
  impl_->scene.side = def.side;
  static_cast<WorldDef&>(impl_->options) = def;
  check(impl_->options);
}

World detail::world_of(const RunConfig& config) {
  auto impl = std::make_unique<World::Impl>();
  impl->scene = make_scene(config);
  for (const auto& t : impl->scene.types) impl->objects.emplace_back(t);
  impl->options = config;
  impl->from_scene = true;
  return World(std::move(impl));
}

World World::scene() { return detail::world_of(RunConfig{}); }

World World::scene(const std::string& scene_file) {
  RunConfig file;
  file.where = scene_file;
  return detail::world_of(run_config(file));
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

uint32_t World::add_body(const Object& object, const Pose& pose, const Eigen::Vector3d& velocity,
                         const Eigen::Vector3d& spin) {
  Impl& w = *impl_;
  uint32_t type = 0;
  while (type < w.objects.size() && w.objects[type].type() != object.type()) ++type;
  if (type == w.objects.size()) {
    w.objects.push_back(object);
    w.scene.types.push_back(object.type());
  }
  // The bodies the simulation holds now come first, so that the new one's index is theirs plus the ones added.
  if (w.sim && !w.stale) w.scene.bodies = w.sim->scene().bodies;
  Body b;
  b.type = type;
  b.pose = pose;
  b.velocity = velocity;
  b.spin = spin;
  w.scene.bodies.push_back(b);
  w.stale = true;
  return uint32_t(w.scene.bodies.size() - 1);
}

const FrameStats& World::step() {
  Impl& w = *impl_;
  Simulation& sim = w.simulation();
  w.last = sim.step();
  w.last.frame = w.frames++;
  if (w.rec) w.rec->frame(sim, w.last);
  return w.last;
}

size_t World::size() const { return bodies().size(); }
const std::vector<Body>& World::bodies() const {
  return impl_->sim && !impl_->stale ? impl_->sim->scene().bodies : impl_->scene.bodies;
}
const Object& World::object(uint32_t type) const { return impl_->objects.at(type); }
uint64_t World::frame() const { return impl_->frames; }

const std::vector<std::pair<uint32_t, uint32_t>>& World::pairs() const {
  static const std::vector<std::pair<uint32_t, uint32_t>> none;
  return impl_->sim ? impl_->sim->tested_pairs() : none;
}

const std::vector<Contacts>& World::contacts() const {
  static const std::vector<Contacts> none;
  return impl_->sim ? impl_->sim->results() : none;
}

const FrameStats& World::stats() const { return impl_->last; }

uint64_t World::state_hash() const {
  if (impl_->sim && !impl_->stale) return impl_->sim->state_hash();
  // Not stepped since bodies were added: the hash of the bodies as they are.
  return Simulation(impl_->scene, impl_->options).state_hash();
}

void World::record(const std::string& path) {
  stop_recording();
  const Simulation& sim = impl_->simulation();
  // The settings of the run as it is now: its device configuration and that device's clock among them.
  const std::string settings = impl_->from_scene ? record_settings(summary_of(impl_->options, sim)) : "{}";
  impl_->rec = std::make_unique<RecordWriter>(path, sim, settings);
}

void World::stop_recording() {
  if (impl_->rec) impl_->rec->close();
  impl_->rec.reset();
}

}  // namespace voxcd
