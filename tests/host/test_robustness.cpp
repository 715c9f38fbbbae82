// Bad inputs that docs/robustness.md lists and no other suite drives: object types that do not fit the device, pairs
// that name a type that does not exist, a job with a mode outside the enum, shell points outside a narrow PW, bad
// voxelisation and object options, inconsistent objects given to write_object, scene specs out of range, the
// queue broadphase's body limit, a device whose record stream does not match its jobs, and an open mesh given to
// the voxeliser without validation. Each error must say what is wrong and where (the name, the field, the value).
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/png.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/ref/pipeline.h"
#include "tests/error_text.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

using test::error_text;

#define EXPECT_HAS(text, part) EXPECT_NE(std::string(text).find(part), std::string::npos) << (text)

std::shared_ptr<const ObjectType> type_of(const std::string& shape, double voxel) {
  const Mesh m = make_shape(shape);
  ObjectOptions o;
  o.voxel = voxel;
  return std::make_shared<ObjectType>(make_object_type(make_object(m, m.name, 0, o), m.name));
}

TEST(Robustness, VoxmapAboveTwoToTheDWIsACapacityErrorNamingTheType) {
  const auto t = type_of("cube", 0.25);  // 11 x 11 x 11 voxels
  ASSERT_EQ(t->voxmap().dims()[0], 11u);
  DeviceConfig cfg;
  cfg.DW = 3;  // 8 voxels per axis
  const std::string want = "object 'cube': its voxmap is 11x11x11 voxels, above the device's 2^DW = 8 per axis";
  EXPECT_EQ(error_text<CapacityError>([&] { DeviceImage(cfg).add(*t); }), want);
  EXPECT_EQ(error_text<CapacityError>([&] { fit_memory(cfg, {t.get()}); }), want);
  EXPECT_EQ(error_text<CapacityError>([&] { PairCollider(make_device("cpu", cfg), {t}); }), want);
  cfg.DW = 4;  // 16 per axis: fits
  EXPECT_NO_THROW(PairCollider(make_device("cpu", cfg), {t}));
}

TEST(Robustness, TypesBeyondTheLargestMemoriesAreACapacityError) {
  const auto t = type_of("cube", 0.25);
  const size_t shell = t->shell().size();
  // The same type many times over: more shell words than 2^24 (SAW 24), the largest shell memory.
  const size_t copies = (size_t(1) << 24) / shell + 1;
  std::vector<const ObjectType*> types(copies, t.get());
  const std::string e = error_text<CapacityError>([&] { fit_memory(DeviceConfig{}, types); });
  EXPECT_HAS(e, "the object types need " + std::to_string(copies * shell) + " shell words and ");
  EXPECT_HAS(e, "the largest device memories hold 2^24 and 2^28");
  types.pop_back();  // at most 2^24 words: fits, with SAW grown to 24
  EXPECT_EQ(fit_memory(DeviceConfig{}, types).SAW, 24);
}

TEST(Robustness, PairNamingATypeThatDoesNotExistIsAnError) {
  const auto t = type_of("cube", 0.5);
  PairCollider col(make_device("cpu", DeviceConfig{}), {t, t});
  PairRequest ok, bad;
  bad.b = 2;
  std::vector<PairResult> out = col.collide({ok});
  ASSERT_EQ(out.size(), 1u);
  const auto before = out[0].contacts.size();
  EXPECT_EQ(error_text<std::out_of_range>([&] { col.collide({ok, bad}, PairOptions{}, out); }),
            "pair 1 names object type 2 of 2");
  ASSERT_EQ(out.size(), 1u) << "a refused batch changed the results";
  EXPECT_EQ(out[0].contacts.size(), before);
  bad.b = 0;
  bad.a = 7;
  EXPECT_EQ(error_text<std::out_of_range>([&] { col.jobs({bad}); }), "pair 0 names object type 7 of 2");
}

