// The differential check against exact geometry (tests/host/pairs/test_differential.cpp runs a sample in CI,
// bench/bench_differential.cpp the whole corpus for docs/results.md): for pairs of real and generated models at
// random poses, half of them near contact (bisected to the contact with FCL, then moved by up to +-2 voxels along
// the approach), FCL's exact collide (surfaces crossing) or one model inside the other's solid is the truth, and
// voxcd's answer in 2-bit and distance (SB 8) mode, both directions, margin 0, is checked against it:
// - a collision voxcd misses must be shallower than the documented depth (kMissDepth*), measured as the
//   translational penetration depth from above: the shortest translation along any of 26 directions that separates
//   the models (FCL); the deepest point of either surface inside the other's solid is reported beside it;
// - a contact voxcd reports at a pose where the models are apart must come from a pose whose separation (FCL's
//   exact distance) is within the documented bound (kFalseSeparation).
#pragma once

#include <fcl/fcl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "tests/defects.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/mesh/closest.h"
#include "voxcd/host/object/detail/winding.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"

namespace voxcd::test::diff {

// The documented bounds, in voxels of the shared voxel v (docs/pairs.md, "What a contact means"; "Distance
// voxmaps"): a shell point lies within sqrt(3)/2 h of every surface point (h = v / sqrt(2): 0.612 v), plus the
// fixed-point error (below 0.01 v at these sizes); a distance voxmap's field may place the surface up to
// detail::kResolvedTolerance (1/4 voxel) out in the cells it resolves, plus the node quantisation (s/2 = 1/64) and
// the weight truncation (3 (1 + s) 2^-8 = 0.012).
constexpr double kFixedSlack = 0.01;
constexpr double kMissDepth2Bit = 0.6124 + kFixedSlack;
constexpr double kMissDepthDistance = 0.6124 + 0.25 + 0.0157 + 0.0121 + kFixedSlack;
// A contact at a separated pose: within the hit voxel's diagonal of the other surface.
constexpr double kFalseSeparation = 1.7321 + kFixedSlack;

struct Model {
  std::string name;
  Mesh mesh;                // as a file holds it; voxcd repairs it, FCL takes its finite triangles
  std::vector<Mesh> solid;  // closed parts whose union is the solid, when known
  bool known_solid = false; // solid is the truth (an empty list: a sheet, encloses nothing); else the repaired
                            // mesh's generalized winding number decides
};

inline Mesh scaled(Mesh m, double s, const Eigen::Vector3d& shift = Eigen::Vector3d::Zero()) {
  for (auto& v : m.vertices) v = v * s + shift;
  return m;
}

// The model moved and scaled so that its bounding box is centred on the origin with a longest side of 1 (its solid
// too), so that models of any size pair up at one voxel.
inline Model normalized(Model m) {
  Mesh r = m.mesh;
  repair(r);
  Eigen::Vector3d lo, hi;
  r.bounds(lo, hi);
  const double s = 1 / (hi - lo).maxCoeff();
  const Eigen::Vector3d shift = -0.5 * (lo + hi) * s;
  m.mesh = scaled(m.mesh, s, shift);
  for (Mesh& part : m.solid) part = scaled(part, s, shift);
  return m;
}

inline Model from_defect(const Defect& d) {
  Model m;
  m.name = d.name;
  m.mesh = d.mesh;
  m.solid = d.solid;
  m.known_solid = true;
  return m;
}

// An open tube (a cylinder without caps): a sheet.
inline Model open_tube(int n = 48) {
  Model m;
  m.name = "a tube without caps";
  const double pi = std::acos(-1.0);
  for (int i = 0; i < n; ++i)
    for (double z : {-0.6, 0.6}) m.mesh.vertices.emplace_back(0.3 * std::cos(2 * pi * i / n), 0.3 * std::sin(2 * pi * i / n), z);
  for (uint32_t i = 0; i < uint32_t(n); ++i) {
    const uint32_t j = (i + 1) % uint32_t(n);
    m.mesh.triangles.push_back({2 * i, 2 * j, 2 * j + 1});
    m.mesh.triangles.push_back({2 * i, 2 * j + 1, 2 * i + 1});
  }
  m.mesh.name = m.name;
  m.known_solid = true;  // no solid
  return m;
}

// A closed plate `thickness` thick (1 x 1 across).
inline Model thin_plate(double thickness) {
  Model m;
  char b[64];
  std::snprintf(b, sizeof b, "a closed plate %.4g thick", thickness);
  m.name = b;
  m.mesh = make_box(Eigen::Vector3d(-0.5, -0.5, -thickness / 2), Eigen::Vector3d(0.5, 0.5, thickness / 2));
  m.mesh.name = m.name;
  m.solid = {m.mesh};
  m.known_solid = true;
  return m;
}

inline Model open_square() {
  Model m = from_defect(square_sheet());
  m.solid.clear();
  return m;
}

// A room: a floor, four walls 0.04 thick (closed boxes that overlap at the corners), a table (a top and four legs,
// closed boxes, the legs' tops inside the top), a shelf of three boards on two sides (sharing faces), a stool made of
// prisms sharing faces. About 4 x 4 x 2.4.
inline Model room() {
  Model m;
  m.name = "a room with furniture";
  auto box = [&](Eigen::Vector3d lo, Eigen::Vector3d hi) {
    const Mesh b = make_box(lo, hi);
    append(m.mesh, b);
    m.solid.push_back(b);
  };
  const double t = 0.04;
  box({-2, -2, -t}, {2, 2, 0});                   // floor
  box({-2, -2, 0}, {2, -2 + t, 2.4});             // walls
  box({-2, 2 - t, 0}, {2, 2, 2.4});
  box({-2, -2, 0}, {-2 + t, 2, 2.4});
  box({2 - t, -2, 0}, {2, 2, 2.4});
  box({-0.8, -0.5, 0.72}, {0.8, 0.5, 0.76});      // table top
  for (double x : {-0.75, 0.7})
    for (double y : {-0.45, 0.4}) box({x, y, 0}, {x + 0.05, y + 0.05, 0.74});
  // Shelf: two sides and three boards; each board shares its end faces with the sides' inner faces exactly.
  box({1.2, -1.9, 0}, {1.22, -1.5, 1.6});
  box({1.9, -1.9, 0}, {1.92, -1.5, 1.6});
  for (double z : {0.3, 0.9, 1.5}) box({1.22, -1.9, z}, {1.9, -1.5, z + 0.02});
  // Stool: a hexagonal seat of six wedges (shared faces) on a box.
  for (int i = 0; i < 6; ++i) {
    const double pi = std::acos(-1.0), a0 = 2 * pi * i / 6, a1 = 2 * pi * (i + 1) / 6;
    const Eigen::Vector3d c(-1.2, 1.2, 0), p(-1.2 + 0.25 * std::cos(a0), 1.2 + 0.25 * std::sin(a0), 0),
        q(-1.2 + 0.25 * std::cos(a1), 1.2 + 0.25 * std::sin(a1), 0);
    const Mesh w = prism(c, p, q, 0.45, 0.5);
    append(m.mesh, w);
    m.solid.push_back(w);
  }
  box({-1.25, 1.15, 0}, {-1.15, 1.25, 0.45});
  m.mesh.name = m.name;
  m.known_solid = true;
  return m;
}

// A desk-like robot: a base, a column and a two-segment arm, each segment a closed box that shares a face with
// the next (the shared faces given twice, as a modeller exports touching parts), a top made of prisms that share
// edges and faces, and a gripper of two fingers. About 0.7 x 0.5 x 1.1.
inline Model robot() {
  Model m;
  m.name = "a robot of parts sharing faces and edges";
  auto part = [&](const Mesh& b) {
    append(m.mesh, b);
    m.solid.push_back(b);
  };
  part(make_box({-0.25, -0.25, 0}, {0.25, 0.25, 0.15}));     // base
  part(make_box({-0.06, -0.06, 0.15}, {0.06, 0.06, 0.7}));   // column, on the base's top face
  part(make_box({-0.06, -0.06, 0.7}, {0.06, 0.06, 0.82}));   // shoulder, sharing the column's top face
  part(make_box({0.06, -0.05, 0.7}, {0.36, 0.05, 0.8}));     // upper arm, sharing the shoulder's side face in part
  part(make_box({0.36, -0.05, 0.7}, {0.46, 0.05, 1.05}));    // forearm, sharing the upper arm's end face
  // The top: four prisms around the forearm's top centre, sharing their radial faces and the axis edge.
  const Eigen::Vector3d c(0.41, 0, 1.05);
  const Eigen::Vector3d corner[4] = {{0.36, -0.05, 1.05}, {0.46, -0.05, 1.05}, {0.46, 0.05, 1.05}, {0.36, 0.05, 1.05}};
  for (int i = 0; i < 4; ++i) part(prism(c, corner[i], corner[(i + 1) % 4], 1.05, 1.1));
  part(make_box({0.37, -0.05, 1.1}, {0.39, 0.05, 1.18}));    // fingers, on the top's face
  part(make_box({0.43, -0.05, 1.1}, {0.45, 0.05, 1.18}));
  m.mesh.name = m.name;
  m.known_solid = true;
  return m;
}

// Debian's assimp test models that are meshes a tool exported (Blender, 3ds Max, scanners): `names` relative to
// /usr/share/assimp/models. Missing files are an error (the test installs assimp-testmodels).
inline std::vector<Model> real_models(const std::vector<std::string>& names) {
  std::vector<Model> out;
  for (const std::string& n : names) {
    Model m;
    m.name = n;
    m.mesh = load_mesh("/usr/share/assimp/models/" + n, nullptr, LoadOptions{});
    // load_mesh repairs; FCL gets the repaired triangles too (the file's exact surface, welded).
    out.push_back(std::move(m));
  }
  return out;
}

// The inside of a model: its known closed parts (by their pseudo-normals at the closest point), or the generalized
// winding number of the repaired mesh's non-sheet triangles (>= 1/2).
class Inside {
 public:
  explicit Inside(const Model& m) {
    if (m.known_solid) {
      for (const Mesh& p : m.solid) parts_.emplace_back(p);
    } else {
      Mesh r = m.mesh;
      repair(r);
      for (size_t t = 0; t < r.size(); ++t)
        if (!r.is_sheet(t)) soup_.push_back({r.corner(t, 0), r.corner(t, 1), r.corner(t, 2)});
    }
  }
  // Depth of p inside the solid (the largest distance to the surface of a part that contains it; 0 outside). For a
  // solid known only by its winding number: the distance to the repaired surface where the winding number >= 1/2.
  double depth(const Eigen::Vector3d& p) const {
    double best = 0;
    for (const Part& q : parts_) {
      const detail::Closest c = q.tree.closest(p);
      if (!c.found()) continue;
      if ((p - c.point).dot(q.normals.at(c)) < 0) best = std::max(best, std::sqrt(c.d2));
    }
    if (!soup_.empty()) {
      double w = 0, d2 = HUGE_VAL;
      for (const auto& t : soup_) {
        w += detail::triangle_winding(t[0] - p, t[1] - p, t[2] - p);
        d2 = std::min(d2, detail::closest_on_triangle(p, t[0], t[1], t[2]).d2);
      }
      if (w >= 0.5) best = std::max(best, std::sqrt(d2));
    }
    return best;
  }

