// A world a collision user drives (<voxcd/host/api/world.h>, docs/api.md): bodies added from BodyDefs and named by
// BodyIds that a removal retires, poses and velocities set and read, static and kinematic bodies, a step in seconds
// that is the frame step with every motion scaled, a world without walls or response that only detects and reports
// contact events, and errors that name the body.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <voxcd/voxcd.h>

#include "tests/host/test_util.h"
#include "voxcd/host/broadphase/broadphase.h"

namespace voxcd {
namespace {

const Object& sphere() {
  static const Object o = [] {
    ObjectDef def;
    def.voxel = 0.1;
    return Object::load("sphere", def);  // radius 1
  }();
  return o;
}

const Object& torus() {
  static const Object o = [] {
    ObjectDef def;
    def.voxel = 0.1;
    return Object::load("torus", def);
  }();
  return o;
}

BodyDef at(const Object& o, const Eigen::Vector3d& where, const Eigen::Vector3d& velocity = Eigen::Vector3d::Zero(),
           uint64_t user_data = 0) {
  BodyDef d(o);
  d.pose.translation = where;
  d.velocity = velocity;
  d.user_data = user_data;
  return d;
}

// A world that only detects and reports: no walls, no response.
WorldDef detect_only() {
  WorldDef def;
  def.walls = false;
  def.response = false;
  return def;
}

std::pair<uint32_t, uint32_t> key(BodyId a, BodyId b) { return {a.index, b.index}; }

TEST(World, IdsAreSlotsAndGenerationsAndARemovedIdStaysInvalid) {
  World w;
  const BodyId a = w.add(at(sphere(), {20, 50, 50}));
  const BodyId b = w.add(at(sphere(), {40, 50, 50}));
  const BodyId c = w.add(at(sphere(), {60, 50, 50}));
  EXPECT_EQ(a, (BodyId{0, 1}));
  EXPECT_EQ(b, (BodyId{1, 1}));
  EXPECT_EQ(c, (BodyId{2, 1}));
  EXPECT_TRUE(w.is_valid(b));
  EXPECT_FALSE(w.is_valid(BodyId{}));
  EXPECT_TRUE(BodyId{}.is_null());
  w.step();
  w.remove(b);
  EXPECT_FALSE(w.is_valid(b));
  EXPECT_EQ(w.size(), 2u);
  EXPECT_EQ(w.ids(), (std::vector<BodyId>{a, c}));
  // The slot is used again, with the next generation: the old id names nothing.
  const BodyId d = w.add(at(sphere(), {80, 50, 50}));
  EXPECT_EQ(d, (BodyId{1, 2}));
  EXPECT_FALSE(w.is_valid(b));
  EXPECT_TRUE(w.is_valid(d));
  EXPECT_EQ(w.pose(d).translation, Eigen::Vector3d(80, 50, 50));
  // bodies() and ids() in slot order.
  EXPECT_EQ(w.ids(), (std::vector<BodyId>{a, d, c}));
  EXPECT_EQ(w.bodies()[1].pose.translation, Eigen::Vector3d(80, 50, 50));
  EXPECT_EQ(w.bodies()[2].pose.translation, w.pose(c).translation);
  try {
    w.pose(b);
    ADD_FAILURE() << "a removed id was taken";
  } catch (const BodyError& e) {
    EXPECT_EQ(std::string(e.what()), "body 1: it was removed (generation 1; the slot is at 2)");
    EXPECT_EQ(e.where(), "body 1");
    EXPECT_EQ(e.body, b);
    EXPECT_EQ(e.field, "");
  }
  EXPECT_THROW(w.remove(b), BodyError);
  EXPECT_THROW(w.pose(BodyId{7, 1}), BodyError);
  try {
    w.velocity(BodyId{});
    ADD_FAILURE() << "the null id was taken";
  } catch (const Error& e) {  // the base catches it too
    EXPECT_NE(std::string(e.what()).find("the null id"), std::string::npos) << e.what();
  }
}

TEST(World, PosesVelocitiesAndUserDataAreSetAndRead) {
  World w;
  BodyDef def = at(torus(), {30, 40, 50}, {0.5, 0, 0}, 42);
  def.angular_velocity = {0, 0, 0.01};
  const BodyId id = w.add(def);
  EXPECT_EQ(w.user_data(id), 42u);
  EXPECT_EQ(w.kind(id), BodyKind::kDynamic);
  EXPECT_EQ(w.object(id).name(), torus().name());
  EXPECT_EQ(w.velocity(id), Eigen::Vector3d(0.5, 0, 0));
  EXPECT_EQ(w.angular_velocity(id), Eigen::Vector3d(0, 0, 0.01));
  w.step();
  EXPECT_EQ(w.pose(id).translation, Eigen::Vector3d(30.5, 40, 50));
  // Set between steps: the next step starts from them (a teleport).
  Pose p;
  p.translation = {10, 10, 10};
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  w.set_pose(id, p);
  w.set_velocity(id, {0, 0.25, 0});
  w.set_angular_velocity(id, {0, 0, 0});
  w.set_user_data(id, 7);
  EXPECT_EQ(w.pose(id).translation, p.translation);
  EXPECT_EQ(w.pose(id).rotation.coeffs(), p.rotation.coeffs());
  EXPECT_EQ(w.user_data(id), 7u);
  w.step();
  EXPECT_EQ(w.pose(id).translation, Eigen::Vector3d(10, 10.25, 10));
  EXPECT_EQ(w.velocity(id), Eigen::Vector3d(0, 0.25, 0));
  EXPECT_EQ(w.bodies()[0].velocity, Eigen::Vector3d(0, 0.25, 0));
}

TEST(World, StaticBodiesNeverMoveAndTheResponsePushesOnlyDynamicOnes) {
  World w;
  BodyDef s = at(sphere(), {50, 50, 50});
  s.kind = BodyKind::kStatic;
  s.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const BodyId is = w.add(s);
  BodyDef s2 = s;  // overlapping the first: two static bodies are never tested
  s2.pose.translation = {51, 50, 50};
  const BodyId is2 = w.add(s2);
  const BodyId id = w.add(at(sphere(), {46, 50, 50}, {0.25, 0, 0}));
  const Pose before = w.pose(is);
  uint64_t responses = 0;
  for (int f = 0; f < 30; ++f) {
    responses += w.step().responses;
    for (const auto& p : w.pairs()) EXPECT_FALSE(w.ids()[p.first] == is && w.ids()[p.second] == is2);
    for (const ContactData& d : w.touching()) EXPECT_NE(key(d.a, d.b), key(is, is2));
  }
  EXPECT_GT(responses, 0u);
  EXPECT_EQ(w.pose(is).translation, before.translation);
  EXPECT_EQ(w.pose(is).rotation.coeffs(), before.rotation.coeffs());
  EXPECT_EQ(w.velocity(is), Eigen::Vector3d::Zero());
  // The dynamic body bounced back off it, its speed kept (a reflection).
  EXPECT_LT(w.velocity(id).x(), 0);
  EXPECT_NEAR(w.velocity(id).norm(), 0.25, 1e-12);
  EXPECT_LT(w.pose(id).translation.x(), 48);
  EXPECT_EQ(w.kind(is), BodyKind::kStatic);

  // A kinematic body moves by its velocity alone and pushes a dynamic one.
  World k;
  BodyDef kd = at(sphere(), {46, 50, 50}, {0.25, 0, 0});
  kd.kind = BodyKind::kKinematic;
  const BodyId ik = k.add(kd);
  const BodyId id2 = k.add(at(sphere(), {50, 50.2, 50}));
  for (int f = 0; f < 20; ++f) k.step();
  EXPECT_EQ(k.velocity(ik), Eigen::Vector3d(0.25, 0, 0));
  EXPECT_EQ(k.pose(ik).translation.x(), 46 + 20 * 0.25);
  EXPECT_GT(k.velocity(id2).x(), 0.3);  // about 0.5: the relative velocity reflected
}

// The bodies of the step test: near a wall, and pairs that meet, turning.
void fill(World& w, double scale) {
  const std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> bodies = {
      {{2.5, 10, 10}, {-0.3, 0.05, 0}}, {{8, 10, 10}, {0.2, 0, 0.01}}, {{11, 10.5, 10}, {-0.2, 0, 0}},
      {{14, 14, 14}, {0.1, 0.12, -0.07}}, {{16, 15, 14}, {-0.1, 0, 0}}};
  for (size_t i = 0; i < bodies.size(); ++i) {
    BodyDef d = at(i % 2 ? torus() : sphere(), bodies[i].first, bodies[i].second * scale);
    d.angular_velocity = Eigen::Vector3d(0.01, 0.02 * double(i), -0.015) * scale;
    w.add(d);
  }
}

TEST(World, AStepOfDtSecondsIsTheFrameStepWithEveryMotionScaled) {
  // dt a power of two: velocities per second are those per frame times 64, exactly, and every motion of a step is
  // exactly a frame's. Bit for bit: poses, the contacts' outcomes, wall bounces and responses.
  WorldDef def;
  def.side = 20;
  World frames(def), seconds(def);
  fill(frames, 1);
  fill(seconds, 64);
  uint64_t touching = 0, walls = 0, responses = 0;
  for (int f = 0; f < 80; ++f) {
    const FrameStats a = frames.step();
    const FrameStats b = seconds.step(1.0 / 64);
    ASSERT_EQ(a.touching, b.touching) << "frame " << f;
    ASSERT_EQ(a.responses, b.responses) << "frame " << f;
    ASSERT_EQ(a.wall_hits, b.wall_hits) << "frame " << f;
    ASSERT_EQ(a.hits, b.hits) << "frame " << f;
    touching += a.touching, walls += a.wall_hits, responses += a.responses;
  }
  EXPECT_GT(touching, 0u);
  EXPECT_GT(walls, 0u);
  EXPECT_GT(responses, 0u);
  for (size_t i = 0; i < frames.size(); ++i) {
    const Body &a = frames.bodies()[i], &b = seconds.bodies()[i];
    EXPECT_EQ(a.pose.translation, b.pose.translation) << i;
    EXPECT_EQ(a.pose.rotation.coeffs(), b.pose.rotation.coeffs()) << i;
    EXPECT_EQ(a.velocity * 64, b.velocity) << i;
    EXPECT_EQ(a.spin * 64, b.spin) << i;
  }
  // Ten steps of a tenth of a second move a body without contacts as far as a frame step moves it at the same
  // velocity per frame (to rounding): a frame step is a step of one unit of time.
  World one, tenth;
  one.add(at(sphere(), {30, 30, 30}, {0.7, -0.2, 0.3}));
  tenth.add(at(sphere(), {30, 30, 30}, {0.7, -0.2, 0.3}));
  for (int f = 0; f < 3; ++f) {
    one.step();
    for (int k = 0; k < 10; ++k) tenth.step(0.1);
  }
  EXPECT_TRUE(one.bodies()[0].pose.translation.isApprox(tenth.bodies()[0].pose.translation, 1e-12))
      << one.bodies()[0].pose.translation.transpose() << " against " << tenth.bodies()[0].pose.translation.transpose();
  // A step of no time moves nothing and finds the contacts where the bodies are.
  World still;
  still.add(at(sphere(), {50, 50, 50}, {1, 0, 0}));
  still.add(at(sphere(), {51, 50, 50}, {-1, 0, 0}));
  still.step(0);
  EXPECT_EQ(still.pose(still.ids()[0]).translation, Eigen::Vector3d(50, 50, 50));
  EXPECT_EQ(still.touching().size(), 1u);
}

TEST(World, AStepOfDtSecondsWithContinuousCollisionIsTheFrameStepScaled) {
  ObjectDef od;
  od.voxel = 0.1;
  od.distance_bits = 8;
  const Object ball = Object::load("sphere", od);
  WorldDef def;
  def.side = 12;
  def.distance_bits = 8;
  def.ccd = true;
  World frames(def), seconds(def);
  for (World* w : {&frames, &seconds}) {
    const double s = w == &seconds ? 32 : 1;
    w->add(at(ball, {3, 6, 6}, Eigen::Vector3d(1.5, 0, 0) * s));  // faster than its size a frame: ccd stops it
    w->add(at(ball, {9, 6.3, 6}, Eigen::Vector3d(-1.5, 0, 0) * s));
    w->add(at(ball, {6, 2, 6}, Eigen::Vector3d(0, -0.8, 0) * s));
  }
  uint64_t toi = 0;
  for (int f = 0; f < 12; ++f) {
    const FrameStats a = frames.step();
    const FrameStats b = seconds.step(1.0 / 32);
    ASSERT_EQ(a.ccd_toi, b.ccd_toi) << "frame " << f;
    ASSERT_EQ(a.ccd_iterations, b.ccd_iterations) << "frame " << f;
    toi += a.ccd_toi;
  }
  EXPECT_GT(toi, 0u);
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames.bodies()[i].pose.translation, seconds.bodies()[i].pose.translation) << i;
    EXPECT_EQ(frames.bodies()[i].velocity * 32, seconds.bodies()[i].velocity) << i;
  }
}

