// The built-in scene of the paper's environment (one shape scaled to fill the density), its default voxel, and
// make_scene, which picks it or a scene file's.
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"

namespace voxcd {

double default_voxel(double volume, double extent) {
  double v = std::cbrt(volume / kPaperObjectVolume);
  if (!(v >= extent / kDefaultMostAcross)) v = extent / kDefaultMostAcross;  // also a volume that is not positive
  if (v > extent / kDefaultFewestAcross) v = extent / kDefaultFewestAcross;
  return v;
}

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

// The largest radius of spheres of which the lattice fits `count` in the cube (0 when not even one fits).
double largest_radius_for(double side, uint64_t count) {
  double lo = 0, hi = side / 2;
  if (lattice_capacity(side, hi * (1 - 1e-12)) >= count) return hi;
  for (int i = 0; i < 80; ++i) {
    const double mid = 0.5 * (lo + hi);
    (lattice_capacity(side, mid) >= count ? lo : hi) = mid;
  }
  return lo;
}

// The built-in scene's voxel (`what` says where it comes from) against an object `extent` across.
void check_voxels_across(const std::string& what, double extent, double voxel) {
  if (extent / voxel > kMaxVoxelsAcross) {
    char across[32];  // as a double: a tiny voxel makes the count too large for an int, or infinite
    std::snprintf(across, sizeof across, "%.6g", extent / voxel);
    throw std::invalid_argument("scene: " + what + " makes each object " + across + " voxels across, above 2^10");
  }
  if (extent / voxel < 2)
    throw std::invalid_argument("scene: " + what + " is larger than half the object (" + std::to_string(extent) +
                                " across); objects would be a voxel or two");
  if (extent / voxel < kMinVoxelsAcross)
    throw std::invalid_argument("scene: " + what + " leaves " + num(extent / voxel) +
                                " voxels along the object's longest side (" + num(extent) + "); at least " +
                                std::to_string(kMinVoxelsAcross) + " are needed: a voxel of at most " +
                                num(extent / kMinVoxelsAcross) + ", or a resolution");
}

// The built-in scene (make_scene): one type, scaled to fill the density, with the paper's voxel by default.
Scene make_builtin_scene(const RunConfig& c) {
  const SceneTypeSpec& t = c.types.at(0);
  const uint64_t objects = t.count;
  std::string source;
  uint64_t hash = 0;
  Mesh mesh = load_source(t.shape, &source, &hash);
  // Scale so that the objects fill `density` of the cube, and centre the mesh on its box's centre.
  const double each = c.density * c.side * c.side * c.side / double(objects);  // one's volume
  const double volume = mesh.volume();
  const double s = std::cbrt(each / volume);
  Eigen::Vector3d lo, hi;
  mesh.bounds(lo, hi);
  const Eigen::Vector3d mid = 0.5 * (lo + hi);
  for (auto& v : mesh.vertices) v = (v - mid) * s;
  const double extent = (hi - lo).maxCoeff() * s;
  // The voxel: given, from the resolution, or the paper's scaled with the object (1 for the paper's scene).
  const double voxel = t.voxel > 0    ? t.voxel
                       : t.resolution ? voxel_for_resolution(mesh, t.resolution)
                                      : default_voxel(each, extent);
  const std::string what = t.voxel > 0    ? "voxel " + std::to_string(voxel)
                           : t.resolution ? "resolution " + std::to_string(t.resolution)
                                          : "the default voxel " + num(voxel);
  check_voxels_across(what, extent, voxel);
  ObjectOptions oo;
  oo.voxel = voxel;
  oo.distance_bits = c.distance_bits;
  oo.band = c.band;
  set_storage(oo, c.storage);
  Scene scene;
  scene.side = c.side;
  auto type = std::make_shared<ObjectType>(
      make_object_type(make_object(mesh, source, hash, oo), t.shape + " x" + std::to_string(s)));
  type->mesh = std::make_shared<const Mesh>(std::move(mesh));
  scene.types.push_back(type);
  const double r = type->radius;
  if (2 * r >= c.side) throw std::invalid_argument("scene: the objects do not fit the cube");
  try {
    place_bodies(scene, {objects}, c.speed, c.spin, c.seed);
  } catch (const PlacementError& e) {
    // Object size (and with the default voxel, bounding radius) goes with the cube root of the density.
    const double r_fit = largest_radius_for(c.side, objects);
    const double most = c.density * std::pow(r_fit / e.radius, 3);
    throw std::invalid_argument("scene: could not place object " + std::to_string(e.instance) + " of " +
                                std::to_string(objects) + " without overlapping bounding spheres: at density " +
                                num(c.density) + " each object's bounding sphere has radius " + num(e.radius) +
                                ", and even packed on a lattice only " + std::to_string(e.capacity) +
                                " such spheres fit the cube; " + std::to_string(objects) +
                                " objects of this shape fit up to a density of about " + num(most));
  }
  return scene;
}

}  // namespace

Scene make_scene(const RunConfig& c) {
  check(c);
  return c.builtin() ? make_builtin_scene(c) : make_file_scene(c);
}

}  // namespace voxcd