 private:
  struct Part {
    explicit Part(const Mesh& m) : tree(m.vertices, m.triangles), normals(m.vertices, m.triangles) {}
    detail::TriangleTree tree;
    detail::PseudoNormals normals;
  };
  std::vector<Part> parts_;
  std::vector<std::array<Eigen::Vector3d, 3>> soup_;
};

using Bvh = fcl::BVHModel<fcl::OBBRSSd>;

inline std::shared_ptr<Bvh> bvh_of(const Mesh& m) {
  auto model = std::make_shared<Bvh>();
  std::vector<fcl::Vector3d> v(m.vertices.begin(), m.vertices.end());
  std::vector<fcl::Triangle> t;
  for (const auto& tri : m.triangles)
    if (m.vertices[tri[0]].allFinite() && m.vertices[tri[1]].allFinite() && m.vertices[tri[2]].allFinite())
      t.emplace_back(tri[0], tri[1], tri[2]);
  model->beginModel();
  model->addSubModel(v, t);
  model->endModel();
  return model;
}

inline RigidPose inverse(const RigidPose& p) {
  RigidPose q;
  q.rotation = p.rotation.conjugate();
  q.translation = -(q.rotation * p.translation);
  return q;
}

inline fcl::Transform3d to_fcl(const RigidPose& p) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = p.rotation.toRotationMatrix();
  t.translation() = p.translation;
  return t;
}

