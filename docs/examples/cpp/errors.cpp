// Every error the API documents, caught by name (docs/api.md, "Errors"); each is also a voxcd::Error, with what()
// and where(). Exits non-zero when a call does not throw the error it should.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <voxcd/voxcd.h>

namespace {

int failures = 0;

// Runs f, which must throw E; prints what and where.
template <class E, class F>
void expect(const char* name, F&& f) {
  try {
    f();
  } catch (const E& e) {
    const voxcd::Error& base = e;
    std::printf("%-16s %s (where: %s)\n", name, base.what(), base.where().c_str());
    return;
  } catch (const std::exception& e) {
    std::printf("%-16s FAILED: another error: %s\n", name, e.what());
  }
  std::printf("%-16s FAILED\n", name);
  ++failures;
}

}  // namespace

int main() {
  const voxcd::Object torus = voxcd::Object::load("torus");
  voxcd::ObjectDef fine;
  fine.voxel = torus.voxel() / 4;  // voxels 4 times finer than the torus's: beyond the rtl models' widths
  const voxcd::Object sphere = voxcd::Object::load("sphere", fine);

  expect<voxcd::MeshError>("MeshError", [] { voxcd::Object::load("no-such-file-or-shape"); });
  std::ofstream("not_an_object.vxo") << "VOXCDOBJ but nothing else";
  expect<voxcd::ObjectFileError>("ObjectFileError", [] { voxcd::Object::load("not_an_object.vxo"); });
  voxcd::Pose nan;
  nan.translation = {std::nan(""), 0, 0};
  expect<voxcd::RangeError>("RangeError", [&] { voxcd::collide(torus, voxcd::Pose{}, torus, nan); });
  voxcd::CollideOptions rtl;
  rtl.backend = "rtl";
  expect<voxcd::CapacityError>("CapacityError", [&] { voxcd::collide(torus, voxcd::Pose{}, sphere, {}, rtl); });
  voxcd::CollideOptions none;
  none.backend = "no-such-backend";
  expect<voxcd::DeviceError>("DeviceError", [&] { voxcd::collide(torus, voxcd::Pose{}, torus, {}, none); });
  std::ofstream("bad_scene.json") << R"({"types": [{"shape": "cube", "voxel": -1}]})";
  expect<voxcd::SceneFileError>("SceneFileError", [] { voxcd::World::scene("bad_scene.json"); });
  voxcd::WorldDef def;
  def.side = -1;
  expect<voxcd::OptionError>("OptionError", [&] { voxcd::World world(def); });
  std::ofstream("small_scene.json") << R"({"types": [{"shape": "cube", "count": 8, "voxel": 0.1}]})";
  voxcd::SizeOptions size;
  size.accuracy = 1e-12;  // finer than any device's fixed-point path
  expect<voxcd::SizeError>("SizeError", [&] { voxcd::size_device("small_scene.json", size); });
  voxcd::World world;
  const voxcd::BodyId id = world.add(voxcd::BodyDef(torus));
  world.remove(id);
  expect<voxcd::BodyError>("BodyError", [&] { world.pose(id); });  // a removed body's id
  expect<voxcd::Error>("Error", [] { voxcd::Object::load("no-such-file-or-shape"); });
  return failures == 0 ? 0 : 1;
}