TEST(World, ADetectOnlyWorldReportsBeginAndEndEventsAndNeverChangesVelocities) {
  World w(detect_only());
  const Eigen::Vector3d va(0.5, 0, 0), vb(-0.5, 0, 0);
  const BodyId a = w.add(at(sphere(), {44, 50, 50}, va, 100));
  const BodyId b = w.add(at(sphere(), {56, 51, 50}, vb, 200));  // passes A one radius aside: always some overlap
  std::set<std::pair<uint32_t, uint32_t>> now;                   // the pairs touching, from the events alone
  int begins = 0, ends = 0, touching_frames = 0;
  for (int f = 0; f < 30; ++f) {
    const FrameStats st = w.step();
    EXPECT_EQ(st.responses, 0u);
    EXPECT_EQ(st.wall_hits, 0u);
    EXPECT_EQ(w.velocity(a), va);
    EXPECT_EQ(w.velocity(b), vb);
    for (const ContactEvent& e : w.begin_events()) {
      EXPECT_EQ(key(e.a, e.b), key(a, b));
      EXPECT_EQ(e.user_data_a, 100u);
      EXPECT_EQ(e.user_data_b, 200u);
      EXPECT_TRUE(now.insert(key(e.a, e.b)).second);
      ++begins;
    }
    for (const ContactEvent& e : w.end_events()) {
      EXPECT_EQ(e.a, a);
      EXPECT_EQ(e.b, b);
      EXPECT_EQ(e.user_data_b, 200u);
      EXPECT_EQ(now.erase(key(e.a, e.b)), 1u);
      ++ends;
    }
    std::set<std::pair<uint32_t, uint32_t>> touching;
    for (const ContactData& d : w.touching()) {
      touching.insert(key(d.a, d.b));
      EXPECT_GT(d.hits, 0u);
      EXPECT_GT(d.contacts, 0u);
      EXPECT_EQ(d.user_data_a, 100u);
      EXPECT_NEAR(d.normal.norm(), 1, 1e-12);
      EXPECT_GT(d.deepest.depth, 0);
      EXPECT_EQ(d.deepest.pair, d.pair);
      EXPECT_EQ(w.contacts()[d.pair].hits, d.hits);
      EXPECT_EQ(w.ids()[w.pairs()[d.pair].first], d.a);
      // From A towards B: along +x while A is behind B.
      if (w.pose(a).translation.x() < w.pose(b).translation.x() - 0.5) {
        EXPECT_GT(d.normal.x(), 0.3);
      }
      ++touching_frames;
    }
    EXPECT_EQ(touching, now) << "frame " << f;
  }
  EXPECT_EQ(begins, 1);
  EXPECT_EQ(ends, 1);
  EXPECT_GT(touching_frames, 2);
  EXPECT_TRUE(w.touching().empty());
  // They passed through each other.
  EXPECT_GT(w.pose(a).translation.x(), w.pose(b).translation.x());
}