// Points on a mesh's surface at spacing at most `step` (its vertices and a barycentric grid on each triangle).
inline std::vector<Eigen::Vector3d> surface_samples(const Mesh& m, double step) {
  std::vector<Eigen::Vector3d> out;
  for (size_t t = 0; t < m.size(); ++t) {
    const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    if (!(a.allFinite() && b.allFinite() && c.allFinite())) continue;
    const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const int n = std::max(1, int(std::ceil(longest / step)));
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) out.push_back(a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n));
  }
  return out;
}

struct Outcome {
  bool truth = false;        // FCL: surfaces cross; or one model inside the other
  bool fcl = false;          // FCL's collide alone
  bool voxcd[2] = {false, false};  // 2-bit, distance
  double depth = 0;          // translational penetration depth from above, voxels (computed for misses)
  double point_depth = 0;    // the deepest point of either surface inside the other's solid, voxels (misses)
  double separation = 0;     // FCL's distance, voxels (computed for false contacts)
};

struct Tally {
  uint64_t tp = 0, fn = 0, fp = 0, tn = 0;
  uint64_t missed_beyond = 0, false_beyond = 0;
  double worst_missed_depth = 0, worst_false_separation = 0;
  std::string worst_missed, worst_false;  // the pair and pose of each worst case
};

