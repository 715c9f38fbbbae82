#include "voxcd/host/api/world.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "voxcd/host/api/access.h"
#include "voxcd/host/scene/record.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd {

namespace {

constexpr uint32_t kNowhere = std::numeric_limits<uint32_t>::max();

// A body's place in the world: its generation (the id's), whether a body holds it, and where its state is.
struct Slot {
  uint32_t generation = 0;  // of its body; once freed, of the next body to hold it
  bool live = false;
  bool enabled = true;
  uint64_t user_data = 0;
  uint32_t at = kNowhere;   // its index in the bodies taking part, while the layout is current and it is enabled
};

std::string vec_text(const Eigen::Vector3d& v) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.6g, %.6g, %.6g)", v.x(), v.y(), v.z());
  return b;
}

std::string body_name(BodyId id) { return "body " + std::to_string(id.index); }

// The key that orders pairs: by the first body's slot, then the second's.
uint64_t pair_key(const ContactEvent& e) { return uint64_t(e.a.index) << 32 | e.b.index; }

}  // namespace

struct World::Impl {
  Scene scene;                       // the types and the cube; its bodies: those taking part while no simulation is
  RunConfig options;                 // how it runs (the scene is `scene`)
  std::vector<Object> objects;       // in type order
  std::unique_ptr<Simulation> sim;   // holds the bodies taking part once made
  size_t sim_types = 0;              // the types its device holds
  uint64_t frames = 0;
  FrameStats last;
  bool from_scene = false;           // made from a scene: a recording's run settings are the run's (else "{}")
  std::unique_ptr<RecordWriter> rec;

  // The bodies: slots (a BodyId's index), the free ones (the last freed used first, as Box2D's id pool), and the
  // layout: the bodies taking part (live and enabled) in slot order, which the simulation holds. A change of who
  // takes part (add, remove, enable) parks every state in `held` (by slot) and makes the layout stale; the next step,
  // or a look at the bodies, lays them out again. Disabled bodies stay in `held`.
  std::vector<Slot> slots;
  std::vector<uint32_t> free;
  std::vector<Body> held;
  bool stale = false;
  std::vector<uint32_t> order;       // the slot of each body taking part
  std::vector<BodyId> ids;           // the id of each
  bool frame_current = false;        // the last step's pairs index the bodies as they are laid out now

  // Contact events: the last step's, and the pairs touching after it (sorted by pair_key) against which the next
  // step's are compared; a body removed or disabled ends its pairs there at once, for the next step's end events.
  std::vector<ContactEvent> begins, ends, ending;
  std::vector<ContactData> touching;
  std::vector<ContactEvent> touches;

  const std::vector<Body>& laid_out() const { return sim ? sim->scene().bodies : scene.bodies; }

  // Every state to `held`, by slot, before who takes part changes.
  void park() {
    if (stale) return;
    const std::vector<Body>& bodies = laid_out();
    if (held.size() < slots.size()) held.resize(slots.size());
    for (size_t i = 0; i < order.size(); ++i) {
      held[order[i]] = bodies[i];
      slots[order[i]].at = kNowhere;
    }
    stale = true;
    frame_current = false;
  }

  // The bodies taking part, in slot order, into the simulation (or `scene` until there is one).
  void lay_out() {
    if (!stale) return;
    order.clear();
    ids.clear();
    std::vector<Body> bodies;
    bool any_disabled = false;
    for (uint32_t s = 0; s < slots.size(); ++s) {
      Slot& sl = slots[s];
      if (!sl.live) continue;
      if (!sl.enabled) {
        any_disabled = true;
        continue;
      }
      sl.at = uint32_t(order.size());
      order.push_back(s);
      ids.push_back({s, sl.generation});
      bodies.push_back(held[s]);
    }
    if (!any_disabled) held = {};  // nothing left parked
    if (sim && sim_types == scene.types.size()) {
      sim->set_bodies(std::move(bodies));
    } else {
      sim.reset();  // a new type: the device is loaded anew
      scene.bodies = std::move(bodies);
    }
    stale = false;
  }

  Simulation& simulation() {
    lay_out();
    if (!sim) {
      Scene s;
      s.side = scene.side;
      s.types = scene.types;
      s.bodies = std::move(scene.bodies);
      scene.bodies.clear();
      sim = std::make_unique<Simulation>(std::move(s), options);
      sim_types = scene.types.size();
    }
    return *sim;
  }