TEST(World, RemovingOrDisablingABodyEndsItsContacts) {
  World w(detect_only());
  const BodyId a = w.add(at(sphere(), {50, 50, 50}, Eigen::Vector3d::Zero(), 1));
  const BodyId b = w.add(at(sphere(), {51, 50, 50}, Eigen::Vector3d::Zero(), 2));
  w.step();
  ASSERT_EQ(w.begin_events().size(), 1u);
  w.remove(b);
  EXPECT_TRUE(w.pairs().empty());  // they indexed the bodies before the removal
  EXPECT_TRUE(w.contacts().empty());
  w.step();
  ASSERT_EQ(w.end_events().size(), 1u);
  EXPECT_EQ(w.end_events()[0].a, a);
  EXPECT_EQ(w.end_events()[0].b, b);
  EXPECT_EQ(w.end_events()[0].user_data_b, 2u);
  EXPECT_TRUE(w.begin_events().empty());
  EXPECT_TRUE(w.touching().empty());
  w.step();
  EXPECT_TRUE(w.end_events().empty());
  // Disabled: out of the steps (its pairs end), its state and id kept; enabled again, its pairs begin again.
  const BodyId c = w.add(at(sphere(), {50, 51, 50}, Eigen::Vector3d::Zero(), 3));
  w.step();
  ASSERT_EQ(w.begin_events().size(), 1u);
  EXPECT_EQ(w.begin_events()[0].b, c);
  w.set_enabled(c, false);
  EXPECT_FALSE(w.is_enabled(c));
  EXPECT_EQ(w.size(), 1u);
  w.step();
  ASSERT_EQ(w.end_events().size(), 1u);
  EXPECT_EQ(w.end_events()[0].b, c);
  EXPECT_EQ(w.pose(c).translation, Eigen::Vector3d(50, 51, 50));
  w.set_pose(c, w.pose(c));
  w.step();
  EXPECT_TRUE(w.begin_events().empty());
  w.set_enabled(c, true);
  w.step();
  ASSERT_EQ(w.begin_events().size(), 1u);
  EXPECT_EQ(w.size(), 2u);
  EXPECT_EQ(w.ids(), (std::vector<BodyId>{a, c}));
}