// One pair of models at a shared voxel, at poses B relative to A.
class PairCheck {
 public:
  PairCheck(const Model& a, const Model& b, uint32_t resolution) : a_(a), b_(b) {
    Eigen::Vector3d lo, hi;
    double side = 0;
    for (const Model* m : {&a, &b}) {
      Mesh r = m->mesh;
      repair(r);
      r.bounds(lo, hi);
      side = std::max(side, (hi - lo).maxCoeff());
      radius_.push_back(0.5 * (hi - lo).norm());
      centre_.push_back(0.5 * (lo + hi));
    }
    voxel_ = side / resolution;
    for (int bits : {0, 8}) {
      std::vector<std::shared_ptr<const ObjectType>> types;
      for (const Model* m : {&a, &b}) {
        Mesh r = m->mesh;
        MeshReport rep = repair(r);
        ObjectOptions o;
        o.voxel = voxel_;
        o.distance_bits = bits;
        types.push_back(std::make_shared<ObjectType>(make_object_type(make_object(r, m->name, 0, o, &rep), m->name)));
      }
      const DeviceConfig cfg = device_config_for("cpu", 4, {types[0].get(), types[1].get()}, bits);
      collider_[bits ? 1 : 0] = std::make_unique<PairCollider>(make_device("cpu", cfg), types);
    }
    bvh_a_ = bvh_of(a.mesh);
    bvh_b_ = bvh_of(b.mesh);
  }

  double voxel() const { return voxel_; }

  bool fcl_collide(const RigidPose& pb) const {
    fcl::CollisionRequestd req;
    fcl::CollisionResultd res;
    fcl::collide(bvh_a_.get(), fcl::Transform3d::Identity(), bvh_b_.get(), to_fcl(pb), req, res);
    return res.isCollision();
  }

  // Random poses: B's orientation uniform; half at a uniform place where the bounding spheres overlap, half on a
  // random approach line bisected (FCL) to the first contact and moved by up to +-2 voxels along it.
  std::vector<RigidPose> poses(size_t n, uint64_t seed) const {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<RigidPose> out;
    const double reach = radius_[0] + radius_[1];
    while (out.size() < n) {
      RigidPose p;
      p.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
      Eigen::Vector3d dir(g(rng), g(rng), g(rng));
      dir.normalize();
      auto at = [&](double s) {
        RigidPose q = p;
        q.translation = centre_[0] + dir * s - p.rotation * centre_[1];
        return q;
      };
      if (out.size() % 2 == 0) {
        out.push_back(at(reach * std::cbrt(u(rng))));
        continue;
      }
      // The farthest colliding distance on a scan, then bisection to the first contact from outside.
      double in = -1;
      for (int k = 16; k >= 0; --k)
        if (fcl_collide(at(reach * k / 16))) {
          in = reach * k / 16;
          break;
        }
      if (in < 0) continue;  // this line never touches (a hollow model's axis): draw another
      double out_s = std::min(reach * 1.001, in + reach / 16);
      for (int it = 0; it < 40 && out_s - in > 1e-4 * voxel_; ++it) {
        const double mid = 0.5 * (in + out_s);
        (fcl_collide(at(mid)) ? in : out_s) = mid;
      }
      out.push_back(at(in + (4 * u(rng) - 2) * voxel_));
    }
    return out;
  }

  Outcome check(const RigidPose& pb) {
    Outcome o;
    o.fcl = fcl_collide(pb);
    o.truth = o.fcl || contained(pb);
    for (int k = 0; k < 2; ++k) {
      PairRequest r;
      r.a = 0;
      r.b = 1;
      r.pose_b = pb;
      PairOptions opt;
      opt.mode = Mode::Count;
      opt.both_directions = true;
      o.voxcd[k] = collider_[k]->collide({r}, opt).at(0).hits > 0;
    }
    if (o.truth && !(o.voxcd[0] && o.voxcd[1])) {
      o.point_depth = crossing_depth(pb) / voxel_;
      o.depth = penetration_depth(pb) / voxel_;
    }
    if (!o.truth && (o.voxcd[0] || o.voxcd[1])) {
      fcl::DistanceRequestd req;
      fcl::DistanceResultd res;
      fcl::distance(bvh_a_.get(), fcl::Transform3d::Identity(), bvh_b_.get(), to_fcl(pb), req, res);
      o.separation = res.min_distance / voxel_;
    }
    return o;
  }