TEST(Robustness, JobWithAModeOutsideTheEnumIsRefused) {
  const DeviceConfig cfg;
  DeviceMemory mem;
  mem.shell.assign(4, ShellWord{0, 0, 0});
  mem.map.assign(1, 0);
  Job j;
  j.tag = 5;
  j.shell_count = 4;
  j.nx = j.ny = j.nz = 2;
  for (int i = 0; i < 3; ++i) j.M[i][i] = int64_t(1) << cfg.MF;
  EXPECT_NO_THROW(validate_job(cfg, j, mem.shell.size(), mem.map.size()));
  j.mode = static_cast<Mode>(3);
  const std::string want = "job tag 5: mode 3 is not ALL, FIRST or COUNT";
  EXPECT_EQ(error_text<JobError>([&] { validate_job(cfg, j, mem.shell.size(), mem.map.size()); }), want);
  // Every software backend refuses it before running anything.
  for (const std::string backend : {"ref", "cpu"}) {
    auto dev = make_device(backend, cfg);
    dev->load(mem);
    EXPECT_EQ(error_text<JobError>([&] { dev->run({j}); }), want) << backend;
  }
}

TEST(Robustness, ShellPointOutsideANarrowPWNamesThePoint) {
  // PW 10 with PF 2: shell coordinates in [-128, 128) shell cells; a cube at voxel 0.02 has a shell grid of about
  // 145 cells per axis.
  const auto t = type_of("cube", 0.02);
  DeviceConfig cfg;
  cfg.PW = 10;
  cfg.PF = 2;
  cfg.SAW = 17;  // room for its 119288 points
  cfg.validate();
  const std::string e = error_text<RangeError>([&] { t->shell().words(cfg); });
  EXPECT_HAS(e, "shell point ");
  EXPECT_HAS(e, "does not fit signed 10-bit with 2 fraction bits, range [-128, 127.75]");
  EXPECT_EQ(error_text<RangeError>([&] { DeviceImage(cfg).add(*t); }), e);
}

TEST(Robustness, BadObjectOptionsAndInputsNameTheMeshAndTheValue) {
  const Mesh cube = make_shape("cube");
  VoxelizeOptions vo;
  vo.voxel = 0.5;
  vo.shift = Eigen::Vector3d(0.5, 0, 0.5);
  EXPECT_HAS(error_text<MeshError>([&] { place_grid(cube, vo); }),
             "cube: grid shift components must lie in [1/1024, 1], got 0.000000");
  vo.shift.y() = 1.5;
  EXPECT_HAS(error_text<MeshError>([&] { place_grid(cube, vo); }), "got 1.500000");
  ShellOptions so;
  so.target_voxel = 0.5;
  so.ratio = 0;
  EXPECT_EQ(error_text<MeshError>([&] { point_shell(cube, so); }),
            "cube: the shell ratio must be a positive finite number, got 0.000000");
  so.ratio = std::nan("");
  EXPECT_HAS(error_text<MeshError>([&] { point_shell(cube, so); }), "the shell ratio must be a positive finite");
  EXPECT_EQ(error_text<MeshError>([&] { load_object_type("cube", 0); }),
            "cube: a mesh or shape needs a positive voxel size (--voxel) to be voxelised");
  EXPECT_HAS(error_text<MeshError>([&] { load_object_type("cube", -1); }), "needs a positive voxel size");

  // A voxmap with nothing on it (every voxel cleared after voxelising).
  ObjectOptions oo;
  oo.voxel = 0.5;
  ObjectFile obj = make_object(cube, "cube", 0, oo);
  for (uint64_t& w : obj.voxmap.words()) w = 0;
  EXPECT_EQ(error_text<MeshError>([&] { make_object_type(obj, "empty"); }), "empty: the voxmap has no surface voxel");

  // A directory given as a mesh.
  const std::string dir = test::tmp_path("robust_dir");
  std::filesystem::create_directories(dir);
  EXPECT_EQ(error_text<MeshError>([&] { load_source(dir); }), dir + ": not a regular file");
  std::filesystem::remove(dir);

  // A mesh built in code whose triangle names a vertex that does not exist.
  Mesh m;
  m.name = "built";
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  m.triangles = {{0, 1, 7}};
  EXPECT_EQ(error_text<MeshError>([&] { validate(m); }), "built: triangle 0 has vertex index 7 out of range");
  EXPECT_EQ(error_text<MeshError>([&] { weld(m); }),
            "built: triangle 0 has vertex index 7 out of range (3 vertices)");
}

