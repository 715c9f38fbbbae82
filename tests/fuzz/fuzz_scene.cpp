// Fuzz target: scene input (RunConfig, what voxcd simulate's options fill) through make_scene. The input is the
// built-in scene's fields in binary: shape (one byte: a built-in shape, or a name that is neither a shape nor a file),
// objects (two bytes, mod 128), side, density, speed, spin and voxel (doubles, as their bytes) and the seed.
// std::invalid_argument naming the field (check()) or starting with "scene: " (make_scene) and MeshError naming the
// shape are the documented errors. A scene
// that is made must hold every object with its bounding sphere inside the cube. Valid specs whose objects would be
// more than 12 voxels across (computed as make_scene does) are skipped: they cost time, not coverage (the check of
// the size runs before voxelising).
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/object/shapes.h"
#include "tests/fuzz/fuzz_common.h"

using namespace voxcd;

namespace {

struct Reader {
  const uint8_t* p;
  template <class T>
  T next() {
    T v;
    std::memcpy(&v, p, sizeof v);
    p += sizeof v;
    return v;
  }
};

constexpr size_t kSize = 1 + 2 + 5 * 8 + 8;

// A built-in shape's largest extent over the cube root of its volume: make_scene's objects are that ratio times
// cbrt(density * side^3 / objects) across.
double extent_ratio(const std::string& shape) {
  const Mesh m = make_shape(shape);
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  return (hi - lo).maxCoeff() / std::cbrt(m.volume());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kSize) return 0;
  static const char* const kShapes[] = {"polytope36", "stellated", "icosahedron", "sphere",
                                        "torus",      "cube",      "plate",       "no-such-shape"};
  Reader r{data};
  RunConfig s;
  s.types[0].shape = kShapes[r.next<uint8_t>() % 8];
  s.types[0].count = r.next<uint16_t>() % 128;
  s.side = r.next<double>();
  s.density = r.next<double>();
  s.speed = r.next<double>();
  s.spin = r.next<double>();
  s.types[0].voxel = r.next<double>();
  s.seed = r.next<uint64_t>();
  const bool valid = s.types[0].count > 0 && s.side > 0 && std::isfinite(s.side) && s.density > 0 && s.density <= 0.3 &&
                     s.speed >= 0 && std::isfinite(s.speed) && s.spin >= 0 && std::isfinite(s.spin) &&
                     s.types[0].voxel > 0 && std::isfinite(s.types[0].voxel);
  static const double kRatio[] = {extent_ratio(kShapes[0]), extent_ratio(kShapes[1]), extent_ratio(kShapes[2]),
                                  extent_ratio(kShapes[3]), extent_ratio(kShapes[4]), extent_ratio(kShapes[5]),
                                  extent_ratio(kShapes[6]), 1.0};
  const double across = kRatio[data[0] % 8] * std::cbrt(s.density / double(s.types[0].count)) * s.side / s.types[0].voxel;
  if (valid && across > 12) return 0;
  try {
    const Scene sc = make_scene(s);
    if (sc.bodies.size() != s.types[0].count || sc.types.size() != 1) fuzz::finding("make_scene: wrong number of bodies");
    const ObjectType& t = *sc.types[0];
    for (const Body& b : sc.bodies) {
      const Eigen::Vector3d c = b.pose.translation + b.pose.rotation * t.centre;
      for (int i = 0; i < 3; ++i)
        if (!(c[i] >= t.radius * (1 - 1e-9) && c[i] <= s.side - t.radius * (1 - 1e-9)))
          fuzz::finding("make_scene: a body's bounding sphere leaves the cube");
    }
  } catch (const OptionError& e) {
    // check()'s errors name the field.
    bool named = false;
    for (const char* field : {"types[0].", "side", "density", "speed", "spin"})
      named = named || e.where().rfind(field, 0) == 0;
    if (!named) fuzz::finding("OptionError names no field: " + std::string(e.what()));
  } catch (const std::invalid_argument& e) {
    // make_scene's own start with "scene: ".
    const std::string what = e.what();
    if (what.rfind("scene: ", 0) != 0) fuzz::finding("std::invalid_argument names no field: " + what);
  } catch (const MeshError& e) {
    fuzz::expect_prefix(e.what(), s.types[0].shape + ":", "MeshError");
  }
  return 0;
}