TEST(World, WithoutWallsABodyLeavesTheCube) {
  for (const bool walls : {true, false}) {
    WorldDef def;
    def.side = 10;
    def.walls = walls;
    World w(def);
    const BodyId id = w.add(at(sphere(), {5, 5, 5}, {1, 0, 0}));
    uint64_t bounces = 0;
    for (int f = 0; f < 20; ++f) bounces += w.step().wall_hits;
    if (walls) {
      EXPECT_GT(bounces, 0u);
      EXPECT_LE(w.pose(id).translation.x(), 10);
    } else {
      EXPECT_EQ(bounces, 0u);
      EXPECT_EQ(w.pose(id).translation.x(), 25);
    }
  }
  // Outside the cube every broadphase finds the pairs: one body catches up with another at x = 13, beyond the side.
  uint64_t hash = 0;
  for (const std::string& broadphase : broadphase_names()) {
    WorldDef def;
    def.side = 10;
    def.walls = false;
    def.broadphase = broadphase;
    World w(def);
    w.add(at(sphere(), {5, 5, 5}, {1, 0, 0}));
    w.add(at(sphere(), {9, 5.5, 5}, {0.5, 0, 0}));
    w.add(at(sphere(), {5, 5, 5.2}, {-1, -1, 0}));
    uint64_t touching = 0, begun = 0;
    for (int f = 0; f < 40; ++f) {
      touching += w.step().touching;
      begun += w.begin_events().size();
    }
    EXPECT_GT(touching, 0u) << broadphase;
    EXPECT_EQ(begun, 1u) << broadphase;
    if (hash == 0) hash = w.state_hash();
    EXPECT_EQ(w.state_hash(), hash) << broadphase;
  }
}

