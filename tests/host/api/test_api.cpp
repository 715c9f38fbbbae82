// The public API (<voxcd/voxcd.h>, docs/api.md): objects from files, shapes, arrays and meshes; collide() against
// the collider it stands for; objects of very different voxels; a world stepped by its caller against `voxcd
// simulate`'s run; errors that say what to change.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include <voxcd/voxcd.h>

#include "tests/defects.h"
#include "tests/host/test_util.h"
#include "voxcd/host/api/access.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/scene/simulate.h"

namespace voxcd {
namespace {

// The names the API's structs take, from the umbrella alone: each shape loads, each broadphase steps a world, each
// mode parses (ref/types.h), and the defaults are among them.
TEST(Api, NamesOfShapesBroadphasesAndModes) {
  const std::vector<std::string> shapes = shape_names(), broadphases = broadphase_names();
  ASSERT_FALSE(shapes.empty());
  EXPECT_NE(std::find(shapes.begin(), shapes.end(), "torus"), shapes.end());
  ObjectDef coarse;
  coarse.resolution = 8;
  for (const std::string& s : shapes) EXPECT_GT(Object::load(s, coarse).shell_count(), 0u) << s;
  EXPECT_NE(std::find(broadphases.begin(), broadphases.end(), WorldDef{}.broadphase), broadphases.end());
  for (const std::string& b : broadphases) {
    WorldDef def;
    def.broadphase = b;
    World w(def);
    for (double x : {40.0, 41.0}) {
      BodyDef body(Object::load("cube", coarse));
      body.pose.translation = {x, 50, 50};
      w.add(body);
    }
    EXPECT_EQ(w.step().touching, 1u) << b;
  }
  EXPECT_EQ(mode_names(), (std::vector<std::string>{"ALL", "FIRST", "COUNT"}));
  for (const std::string& m : mode_names()) EXPECT_TRUE(parse_mode(m).has_value()) << m;
}

TEST(Api, ObjectsFromShapesFilesArraysAndMeshes) {
  ObjectDef def;
  def.voxel = 0.1;
  const Object torus = Object::load("torus", def);
  EXPECT_EQ(torus.voxel(), 0.1);
  EXPECT_GT(torus.shell_count(), 0u);
  // The count and the points (rows of the object's frame, unit normals), as Python's shell_count and shell_points.
  const auto points = torus.shell_points();
  const auto normals = torus.shell_normals();
  ASSERT_EQ(size_t(points.rows()), torus.shell_count());
  ASSERT_EQ(size_t(normals.rows()), torus.shell_count());
  EXPECT_EQ(Eigen::Vector3d(points.row(0).transpose()), ApiAccess::type_of(torus)->shell().points[0]);
  EXPECT_NEAR(normals.rowwise().norm().minCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(normals.rowwise().norm().maxCoeff(), 1.0, 1e-12);
  EXPECT_TRUE(torus.report().closed);
  // By default 32 voxels along the longest side.
  const Object cube = Object::load("cube");
  EXPECT_NEAR(cube.voxel(), 2.0 / 32, 1e-12);
  // An object file brings its voxel; arrays and a Mesh give the same object as the mesh itself.
  const std::string path = test::tmp_path("api_torus.vxo");
  torus.save(path);
  const Object back = Object::load(path);
  EXPECT_EQ(back.voxel(), 0.1);
  EXPECT_EQ(back.dims(), torus.dims());
  const Mesh box = make_box({0, 0, 0}, {1, 2, 3});
  std::vector<double> xyz;
  for (const auto& v : box.vertices) xyz.insert(xyz.end(), {v.x(), v.y(), v.z()});
  std::vector<uint32_t> tri;
  for (const auto& t : box.triangles) tri.insert(tri.end(), t.begin(), t.end());
  const Object from_arrays = Object::from_arrays(xyz.data(), box.vertices.size(), tri.data(), box.size());
  const Object from_mesh = Object::from_mesh(box);
  EXPECT_EQ(from_arrays.dims(), from_mesh.dims());
  EXPECT_EQ(ApiAccess::type_of(from_arrays)->voxmap().words(), ApiAccess::type_of(from_mesh)->voxmap().words());
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> V(box.vertices.size(), 3);
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> F(box.size(), 3);
  for (size_t i = 0; i < box.vertices.size(); ++i) V.row(Eigen::Index(i)) = box.vertices[i].transpose();
  for (size_t t = 0; t < box.size(); ++t)
    for (int k = 0; k < 3; ++k) F(Eigen::Index(t), k) = int(box.triangles[t][size_t(k)]);
  EXPECT_EQ(ApiAccess::type_of(Object::from_arrays(V, F))->voxmap().words(),
            ApiAccess::type_of(from_mesh)->voxmap().words());
  // Bad input says what and where.
  tri[4] = 99;
  try {
    Object::from_arrays(xyz.data(), box.vertices.size(), tri.data(), box.size());
    ADD_FAILURE() << "an index out of range was taken";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1 has vertex index 99 out of range (8 vertices)"), std::string::npos)
        << e.what();
  }
  F(0, 0) = -1;
  EXPECT_THROW(Object::from_arrays(V, F), MeshError);
  EXPECT_THROW(Object::load("no/such/mesh.stl"), MeshError);
  std::remove(path.c_str());
}

TEST(Api, CollideIsTheCollidersQuery) {
  ObjectDef def;
  def.voxel = 0.08;
  const Object a = Object::load("torus", def), b = Object::load("polytope36", def);
  Pose pb;
  pb.translation = {1.0, 0.2, 0};
  pb.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  const Contacts c = collide(a, Pose{}, b, pb);
  ASSERT_GT(c.hits, 0u);
  // The same query through the collider the API stands for.
  const DeviceConfig cfg = device_config_for("cpu", 4, {ApiAccess::type_of(a).get(), ApiAccess::type_of(b).get()});
  PairCollider col(make_device("cpu", cfg), {ApiAccess::type_of(a), ApiAccess::type_of(b)});
  PairRequest r;
  r.a = 0, r.b = 1, r.pose_b = pb;
  PairOptions o;
  o.both_directions = true;
  const PairResult want = col.collide({r}, o).at(0);
  ASSERT_EQ(c.contacts.size(), want.contacts.size());
  EXPECT_EQ(c.hits, want.hits);
  for (size_t i = 0; i < want.contacts.size(); ++i) EXPECT_EQ(c.contacts[i].position, want.contacts[i].position);
  // Modes, and a batch equal to one pose at a time.
  CollideOptions count;
  count.mode = Mode::Count;
  EXPECT_EQ(collide(a, Pose{}, b, pb, count).hits, c.hits);
  EXPECT_TRUE(collide(a, Pose{}, b, pb, count).contacts.empty());
  Pose far;
  far.translation = {10, 0, 0};
  const std::vector<Contacts> batch = collide(a, b, {{Pose{}, pb}, {Pose{}, far}});
  ASSERT_EQ(batch.size(), 2u);
  EXPECT_EQ(batch[0].contacts.size(), c.contacts.size());
  EXPECT_EQ(batch[1].hits, 0u);
}

TEST(Api, SparseObjectsCollideAsTheirDenseForms) {
  ObjectDef def;
  def.voxel = 0.08;
  const Object a = Object::load("torus", def), b = Object::load("polytope36", def);
  def.storage = ObjectStorage::kSparse;
  const Object sa = Object::load("torus", def), sb = Object::load("polytope36", def);
  ASSERT_TRUE(ApiAccess::type_of(sa)->object.voxmap_sparse() && ApiAccess::type_of(sa)->object.shell_sparse());
  Pose pb;
  pb.translation = {1.0, 0.2, 0};
  pb.rotation = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized());
  const Contacts want = collide(a, Pose{}, b, pb), got = collide(sa, Pose{}, sb, pb);
  ASSERT_GT(want.hits, 0u);
  EXPECT_EQ(got.hits, want.hits);
  // The same positions; a sparse shell's blocks run brick by brick, so in another order.
  std::vector<std::array<double, 3>> pw, pg;
  for (const Contact& k : want.contacts) pw.push_back({k.position.x(), k.position.y(), k.position.z()});
  for (const Contact& k : got.contacts) pg.push_back({k.position.x(), k.position.y(), k.position.z()});
  std::sort(pw.begin(), pw.end());
  std::sort(pg.begin(), pg.end());
  EXPECT_EQ(pg, pw);
}

TEST(Api, ObjectsOfVeryDifferentVoxelsShareADevice) {
  // A small voxel for one, a voxel 5 times larger for the other: M's entries reach 0.2 / 0.04 / sqrt(2) = 3.5.
  ObjectDef fine, coarse;
  fine.voxel = 0.04;
  coarse.voxel = 0.2;
  const Object a = Object::load("torus", coarse), b = Object::load("sphere", fine);
  Pose pb;
  pb.translation = {1.0, 0, 0};
  const Contacts c = collide(a, Pose{}, b, pb);
  EXPECT_GT(c.hits, 0u);
  double ratio = 0;
  EXPECT_GT(matrix_width_for(DeviceConfig{}, {ApiAccess::type_of(a).get(), ApiAccess::type_of(b).get()}, &ratio), 18);
  EXPECT_GT(ratio, 3.0);
  // The rtl backend's models have MW 18: the error says what to change.
  try {
    device_config_for("rtl", 4, {ApiAccess::type_of(a).get(), ApiAccess::type_of(b).get()});
    ADD_FAILURE() << "the rtl backend took a matrix it cannot hold";
  } catch (const CapacityError& e) {
    EXPECT_NE(std::string(e.what()).find("Voxelise the objects at voxels within a factor of 2.83"), std::string::npos)
        << e.what();
  }
}

TEST(Api, AWorldSteppedByItsCallerIsTheToolsRun) {
  // The built-in scene stepped 100 frames: the state hash of `voxcd simulate --frames 100`.
  RunConfig c;
  c.frames = 100;
  const SimulationSummary s = simulate(c);
  World w = World::scene();
  for (int f = 0; f < 100; ++f) w.step();
  EXPECT_EQ(w.state_hash(), s.state_hash);
  EXPECT_EQ(w.frame(), 100u);
  EXPECT_EQ(w.size(), 64u);
  // A scene file, as `voxcd simulate small.json --frames 30` runs it (its own settings; frames given by the caller).
  RunConfig given;
  given.where = VOXCD_SCENES_DIR "/small.json";
  RunConfig file = run_config(given);
  file.frames = 30;
  const SimulationSummary fs = simulate(file);
  World from_file = World::scene(VOXCD_SCENES_DIR "/small.json");
  for (int k = 0; k < 30; ++k) from_file.step();
  EXPECT_EQ(from_file.state_hash(), fs.state_hash);
  EXPECT_EQ(from_file.size(), fs.config.objects());
  EXPECT_NE(from_file.state_hash(), World::scene().state_hash());
  // A file that cannot be read is an error naming it.
  try {
    World::scene("no/such/scene.json");
    ADD_FAILURE() << "no error for a missing scene file";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("no/such/scene.json"), std::string::npos) << e.what();
  }
  // A world of one's own: two bodies that meet.
  World own;
  ObjectDef def;
  def.voxel = 0.1;
  const Object torus = Object::load("torus", def), cube = Object::load("cube", def);
  BodyDef a(torus), b(cube);
  a.pose.translation = {40, 50, 50};
  a.velocity = {0.25, 0, 0};
  const BodyId ia = own.add(a);
  EXPECT_EQ(ia, (BodyId{0, 1}));
  b.pose.translation = {46, 50, 50};
  b.velocity = {-0.25, 0, 0};
  const BodyId ib = own.add(b);
  EXPECT_EQ(ib, (BodyId{1, 1}));
  uint64_t touching = 0;
  for (int f = 0; f < 30; ++f) touching += own.step().touching;
  EXPECT_GT(touching, 0u);
  EXPECT_NE(own.pose(ia).translation.x(), 40.0);
  // A body added after frames joins the next; the others keep their state.
  const Eigen::Vector3d before = own.pose(ib).translation;
  BodyDef later(torus);
  later.pose.translation = {80, 80, 80};
  EXPECT_EQ(own.add(later), (BodyId{2, 1}));
  EXPECT_EQ(own.pose(ib).translation, before);
  EXPECT_EQ(own.bodies()[1].pose.translation, before);
  own.step();
  EXPECT_EQ(own.size(), 3u);
  // Recording from the API.
  const std::string path = test::tmp_path("api_world.vxr");
  own.record(path);
  for (int f = 0; f < 3; ++f) own.step();
  own.stop_recording();
  std::FILE* fp = std::fopen(path.c_str(), "rb");
  ASSERT_NE(fp, nullptr);
  std::fclose(fp);
  std::remove(path.c_str());
}

// One default for one concept: every door tests both directions unless told otherwise; only the paper's built-in
// scene keeps one direction, so `voxcd simulate`'s runs and state hashes stay the paper's.
TEST(Api, BothDirectionsIsTheDefaultEverywhereButThePapersScene) {
  EXPECT_TRUE(CollideOptions{}.both_directions);
  EXPECT_TRUE(WorldDef{}.both_directions);
  EXPECT_TRUE(PairOptions{}.both_directions);
  EXPECT_FALSE(RunConfig{}.both_directions) << "the built-in scene is the paper's: one direction";
  EXPECT_TRUE(run_config(RunConfig{}, std::string(R"({"types": [{"shape": "cube"}]})")).both_directions)
      << "a scene file without \"both_directions\" runs as a World does";
  for (const char* name : {"paper", "mixed", "small", "large"}) {
    RunConfig o;
    o.where = std::string(VOXCD_SCENES_DIR "/") + name + ".json";
    EXPECT_FALSE(run_config(o).both_directions) << name << ".json says \"both_directions\": false";
  }
  // World's default and collide()'s give the same contacts for the same two bodies.
  ObjectDef def;
  def.voxel = 0.1;
  const Object torus = Object::load("torus", def), cube = Object::load("cube", def);
  World w;
  Pose pa, pb;
  pa.translation = {50, 50, 50};
  pb.translation = {51.2, 50, 50};
  BodyDef da(torus), db(cube);
  da.pose = pa;
  db.pose = pb;
  w.add(da);
  w.add(db);
  w.step();
  ASSERT_EQ(w.contacts().size(), 1u);
  const Contacts want = collide(torus, w.bodies()[0].pose, cube, w.bodies()[1].pose);
  EXPECT_EQ(w.contacts()[0].hits, want.hits);
  EXPECT_EQ(w.contacts()[0].contacts.size(), want.contacts.size());
  EXPECT_TRUE(std::any_of(want.contacts.begin(), want.contacts.end(), [](const Contact& k) { return !k.a_in_b; }));
}

TEST(Api, DevicesBackendsAndSizing) {
  const std::vector<std::string> b = device_backends();
  EXPECT_NE(std::find(b.begin(), b.end(), "cpu"), b.end());
  EXPECT_NE(std::find(b.begin(), b.end(), "ref"), b.end());
  SizeOptions o;
  o.frames = 20;
  const DeviceSize d = size_device(VOXCD_SCENES_DIR "/small.json", o);
  EXPECT_GT(d.config.LANES, 0);
  EXPECT_GT(d.error, 0);
  EXPECT_NE(d.text.find("config"), std::string::npos) << d.text;
  EXPECT_EQ(d.json.front(), '{');
  o.clock_mhz = 40;
  const DeviceSize at40 = size_device(VOXCD_SCENES_DIR "/small.json", o);
  EXPECT_NE(at40.text.find("at 40 MHz (given by SizeOptions::clock_mhz)"), std::string::npos) << at40.text;
  EXPECT_NE(at40.json.find("\"clock_mhz\": 40"), std::string::npos) << at40.json;
  o.clock_mhz = -1;
  EXPECT_THROW(size_device(VOXCD_SCENES_DIR "/small.json", o), OptionError);
}

}  // namespace
}  // namespace voxcd