  // The slot of a valid id; BodyError otherwise.
  uint32_t slot(BodyId id) const {
    if (id.index < slots.size() && slots[id.index].live && slots[id.index].generation == id.generation)
      return id.index;
    std::string why;
    if (id.is_null())
      why = "the null id (BodyId{}) names no body";
    else if (id.index >= slots.size() || id.generation >= slots[id.index].generation)
      why = "no body of this world has this id (generation " + std::to_string(id.generation) + ")";
    else
      why = "it was removed (generation " + std::to_string(id.generation) + "; the slot is at " +
            std::to_string(slots[id.index].generation) + ")";
    throw BodyError(id, "", body_name(id), why);
  }

  const Body& body(uint32_t s) const {
    return !stale && slots[s].enabled ? laid_out()[slots[s].at] : held[s];
  }
  // Body s to change between steps (the simulation flags it for the broadphase).
  Body& edit(uint32_t s) {
    if (stale || !slots[s].enabled) return held[s];
    return sim ? sim->edit_body(slots[s].at) : scene.bodies[slots[s].at];
  }

  void refuse_while_recording(const char* what) const {
    if (rec)
      throw RecordError("a recording holds the bodies it began with: " + std::string(what) +
                        " a body while recording is refused (stop_recording() first; a new recording may follow)");
  }

  // A body's pairs end now: they come out of the pairs touching, into the next step's end events.
  void end_pairs_of(uint32_t s) {
    auto keep = std::remove_if(touches.begin(), touches.end(), [&](const ContactEvent& e) {
      if (e.a.index != s && e.b.index != s) return false;
      ending.push_back(e);
      return true;
    });
    touches.erase(keep, touches.end());
  }

  void events();
};

namespace {

// BodyError naming `where` and `field` for a pose that is not finite or a rotation that is not a unit quaternion.
void check_pose(BodyId id, const std::string& where, const Pose& p) {
  const Eigen::Vector4d q = p.rotation.coeffs();
  if (!p.translation.allFinite())
    throw BodyError(id, "pose", where, "translation " + vec_text(p.translation) + " is not finite");
  if (!q.allFinite()) throw BodyError(id, "pose", where, "the rotation is not finite");
  const double n = q.norm();
  if (!(std::abs(n - 1) <= 1e-6)) {
    char b[64];
    std::snprintf(b, sizeof b, "%.9g", n);
    throw BodyError(id, "pose", where, std::string("the rotation is a quaternion of norm ") + b +
                                           ", not a unit quaternion");
  }
}

void check_motion(BodyId id, const std::string& where, const char* field, const Eigen::Vector3d& v, BodyKind kind) {
  if (!v.allFinite()) throw BodyError(id, field, where, vec_text(v) + " is not finite");
  if (kind == BodyKind::kStatic && !v.isZero(0))
    throw BodyError(id, field, where, vec_text(v) + " given to a static body, which never moves (make it kinematic)");
}

}  // namespace

void World::Impl::events() {
  // The pairs touching now, in pair order (the simulation's, by body index: by slot, as the layout is).
  touching.clear();
  const auto& pairs = sim->tested_pairs();
  const auto& results = sim->results();
  for (size_t q = 0; q < pairs.size(); ++q) {
    const PairResult& r = results[q];
    if (r.hits == 0) continue;
    ContactData d;
    d.a = ids[pairs[q].first];
    d.b = ids[pairs[q].second];
    d.user_data_a = slots[d.a.index].user_data;
    d.user_data_b = slots[d.b.index].user_data;
    d.hits = r.hits;
    d.contacts = r.contacts.size();
    d.pair = q;
    d.deepest.position.setZero();
    d.deepest.normal.setZero();
    for (const Contact& c : r.contacts) d.normal += c.a_in_b ? c.normal : -c.normal;
    if (d.normal.squaredNorm() >= 1e-24) d.normal.normalize();
    else d.normal.setZero();
    for (const Contact& c : r.contacts)
      if (&c == &r.contacts.front() || c.depth > d.deepest.depth) d.deepest = c;
    touching.push_back(d);
  }
  std::stable_sort(touching.begin(), touching.end(), [](const ContactData& x, const ContactData& y) {
    return std::make_pair(x.a.index, x.b.index) < std::make_pair(y.a.index, y.b.index);
  });
  // Against the pairs touching after the last step (less those ended by a removal since): begun and ended.
  begins.clear();
  ends = std::move(ending);
  ending.clear();
  std::vector<ContactEvent> now;
  now.reserve(touching.size());
  for (const ContactData& d : touching) now.push_back({d.a, d.b, d.user_data_a, d.user_data_b});
  size_t i = 0, j = 0;
  while (i < touches.size() || j < now.size()) {
    if (j == now.size() || (i < touches.size() && pair_key(touches[i]) < pair_key(now[j]))) {
      ContactEvent e = touches[i++];
      e.user_data_a = slots[e.a.index].user_data;  // both bodies are live: their user data now
      e.user_data_b = slots[e.b.index].user_data;
      ends.push_back(e);
    } else if (i == touches.size() || pair_key(now[j]) < pair_key(touches[i])) {
      begins.push_back(now[j++]);
    } else {
      ++i, ++j;
    }
  }
  touches = std::move(now);
}