 private:
  // One model inside the other's solid without the surfaces crossing: some vertex of one lies inside the other.
  bool contained(const RigidPose& pb) {
    const Inside& ia = inside(0);
    const Inside& ib = inside(1);
    const Mesh& ma = a_.mesh;
    const Mesh& mb = b_.mesh;
    const size_t step_a = std::max<size_t>(1, ma.vertices.size() / 16), step_b = std::max<size_t>(1, mb.vertices.size() / 16);
    for (size_t i = 0; i < mb.vertices.size(); i += step_b)
      if (mb.vertices[i].allFinite() && ia.depth(pb.rotation * mb.vertices[i] + pb.translation) > 0) return true;
    const RigidPose inv = inverse(pb);
    for (size_t i = 0; i < ma.vertices.size(); i += step_a)
      if (ma.vertices[i].allFinite() && ib.depth(inv.rotation * ma.vertices[i] + inv.translation) > 0) return true;
    return false;
  }

 public:
  // The translational penetration depth, from above: the shortest translation of B along any of the 26 directions
  // to the neighbours of a cube (axes, face and space diagonals) that leaves the models apart (FCL's collide and
  // the containment test both false), found by steps of v/4 and bisection to v/1000 (world units).
  double penetration_depth(const RigidPose& pb) {
    double best = HUGE_VAL;
    const double step = voxel_ / 4;
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy && !dz) continue;
          const Eigen::Vector3d d = Eigen::Vector3d(dx, dy, dz).normalized();
          auto apart = [&](double t) {
            RigidPose q = pb;
            q.translation += d * t;
            return !fcl_collide(q) && !contained(q);
          };
          double in = 0, out = step;
          while (out < best && !apart(out)) in = out, out += step;
          if (out >= best) continue;
          for (int it = 0; it < 12 && out - in > voxel_ / 1000; ++it) {
            const double mid = 0.5 * (in + out);
            (apart(mid) ? out : in) = mid;
          }
          best = std::min(best, out);
        }
    return best;
  }

  // The deepest point of either surface inside the other's solid (world units).
  double crossing_depth(const RigidPose& pb) {
    const Inside& ia = inside(0);
    const Inside& ib = inside(1);
    double best = 0;
    const RigidPose inv = inverse(pb);
    for (const Eigen::Vector3d& p : surface_samples(b_.mesh, voxel_ / 4))
      best = std::max(best, ia.depth(pb.rotation * p + pb.translation));
    for (const Eigen::Vector3d& p : surface_samples(a_.mesh, voxel_ / 4))
      best = std::max(best, ib.depth(inv.rotation * p + inv.translation));
    return best;
  }

 private:
  const Inside& inside(int k) {
    if (!inside_[k]) inside_[k] = std::make_unique<Inside>(k == 0 ? a_ : b_);
    return *inside_[k];
  }

  Model a_, b_;
  double voxel_ = 0;
  std::vector<double> radius_;
  std::vector<Eigen::Vector3d> centre_;
  std::unique_ptr<PairCollider> collider_[2];
  std::shared_ptr<Bvh> bvh_a_, bvh_b_;
  std::unique_ptr<Inside> inside_[2];
};

// Adds an outcome to mode k's tally (0: 2-bit, 1: distance); `where` names the pair and pose for the worst cases.
inline void tally(Tally& t, int k, const Outcome& o, const std::string& where) {
  const double limit = k == 0 ? kMissDepth2Bit : kMissDepthDistance;
  if (o.truth && o.voxcd[k]) ++t.tp;
  if (!o.truth && !o.voxcd[k]) ++t.tn;
  if (o.truth && !o.voxcd[k]) {
    ++t.fn;
    if (o.depth > limit) ++t.missed_beyond;
    if (o.depth > t.worst_missed_depth) t.worst_missed_depth = o.depth, t.worst_missed = where;
  }
  if (!o.truth && o.voxcd[k]) {
    ++t.fp;
    if (o.separation > kFalseSeparation) ++t.false_beyond;
    if (o.separation > t.worst_false_separation) t.worst_false_separation = o.separation, t.worst_false = where;
  }
}

}  // namespace voxcd::test::diff