TEST(World, BadInputNamesTheBodyAndTheValue) {
  World w;
  const BodyId a = w.add(at(sphere(), {20, 20, 20}));
  const BodyId b = w.add(at(sphere(), {40, 20, 20}));
  const BodyId c = w.add(at(sphere(), {60, 20, 20}));
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  try {
    w.set_velocity(c, {inf, 0, 0});
    ADD_FAILURE() << "an infinite velocity was taken";
  } catch (const BodyError& e) {
    EXPECT_EQ(std::string(e.what()), "body 2: velocity: (inf, 0, 0) is not finite");
    EXPECT_EQ(e.where(), "body 2");
    EXPECT_EQ(e.body, c);
    EXPECT_EQ(e.field, "velocity");
  }
  try {
    w.set_angular_velocity(b, {0, nan, 0});
    ADD_FAILURE() << "a NaN angular velocity was taken";
  } catch (const BodyError& e) {
    EXPECT_EQ(std::string(e.what()), "body 1: angular_velocity: (0, nan, 0) is not finite");
  }
  Pose p;
  p.translation = {nan, 1, 2};
  try {
    w.set_pose(a, p);
    ADD_FAILURE() << "a NaN pose was taken";
  } catch (const BodyError& e) {
    EXPECT_EQ(std::string(e.what()), "body 0: pose: translation (nan, 1, 2) is not finite");
    EXPECT_EQ(e.field, "pose");
  }
  BodyDef d = at(sphere(), {1, 2, 3});
  d.pose.rotation.coeffs() << 0, 0, 0, 2;
  try {
    w.add(d);
    ADD_FAILURE() << "a rotation that is not a unit quaternion was taken";
  } catch (const BodyError& e) {
    EXPECT_NE(std::string(e.what()).find("the new body ("), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("pose: the rotation is a quaternion of norm 2, not a unit quaternion"),
              std::string::npos)
        << e.what();
    EXPECT_TRUE(e.body.is_null());
  }
  BodyDef s = at(sphere(), {1, 2, 3}, {0, 0, 1});
  s.kind = BodyKind::kStatic;
  try {
    w.add(s);
    ADD_FAILURE() << "a static body with a velocity was taken";
  } catch (const BodyError& e) {
    EXPECT_NE(std::string(e.what()).find("velocity: (0, 0, 1) given to a static body"), std::string::npos) << e.what();
  }
  s.velocity.setZero();
  const BodyId is = w.add(s);
  EXPECT_THROW(w.set_velocity(is, {1, 0, 0}), BodyError);
  w.set_velocity(is, {0, 0, 0});  // zero is its velocity
  // The state is unchanged by the calls refused, and so is the world's size.
  EXPECT_EQ(w.size(), 4u);
  EXPECT_EQ(w.velocity(c), Eigen::Vector3d::Zero());
  // A step that is not a number of seconds; settings that exclude each other.
  for (const double dt : {-1.0, nan, inf}) {
    try {
      w.step(dt);
      ADD_FAILURE() << "dt " << dt << " was taken";
    } catch (const OptionError& e) {
      EXPECT_EQ(e.options, std::vector<std::string>{"dt"});
    }
  }
  WorldDef ccd;
  ccd.distance_bits = 8;
  ccd.ccd = true;
  ccd.response = false;
  try {
    World bad(ccd);
    ADD_FAILURE() << "continuous collision without the response was taken";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.options, (std::vector<std::string>{"ccd", "response"}));
  }
}