TEST(Robustness, WriteObjectRefusesAnInconsistentObjectAndWritesNothing) {
  ObjectOptions oo;
  oo.voxel = 0.5;
  const ObjectFile good = make_object(make_shape("cube"), "shape:cube", 0, oo);
  const std::string path = test::tmp_path("robust.vox");
  std::remove(path.c_str());
  ObjectFile bad = good;
  bad.shell.normals.pop_back();
  EXPECT_EQ(error_text<ObjectFileError>([&] { write_object(path, bad); }),
            path + ": the shell's cells, points and normals differ in number");
  bad = good;
  bad.shell.grid.dims[1] = 0;
  EXPECT_EQ(error_text<ObjectFileError>([&] { write_object(path, bad); }),
            path + ": grid dimension 0 does not fit an object file");
  bad.shell.grid.dims[1] = kObjectMaxDim + 1;
  EXPECT_HAS(error_text<ObjectFileError>([&] { write_object(path, bad); }),
             "grid dimension " + std::to_string(kObjectMaxDim + 1) + " does not fit");
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(Robustness, SceneSettingsOutOfRangeNameTheField) {
  // check()'s errors are OptionErrors; make_scene's own ("scene: ...") std::invalid_argument.
  auto scene_error = [](void (*change)(RunConfig&), bool option = true) {
    RunConfig s;
    s.types[0].count = 8;
    s.types[0].voxel = 2;
    change(s);
    return option ? error_text<OptionError>([&] { make_scene(s); })
                  : error_text<std::invalid_argument>([&] { make_scene(s); });
  };
  // Values set in code: check() names the field.
  EXPECT_EQ(scene_error([](RunConfig& s) { s.types[0].count = 0; }), "types[0].count: 0 is outside [1, 1048576]");
  EXPECT_EQ(scene_error([](RunConfig& s) { s.side = -1; }), "side: -1 is outside (0, 1e+12]");
  EXPECT_EQ(scene_error([](RunConfig& s) { s.side = INFINITY; }), "side: inf is outside (0, 1e+12]");
  EXPECT_EQ(scene_error([](RunConfig& s) { s.speed = -0.1; }), "speed: -0.1 is outside [0, 1000000]");
  EXPECT_EQ(scene_error([](RunConfig& s) { s.spin = NAN; }), "spin: nan is outside [0, 1000000]");
  EXPECT_EQ(scene_error([](RunConfig& s) { s.types[0].voxel = -1; }), "types[0].voxel: -1 is outside (0, 1e+12]");
  EXPECT_HAS(scene_error([](RunConfig& s) { s.types[0].voxel = 50; }, false),
             "scene: voxel 50.000000 is larger than half the object");
  // Long thin plates at the highest density: their enclosing spheres do not all fit the cube.
  const std::string crowded = scene_error([](RunConfig& s) {
    s.types[0].shape = "plate";
    s.types[0].count = 64;
    s.density = 0.3;
    s.types[0].voxel = 0.5;
  }, false);
  EXPECT_TRUE(crowded == "scene: the objects do not fit the cube" ||
              crowded.rfind("scene: could not place object ", 0) == 0)
      << crowded;
}

// One object of the paper's polytope at 30% of the cube: its enclosing sphere is wider than the cube.
TEST(Robustness, SceneWhoseObjectIsWiderThanTheCubeSaysSo) {
  RunConfig s;
  s.types[0].count = 1;
  s.density = 0.3;
  EXPECT_EQ(error_text<std::invalid_argument>([&] { make_scene(s); }), "scene: the objects do not fit the cube");
}

// write_object onto a directory: the rename into place fails, the temporary file goes, the directory stays.
TEST(Robustness, ObjectFileThatCannotBeRenamedIntoPlaceLeavesNothingBehind) {
  ObjectOptions o;
  o.voxel = 0.5;
  const ObjectFile obj = make_object(make_shape("cube"), "shape:cube", 1, o);
  const std::string dir = test::tmp_path("object_in_the_way");
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(std::filesystem::create_directory(dir));
  EXPECT_EQ(error_text<ObjectFileError>([&] { write_object(dir, obj); }),
            dir + ": cannot rename " + dir + ".tmp into place");
  EXPECT_FALSE(std::filesystem::exists(dir + ".tmp"));
  EXPECT_TRUE(std::filesystem::is_directory(dir));
  std::filesystem::remove_all(dir);
}

// A picture written where no file can be: the error names the path.
TEST(Robustness, PictureThatCannotBeWrittenNamesThePath) {
  const std::string dir = test::tmp_path("picture_in_the_way");
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(std::filesystem::create_directory(dir));
  EXPECT_EQ(error_text<std::runtime_error>([&] { write_png(dir, Image(4, 3)); }), dir + ": cannot write the picture");
  std::filesystem::remove_all(dir);
}

// A full disk, for the writes in its scope: the process may write no file beyond `bytes` (the write fails with
// EFBIG; SIGXFSZ, which would end the process, is ignored meanwhile).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    old_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    getrlimit(RLIMIT_FSIZE, &old_);
    rlimit r = old_;
    r.rlim_cur = bytes;
    ok_ = setrlimit(RLIMIT_FSIZE, &r) == 0;
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &old_);
    std::signal(SIGXFSZ, old_handler_);
  }
  bool ok() const { return ok_; }

 private:
  rlimit old_{};
  void (*old_handler_)(int) = nullptr;
  bool ok_ = false;
};