World::World(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

World::World(const WorldDef& def) : impl_(std::make_unique<Impl>()) {
  impl_->scene.side = def.side;
  static_cast<WorldDef&>(impl_->options) = def;
  check(impl_->options);
}

World ApiAccess::world_of(const RunConfig& config) {
  auto impl = std::make_unique<World::Impl>();
  impl->scene = make_scene(config);
  for (const auto& t : impl->scene.types) impl->objects.push_back(ApiAccess::object_of(t));
  impl->options = config;
  impl->from_scene = true;
  const size_t n = impl->scene.bodies.size();
  impl->slots.resize(n);
  impl->order.resize(n);
  impl->ids.resize(n);
  for (uint32_t i = 0; i < n; ++i) {
    impl->slots[i].generation = 1;
    impl->slots[i].live = true;
    impl->slots[i].at = i;
    impl->order[i] = i;
    impl->ids[i] = {i, 1};
  }
  return World(std::move(impl));
}

World World::scene() { return ApiAccess::world_of(RunConfig{}); }

World World::scene(const std::string& scene_file) {
  RunConfig file;
  file.where = scene_file;
  return ApiAccess::world_of(run_config(file));
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

BodyId World::add(const BodyDef& def) {
  Impl& w = *impl_;
  const std::string name = "the new body (" + def.object.name() + ")";
  check_pose(BodyId{}, name, def.pose);
  check_motion(BodyId{}, name, "velocity", def.velocity, def.kind);
  check_motion(BodyId{}, name, "angular_velocity", def.angular_velocity, def.kind);
  w.refuse_while_recording("adding");
  uint32_t type = 0;
  const std::shared_ptr<const ObjectType>& def_type = ApiAccess::type_of(def.object);
  while (type < w.objects.size() && ApiAccess::type_of(w.objects[type]) != def_type) ++type;
  if (type == w.objects.size()) {
    w.objects.push_back(def.object);
    w.scene.types.push_back(def_type);
  }
  w.park();
  uint32_t s;
  if (w.free.empty()) {
    s = uint32_t(w.slots.size());
    w.slots.emplace_back();
    w.slots.back().generation = 1;
    w.held.resize(w.slots.size());
  } else {
    s = w.free.back();
    w.free.pop_back();
  }
  Slot& sl = w.slots[s];
  sl.live = true;
  sl.enabled = def.enabled;
  sl.user_data = def.user_data;
  sl.at = kNowhere;
  Body& b = w.held[s];
  b = Body();
  b.type = type;
  b.kind = def.kind;
  b.pose = def.pose;
  b.velocity = def.velocity;
  b.spin = def.angular_velocity;
  return {s, sl.generation};
}

uint32_t World::add_body(const Object& object, const Pose& pose, const Eigen::Vector3d& velocity,
                         const Eigen::Vector3d& spin) {
  BodyDef def(object);
  def.pose = pose;
  def.velocity = velocity;
  def.angular_velocity = spin;
  return add(def).index;
}

void World::remove(BodyId id) {
  Impl& w = *impl_;
  const uint32_t s = w.slot(id);
  w.refuse_while_recording("removing");
  w.park();
  w.end_pairs_of(s);
  Slot& sl = w.slots[s];
  sl.live = false;
  sl.enabled = true;
  sl.user_data = 0;
  ++sl.generation;
  w.free.push_back(s);
}

bool World::is_valid(BodyId id) const {
  const Impl& w = *impl_;
  return id.index < w.slots.size() && w.slots[id.index].live && w.slots[id.index].generation == id.generation;
}

Pose World::pose(BodyId id) const { return impl_->body(impl_->slot(id)).pose; }
Eigen::Vector3d World::velocity(BodyId id) const { return impl_->body(impl_->slot(id)).velocity; }
Eigen::Vector3d World::angular_velocity(BodyId id) const { return impl_->body(impl_->slot(id)).spin; }
uint64_t World::user_data(BodyId id) const { return impl_->slots[impl_->slot(id)].user_data; }
BodyKind World::kind(BodyId id) const { return impl_->body(impl_->slot(id)).kind; }
const Object& World::object(BodyId id) const { return impl_->objects.at(impl_->body(impl_->slot(id)).type); }
bool World::is_enabled(BodyId id) const { return impl_->slots[impl_->slot(id)].enabled; }

void World::set_pose(BodyId id, const Pose& pose) {
  const uint32_t s = impl_->slot(id);
  check_pose(id, body_name(id), pose);
  impl_->edit(s).pose = pose;
}

void World::set_velocity(BodyId id, const Eigen::Vector3d& velocity) {
  const uint32_t s = impl_->slot(id);
  check_motion(id, body_name(id), "velocity", velocity, impl_->body(s).kind);
  impl_->edit(s).velocity = velocity;
}

void World::set_angular_velocity(BodyId id, const Eigen::Vector3d& angular_velocity) {
  const uint32_t s = impl_->slot(id);
  check_motion(id, body_name(id), "angular_velocity", angular_velocity, impl_->body(s).kind);
  impl_->edit(s).spin = angular_velocity;
}

void World::set_user_data(BodyId id, uint64_t user_data) { impl_->slots[impl_->slot(id)].user_data = user_data; }

void World::set_enabled(BodyId id, bool enabled) {
  Impl& w = *impl_;
  const uint32_t s = w.slot(id);
  if (w.slots[s].enabled == enabled) return;
  w.refuse_while_recording(enabled ? "enabling" : "disabling");
  w.park();
  if (!enabled) w.end_pairs_of(s);
  w.slots[s].enabled = enabled;
}

const FrameStats& World::step() {
  Impl& w = *impl_;
  Simulation& sim = w.simulation();
  w.last = sim.step();
  w.last.frame = w.frames++;
  if (w.rec) w.rec->frame(sim, w.last);
  w.frame_current = true;
  w.events();
  return w.last;
}

const FrameStats& World::step(double dt) {
  if (!(std::isfinite(dt) && dt >= 0)) {
    char b[32];
    std::snprintf(b, sizeof b, "%g", dt);
    throw OptionError({"dt"}, std::string(b) + " is not a number of seconds (finite, at least 0)");
  }
  Impl& w = *impl_;
  Simulation& sim = w.simulation();
  w.last = sim.step(dt);
  w.last.frame = w.frames++;
  if (w.rec) w.rec->frame(sim, w.last);
  w.frame_current = true;
  w.events();
  return w.last;
}

const std::vector<ContactEvent>& World::begin_events() const { return impl_->begins; }
const std::vector<ContactEvent>& World::end_events() const { return impl_->ends; }
const std::vector<ContactData>& World::touching() const { return impl_->touching; }

size_t World::size() const {
  impl_->lay_out();
  return impl_->order.size();
}

const std::vector<Body>& World::bodies() const {
  impl_->lay_out();
  return impl_->laid_out();
}

const std::vector<BodyId>& World::ids() const {
  impl_->lay_out();
  return impl_->ids;
}

const Object& World::object(uint32_t type) const { return impl_->objects.at(type); }
uint64_t World::frame() const { return impl_->frames; }

const std::vector<std::pair<uint32_t, uint32_t>>& World::pairs() const {
  static const std::vector<std::pair<uint32_t, uint32_t>> none;
  return impl_->sim && impl_->frame_current ? impl_->sim->tested_pairs() : none;
}

const std::vector<Contacts>& World::contacts() const {
  static const std::vector<Contacts> none;
  return impl_->sim && impl_->frame_current ? impl_->sim->results() : none;
}

const FrameStats& World::stats() const { return impl_->last; }

uint64_t World::state_hash() const {
  impl_->lay_out();
  return voxcd::state_hash(impl_->laid_out());
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