TEST(World, ARecordingHoldsTheBodiesItBeganWith) {
  World w;
  const BodyId a = w.add(at(sphere(), {20, 20, 20}, {0.1, 0, 0}));
  const std::string path = test::tmp_path("world_bodies.vxr");
  w.record(path);
  w.step();
  EXPECT_THROW(w.add(at(sphere(), {40, 20, 20})), RecordError);
  EXPECT_THROW(w.remove(a), RecordError);
  EXPECT_THROW(w.set_enabled(a, false), RecordError);
  w.set_pose(a, w.pose(a));  // poses and velocities may change
  w.step();
  w.stop_recording();
  w.add(at(sphere(), {40, 20, 20}));
  w.step();
  EXPECT_EQ(w.size(), 2u);
  std::remove(path.c_str());
}

TEST(World, TheFormBeforeBodyDefKeepsWorking) {
  World old_form, new_form;
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
  Pose p;
  p.translation = {40, 50, 50};
  EXPECT_EQ(old_form.add_body(torus(), p, Eigen::Vector3d(0.25, 0, 0), Eigen::Vector3d(0, 0.01, 0)), 0u);
  p.translation = {46, 50, 50};
  EXPECT_EQ(old_form.add_body(sphere(), p, Eigen::Vector3d(-0.25, 0, 0)), 1u);
#pragma GCC diagnostic pop
  BodyDef t = at(torus(), {40, 50, 50}, {0.25, 0, 0});
  t.angular_velocity = {0, 0.01, 0};
  new_form.add(t);
  new_form.add(at(sphere(), {46, 50, 50}, {-0.25, 0, 0}));
  for (int f = 0; f < 30; ++f) EXPECT_EQ(old_form.step().touching, new_form.step().touching);
  EXPECT_EQ(old_form.state_hash(), new_form.state_hash());
}

TEST(World, ASceneWorldsBodiesHaveIds) {
  World w = World::scene();
  ASSERT_EQ(w.ids().size(), 64u);
  EXPECT_EQ(w.ids()[3], (BodyId{3, 1}));
  EXPECT_EQ(w.pose(w.ids()[3]).translation, w.bodies()[3].pose.translation);
  for (int f = 0; f < 5; ++f) w.step();
  const BodyId gone = w.ids()[0];
  w.remove(gone);
  const std::vector<Body> kept(w.bodies().begin(), w.bodies().end());
  w.step();
  EXPECT_EQ(w.size(), 63u);
  EXPECT_FALSE(w.is_valid(gone));
  EXPECT_NE(w.bodies()[0].pose.translation, kept[0].pose.translation);  // the first body now is the old second
}

}  // namespace
}  // namespace voxcd