// An object file whose write fails part-way (the disk fills): the error names the path, the temporary is removed
// and the file already at the path is left as it was.
TEST(Robustness, ObjectFileOnAFullDiskLeavesTheOldFileAndNoTemporary) {
  ObjectOptions o;
  o.voxel = 0.5;
  const ObjectFile small = make_object(make_shape("cube"), "shape:cube", 1, o);
  o.voxel = 0.05;
  const ObjectFile large = make_object(make_shape("torus"), "shape:torus", 2, o);
  const std::string path = test::tmp_path("full_disk.vox");
  std::filesystem::remove(path);
  write_object(path, small);
  const auto before = std::filesystem::file_size(path);
  {
    FileSizeLimit full(before + 4096);
    ASSERT_TRUE(full.ok());
    EXPECT_EQ(error_text<ObjectFileError>([&] { write_object(path, large); }), path + ": write failed");
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
  EXPECT_EQ(std::filesystem::file_size(path), before);
  const ObjectFile back = read_object(path);
  EXPECT_EQ(back.voxmap.words(), small.voxmap.words());
  EXPECT_EQ(back.shell.size(), small.shell.size());
  std::filesystem::remove(path);
}

// A picture on a full disk: small enough to sit in the stream's buffer until the file is closed, and the failure
// of that last write is reported.
TEST(Robustness, PictureOnAFullDiskIsAnError) {
  EXPECT_EQ(error_text<std::runtime_error>([&] { write_png("/dev/full", Image(4, 3)); }),
            "/dev/full: cannot write the picture");
  const std::string path = test::tmp_path("full_disk.png");
  std::filesystem::remove(path);
  {
    FileSizeLimit full(16);
    ASSERT_TRUE(full.ok());
    EXPECT_EQ(error_text<std::runtime_error>([&] { write_png(path, Image(4, 3)); }), path + ": cannot write the picture");
  }
  write_png(path, Image(4, 3));  // and it fits once there is room
  EXPECT_GT(std::filesystem::file_size(path), 16u);
  std::filesystem::remove(path);
}

// Generated conformance vectors whose shell blocks do not fit 2^SAW words.
TEST(Robustness, GeneratedVectorsLargerThanTheShellMemorySaySo) {
  GenerateOptions g;
  g.config.SAW = 6;  // 64 words
  g.cloud_points = 100;
  const std::string e = error_text<std::invalid_argument>([&] { generate_vectors(g); });
  EXPECT_EQ(e.rfind("generated shell blocks need ", 0), 0u) << e;
  EXPECT_NE(e.find("words; the shell memory holds 2^SAW = 64"), std::string::npos) << e;
}

TEST(Robustness, QueueBroadphaseRefusesMoreBodiesThanItKeeps) {
  auto bp = make_broadphase("queue");
  std::vector<BodyBounds> bodies(8193);
  for (size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].centre = Eigen::Vector3d(double(i), 0, 0);
    bodies[i].radius = 0.25;
    bodies[i].box.lo = bodies[i].centre - Eigen::Vector3d::Constant(0.25);
    bodies[i].box.hi = bodies[i].centre + Eigen::Vector3d::Constant(0.25);
  }
  EXPECT_EQ(error_text<std::invalid_argument>([&] { bp->update(bodies, 0); }),
            "broadphase queue: 8193 bodies; it keeps every pair and takes at most 8192");
}

