// The room-and-robot scene of bench_contacts (docs/pairs.md, "Speed near the machine's limit"): objects of few
// triangles that fill a large space, where most of a query's shell points land in empty air. The room (4 x 4 x 2.5
// units, 2,148 triangles): a floor, thin walls with a door, a table, two chairs, a shelf, a sofa, two lamps and
// open tubes (pipes without caps: an open mesh, as exports have them). The robot (1.1 units tall, 212 triangles):
// a base, a column, two arm links, a wrist, a gripper of two fingers and a shoulder joint.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"

namespace voxcd::bench {

inline void append(Mesh& to, const Mesh& m) {
  const uint32_t base = uint32_t(to.vertices.size());
  to.vertices.insert(to.vertices.end(), m.vertices.begin(), m.vertices.end());
  for (const auto& t : m.triangles) to.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

inline void add_box(Mesh& to, double x0, double y0, double z0, double x1, double y1, double z1) {
  append(to, make_box(Eigen::Vector3d(x0, y0, z0), Eigen::Vector3d(x1, y1, z1)));
}

// A cylinder about an axis from `a` to `b` of `segments` sides and `rings` bands; with caps (closed, outward) or
// without (an open tube: a single surface with two boundary loops).
inline Mesh cylinder(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double r, int segments, int rings,
                     bool caps) {
  Mesh m;
  const Eigen::Vector3d axis = (b - a).normalized();
  const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  for (int k = 0; k <= rings; ++k)
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * M_PI * s / segments;
      m.vertices.push_back(a + (b - a) * (double(k) / rings) + r * (std::cos(phi) * u + std::sin(phi) * v));
    }
  auto at = [&](int k, int s) { return uint32_t(k * segments + (s % segments)); };
  for (int k = 0; k < rings; ++k)
    for (int s = 0; s < segments; ++s) {
      m.triangles.push_back({at(k, s), at(k, s + 1), at(k + 1, s + 1)});
      m.triangles.push_back({at(k, s), at(k + 1, s + 1), at(k + 1, s)});
    }
  if (caps) {
    const uint32_t ca = uint32_t(m.vertices.size()), cb = ca + 1;
    m.vertices.push_back(a);
    m.vertices.push_back(b);
    for (int s = 0; s < segments; ++s) {
      m.triangles.push_back({ca, at(0, s + 1), at(0, s)});
      m.triangles.push_back({cb, at(rings, s), at(rings, s + 1)});
    }
  }
  return m;
}

inline Mesh make_room() {
  Mesh m;
  const double w = 0.06;  // walls and boards: about one voxel at the room's size / 64
  add_box(m, 0, 0, -w, 4, 4, 0);                                             // floor
  add_box(m, -w, 0, 0, 0, 4, 2.5), add_box(m, 4, 0, 0, 4 + w, 4, 2.5);       // walls x = 0, x = 4
  add_box(m, 0, 4, 0, 4, 4 + w, 2.5);                                        // wall y = 4
  add_box(m, 0, -w, 0, 1.5, 0, 2.5), add_box(m, 2.4, -w, 0, 4, 0, 2.5);      // wall y = 0 with a door
  add_box(m, 1.5, -w, 2.0, 2.4, 0, 2.5);                                     // its lintel
  // A table and two chairs.
  add_box(m, 1.4, 1.6, 0.72, 2.6, 2.4, 0.76);
  for (double x : {1.45, 2.5})
    for (double y : {1.65, 2.3}) add_box(m, x, y, 0, x + 0.05, y + 0.05, 0.72);
  for (double cx : {1.7, 2.2}) {
    const double y0 = 1.1, y1 = 1.5;
    add_box(m, cx - 0.2, y0, 0.44, cx + 0.2, y1, 0.47);
    for (double x : {cx - 0.2, cx + 0.16})
      for (double y : {y0, y1 - 0.04}) add_box(m, x, y, 0, x + 0.04, y + 0.04, 0.44);
    add_box(m, cx - 0.2, y0 - 0.03, 0.47, cx + 0.2, y0, 0.9);
  }
  // A shelf against the wall y = 4: two sides and five boards.
  add_box(m, 2.8, 3.6, 0, 2.83, 4, 1.9), add_box(m, 3.77, 3.6, 0, 3.8, 4, 1.9);
  for (double z : {0.05, 0.5, 0.95, 1.4, 1.87}) add_box(m, 2.83, 3.6, z, 3.77, 4, z + 0.03);
  // A sofa: a seat, a back and two arms.
  add_box(m, 0.1, 2.6, 0, 0.9, 3.9, 0.42), add_box(m, 0.1, 2.6, 0.42, 0.3, 3.9, 0.85);
  add_box(m, 0.3, 2.6, 0.42, 0.9, 2.75, 0.62), add_box(m, 0.3, 3.75, 0.42, 0.9, 3.9, 0.62);
  // Two lamps: a shade (a sphere) on a stand.
  append(m, make_icosphere(Eigen::Vector3d(2.0, 2.0, 1.05), 0.15, 2));
  append(m, cylinder(Eigen::Vector3d(2.0, 2.0, 0.76), Eigen::Vector3d(2.0, 2.0, 0.9), 0.015, 8, 1, true));
  append(m, make_icosphere(Eigen::Vector3d(0.5, 0.5, 1.6), 0.2, 2));
  append(m, cylinder(Eigen::Vector3d(0.5, 0.5, 0), Eigen::Vector3d(0.5, 0.5, 1.4), 0.02, 8, 1, true));
  // Open tubes: a heating pipe along two walls and a vertical pipe in a corner.
  append(m, cylinder(Eigen::Vector3d(0.1, 0.15, 0.3), Eigen::Vector3d(3.9, 0.15, 0.3), 0.05, 24, 6, false));
  append(m, cylinder(Eigen::Vector3d(3.85, 0.3, 0.3), Eigen::Vector3d(3.85, 3.5, 0.3), 0.05, 24, 6, false));
  append(m, cylinder(Eigen::Vector3d(3.8, 3.8, 0.0), Eigen::Vector3d(3.8, 3.8, 2.5), 0.08, 32, 7, false));
  m.name = "room";
  return m;
}

inline Mesh make_robot() {
  Mesh m;
  add_box(m, -0.25, -0.25, 0, 0.25, 0.25, 0.1);                // base
  add_box(m, -0.06, -0.06, 0.1, 0.06, 0.06, 0.6);              // column
  append(m, make_icosphere(Eigen::Vector3d(0, 0, 0.65), 0.09, 1));  // shoulder
  add_box(m, 0.0, -0.05, 0.6, 0.5, 0.05, 0.7);                 // upper arm
  add_box(m, 0.45, -0.04, 0.7, 0.55, 0.04, 1.1);               // forearm
  append(m, cylinder(Eigen::Vector3d(0.5, 0, 1.1), Eigen::Vector3d(0.75, 0, 1.1), 0.04, 12, 1, true));  // wrist
  add_box(m, 0.75, -0.08, 1.07, 0.8, 0.08, 1.13);              // palm
  add_box(m, 0.8, -0.08, 1.08, 0.95, -0.05, 1.12), add_box(m, 0.8, 0.05, 1.08, 0.95, 0.08, 1.12);  // fingers
  m.name = "robot";
  return m;
}

// `n` poses of the robot (B) in the room (A at the identity): anywhere over the floor, turned about every axis,
// most touching the furniture, the walls or the floor.
inline std::vector<PairRequest> robot_poses(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g(0, 1);
  std::vector<PairRequest> out;
  for (size_t k = 0; k < n; ++k) {
    PairRequest r;
    r.a = 0, r.b = 1;
    r.pose_b.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    r.pose_b.translation = Eigen::Vector3d(0.3 + 3.4 * u(rng), 0.3 + 3.4 * u(rng), 0.2 + 1.6 * u(rng));
    out.push_back(r);
  }
  return out;
}

// `n` poses of torus B about torus A (A at the identity), B's centre within 1.2 of A's: most interpenetrate.
inline std::vector<PairRequest> torus_poses(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PairRequest> out;
  for (size_t k = 0; k < n; ++k) {
    PairRequest r;
    r.a = 0, r.b = 1;
    r.pose_b.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    r.pose_b.translation = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized() * 1.2 * std::cbrt(u(rng));
    out.push_back(r);
  }
  return out;
}

}  // namespace voxcd::bench