TEST(Robustness, DeviceWordsOfAnImpossibleMemoryWidthAreAnError) {
  ObjectOptions oo;
  oo.voxel = 0.5;
  const ObjectFile obj = make_object(make_shape("cube"), "shape:cube", 0, oo);
  for (int memw : {0, 1, 48, 128})
    EXPECT_EQ(error_text<std::invalid_argument>([&] { obj.voxmap.device_words(memw); }),
              "MEMW must be a power of two in 2..64, got " + std::to_string(memw));
  EXPECT_EQ(obj.voxmap.device_words(64), obj.voxmap.words());
}

// A device that runs the ref backend and spoils the stream of its next run as told: one record after the last
// completion, or the last completion left out. PairCollider must refuse both streams.
class SpoilingDevice final : public Device {
 public:
  enum class Spoil { None, ExtraRecord, MissingCompletion };
  explicit SpoilingDevice(const DeviceConfig& cfg) : inner_(make_device("ref", cfg)) {}
  std::string name() const override { return "spoiling"; }
  const DeviceConfig& config() const override { return inner_->config(); }
  bool models_cycles() const override { return true; }
  void load(const DeviceMemory& mem) override { inner_->load(mem); }
  std::vector<Record> run(const std::vector<Job>& jobs) override {
    std::vector<Record> out = inner_->run(jobs);
    if (next == Spoil::ExtraRecord) out.push_back(Record::hit(0, 0, 0, 0, 0, 1));
    if (next == Spoil::MissingCompletion) out.pop_back();
    next = Spoil::None;
    return out;
  }
  Spoil next = Spoil::None;

 private:
  std::unique_ptr<Device> inner_;
};

bool same_results(const std::vector<PairResult>& a, const std::vector<PairResult>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].hits != b[i].hits || a[i].lookups != b[i].lookups || a[i].contacts.size() != b[i].contacts.size())
      return false;
    for (size_t k = 0; k < a[i].contacts.size(); ++k) {
      const Contact &x = a[i].contacts[k], &y = b[i].contacts[k];
      if (x.pair != y.pair || x.a_in_b != y.a_in_b || x.point != y.point || x.voxel != y.voxel || x.state != y.state)
        return false;
    }
  }
  return true;
}

TEST(Robustness, DeviceStreamThatDoesNotMatchTheJobsIsADeviceError) {
  const auto t = type_of("cube", 0.25);
  auto owned = std::make_unique<SpoilingDevice>(DeviceConfig{});
  SpoilingDevice* dev = owned.get();
  PairCollider col(std::move(owned), {t, t});
  std::vector<PairRequest> reqs(3);
  reqs[1].pose_b.translation = Eigen::Vector3d(0.5, 0.25, 0);
  reqs[2].pose_b.translation = Eigen::Vector3d(5, 0, 0);  // apart: no contact
  PairOptions opt;
  opt.both_directions = true;
  const size_t jobs = col.jobs(reqs, opt).size();
  ASSERT_GE(jobs, 4u);
  const std::vector<PairResult> good = col.collide(reqs, opt);
  ASSERT_GT(good[0].contacts.size(), 0u);
  ASSERT_GT(good[1].contacts.size(), 0u);

  // A record after the last completion: refused before any result is touched.
  std::vector<PairResult> out = good;
  dev->next = SpoilingDevice::Spoil::ExtraRecord;
  EXPECT_EQ(error_text<DeviceError>([&] { col.collide(reqs, opt, out); }),
            "the device returned records after the completions of all " + std::to_string(jobs) + " jobs");
  EXPECT_TRUE(same_results(out, good)) << "the refused batch changed the results";

  // The last completion missing: refused before any result is touched too.
  dev->next = SpoilingDevice::Spoil::MissingCompletion;
  EXPECT_EQ(error_text<DeviceError>([&] { col.collide(reqs, opt, out); }),
            "the device returned fewer completions than the " + std::to_string(jobs) + " jobs it was given");
  EXPECT_TRUE(same_results(out, good)) << "the refused batch changed the results";

  // Neither loses the collider's types or the device's memory: the next batch is the same as the first.
  col.collide(reqs, opt, out);
  EXPECT_TRUE(same_results(out, good));
  EXPECT_TRUE(same_results(col.collide(reqs, opt), good));
}

// The ray caster (voxelize_raycast, the paper's parity fill) needs a closed mesh; given an open one it finds a
// column ray that crosses the surface an odd number of times, and names it. The winding-number voxeliser takes the
// same mesh and gives the closed cube's voxmap away from the hole.
TEST(Robustness, OpenMeshIsAnOddCrossingForTheRayCasterAndASolidForTheWindingNumber) {
  Mesh m = make_shape("cube");
  // Drop one triangle of a face the x rays cross.
  size_t drop = m.size();
  for (size_t t = 0; t < m.size() && drop == m.size(); ++t) {
    const Eigen::Vector3d n = (m.corner(t, 1) - m.corner(t, 0)).cross(m.corner(t, 2) - m.corner(t, 0));
    if (std::abs(n.x()) > 0.99 * n.norm()) drop = t;
  }
  ASSERT_LT(drop, m.size());
  const Eigen::Vector3d a = m.corner(drop, 0), b = m.corner(drop, 1), c = m.corner(drop, 2);
  m.triangles.erase(m.triangles.begin() + long(drop));
  m.name = "open cube";
  EXPECT_HAS(error_text<MeshError>([&] {
               Mesh copy = m;
               prepare(copy);
             }),
             "open cube: the mesh is open");

  VoxelizeOptions vo;
  vo.voxel = 0.25;
  vo.shift = Eigen::Vector3d(0.3, 0.37, 0.61);  // no column centre on the dropped triangle's edges
  const std::string e = error_text<MeshError>([&] { voxelize_raycast(m, vo); });
  // (No std::regex here: g++ 12 warns falsely inside <regex> under the sanitizers.)
  int cy = -1, cz = -1;
  ASSERT_EQ(std::sscanf(e.c_str(), "open cube: the ray through column (y %d, z %d)", &cy, &cz), 2) << e;
  ASSERT_EQ(e, "open cube: the ray through column (y " + std::to_string(cy) + ", z " + std::to_string(cz) +
                   ") crosses the surface an odd number of times");
  // The named column's ray passes through the dropped triangle (its centre lies inside the triangle's projection
  // onto the y-z plane), so it crosses the cube once.
  const GridPlacement gp = place_grid(m, vo);
  ASSERT_TRUE(cy >= 0 && cz >= 0 && uint32_t(cy) < gp.dims[1] && uint32_t(cz) < gp.dims[2]) << e;
  const double y = gp.origin.y() + vo.voxel * (cy + 0.5);
  const double z = gp.origin.z() + vo.voxel * (cz + 0.5);
  const auto side = [&](const Eigen::Vector3d& p, const Eigen::Vector3d& q) {
    return (q.y() - p.y()) * (z - p.z()) - (q.z() - p.z()) * (y - p.y());
  };
  const double s0 = side(a, b), s1 = side(b, c), s2 = side(c, a);
  EXPECT_TRUE((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0))
      << "column centre (" << y << ", " << z << ") is outside the dropped triangle";

  const Voxmap open = voxelize(m, vo);
  const Voxmap closed = voxelize_raycast(make_shape("cube"), vo);
  ASSERT_EQ(open.dims(), closed.dims());
  // Every voxel that differs lies within two voxels of the hole (the dropped triangle's box).
  const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  size_t differ = 0;
  for (uint32_t vz = 0; vz < open.dims()[2]; ++vz)
    for (uint32_t vy = 0; vy < open.dims()[1]; ++vy)
      for (uint32_t vx = 0; vx < open.dims()[0]; ++vx) {
        if (open.at(vx, vy, vz) == closed.at(vx, vy, vz)) continue;
        ++differ;
        const Eigen::Vector3d p = open.centre(vx, vy, vz);
        const double d = (p - p.cwiseMax(lo).cwiseMin(hi)).cwiseAbs().maxCoeff() / vo.voxel;
        EXPECT_LE(d, 2.0) << "voxel " << vx << " " << vy << " " << vz;
      }
  EXPECT_LT(differ, closed.counts()[kInterior] / 10);
  ObjectOptions oo;
  oo.voxel = vo.voxel;
  oo.shift = vo.shift;
  EXPECT_EQ(make_object(m, m.name, 0, oo).voxmap.words(), open.words());
}

}  // namespace
}  // namespace voxcd
