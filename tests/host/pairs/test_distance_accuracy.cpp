// Contacts of distance voxmaps against exact geometry (tests/exact_geometry.h: brute-force point-triangle
// distance, ray-parity sign), on random near poses of convex and concave shapes, both directions, SB = 8:
//  - every contact lies inside the other object or within kContactBound voxels of its surface, or, in a
//    conservative cell (a surface the nodes do not resolve), within the 2-bit bound kConservativeBound (docs/pairs.md);
//  - every contact's depth is the exact signed distance within kDepthBound voxels inside the band (and at least
//    the band, less that, deeper);
//  - no pose whose shell points reach deeper than kMissedDepth voxels into the other object goes without a contact;
//  - an object wholly inside another is found.
// Seed: printed at start; VOXCD_SEED replays it.
#include <gtest/gtest.h>

#include <cstdlib>
#include <memory>
#include <random>

#include "tests/exact_geometry.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/pairs/collide.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

// Signed distance to a closed mesh: negative inside.
double signed_distance(const Mesh& m, const Eigen::Vector3d& p) {
  const double d = test::mesh_distance(m, p);
  return test::inside_reference(m, p) ? -d : d;
}

// The documented bounds, in voxels of the object whose field is read (docs/pairs.md derives them).
constexpr double kContactBound = 0.25;
constexpr double kDepthBound = 0.5;
constexpr double kMissedDepth = 0.5;
constexpr double kDeepSlack = 1.0;  // deeper than the band less 2 voxels: clamped corners (docs/pairs.md)
constexpr double kConservativeBound = 1.7321 + 0.01;  // a hit cell's diagonal, plus the fixed-point share

uint64_t test_seed() { return test::seed(20261124); }

struct Loaded {
  Mesh mesh;
  std::shared_ptr<ObjectType> type;
};

Loaded load(const std::string& shape, double voxel, int bits, double scale = 1) {
  Loaded l;
  std::string source;
  uint64_t hash = 0;
  l.mesh = load_source(shape, &source, &hash);
  for (Eigen::Vector3d& v : l.mesh.vertices) v *= scale;
  ObjectOptions oo;
  oo.voxel = voxel;
  oo.distance_bits = bits;
  l.type = std::make_shared<ObjectType>(make_object_type(make_object(l.mesh, source, hash, oo), shape));
  return l;
}

struct Stats {
  size_t poses = 0, touching = 0, contacts = 0, checked = 0, outside_bound = 0, depth_off = 0, missed = 0,
         conservative = 0;
  double worst_outside = -1e9, worst_depth_error = 0, worst_deep_short = -1e9, deepest_missed = 0;
};

void run_pair(const std::string& a, const std::string& b, uint64_t seed, Stats& st) {
  const Mesh ma = load_source(a), mb = load_source(b);
  Eigen::Vector3d lo, hi;
  ma.bounds(lo, hi);
  double side = (hi - lo).maxCoeff();
  mb.bounds(lo, hi);
  side = std::max(side, (hi - lo).maxCoeff());
  const double voxel = side / 24;
  const Loaded la = load(a, voxel, 8), lb = load(b, voxel, 8);
  const DeviceConfig cfg = device_config_for("cpu", 4, {la.type.get(), lb.type.get()}, 8);
  PairCollider col(make_device("cpu", cfg), {la.type, lb.type});
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PairRequest> reqs;
  const double reach = la.type->radius + lb.type->radius;
  for (int k = 0; k < 40; ++k) {
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_a.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    r.pose_b.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    Eigen::Vector3d d(n(rng), n(rng), n(rng));
    // Mostly near touching: the shells' spheres overlap by a little.
    d = d.normalized() * reach * (0.55 + 0.45 * u(rng));
    r.pose_a.translation = -(r.pose_a.rotation * la.type->centre);
    r.pose_b.translation = d - r.pose_b.rotation * lb.type->centre;
    reqs.push_back(r);
  }
  PairOptions opt;
  opt.both_directions = true;
  const std::vector<PairResult> res = col.collide(reqs, opt);
  for (size_t i = 0; i < reqs.size(); ++i) {
    ++st.poses;
    const PairRequest& r = reqs[i];
    st.touching += !res[i].contacts.empty();
    st.contacts += res[i].contacts.size();
    // At most ~150 contacts a pose, spread over the list, against the exact surface.
    const size_t stride = std::max<size_t>(1, res[i].contacts.size() / 150);
    for (size_t k = 0; k < res[i].contacts.size(); k += stride) {
      const Contact& c = res[i].contacts[k];
      const Mesh& other = c.a_in_b ? mb : ma;
      const RigidPose& po = c.a_in_b ? r.pose_b : r.pose_a;
      const Eigen::Vector3d local = po.rotation.conjugate() * (c.position - po.translation);
      const double d = signed_distance(other, local) / voxel;
      ++st.checked;
      const ObjectType& ot = *(c.a_in_b ? lb : la).type;
      const auto& v = c.voxel;
      if (ot.object.distance.near_conservative(ot.voxmap(), v[0], v[1], v[2])) {
        // A conservative cell: the 2-bit bound, and no depth to check (the nodes were lowered to 0).
        ++st.conservative;
        if (d > kConservativeBound) ++st.outside_bound;
        continue;
      }
      st.worst_outside = std::max(st.worst_outside, d);
      if (d > kContactBound) ++st.outside_bound;
      // Where the whole cell lies within the band (the point 2 voxels inside its edge: a cell's corners are within
      // sqrt(3) of it) the depth is the exact distance within kDepthBound; deeper, nodes are clamped far inside and
      // the depth is at least the smaller of the depth and the band, less kDeepSlack.
      const double band = (c.a_in_b ? lb : la).type->object.distance.band();
      const double depth = c.depth / voxel;  // positive inside, as -d
      if (-d <= band - 2) {
        const double err = std::abs(depth + d);
        st.worst_depth_error = std::max(st.worst_depth_error, err);
        if (err > kDepthBound) ++st.depth_off;
      } else {
        const double short_by = std::min(-d, band) - kDeepSlack - depth;
        st.worst_deep_short = std::max(st.worst_deep_short, short_by);
        if (short_by > 0) ++st.depth_off;
      }
    }
    if (!res[i].contacts.empty()) continue;
    // No contact: no shell point may lie deeper than kMissedDepth inside the other object.
    double deepest = 0;
    for (int dir = 0; dir < 2; ++dir) {
      const ObjectType& s = *(dir == 0 ? la.type : lb.type);
      const Mesh& other = dir == 0 ? mb : ma;
      const RigidPose& ps = dir == 0 ? r.pose_a : r.pose_b;
      const RigidPose& po = dir == 0 ? r.pose_b : r.pose_a;
      const double reach_o = (dir == 0 ? lb : la).type->radius;
      const Eigen::Vector3d oc = po.rotation * (dir == 0 ? lb : la).type->centre + po.translation;
      for (const Eigen::Vector3d& p : s.shell().points) {
        const Eigen::Vector3d w = ps.rotation * p + ps.translation;
        if ((w - oc).norm() > reach_o) continue;  // outside the other's enclosing sphere: outside it
        deepest = std::max(deepest, -signed_distance(other, po.rotation.conjugate() * (w - po.translation)) / voxel);
      }
    }
    st.deepest_missed = std::max(st.deepest_missed, deepest);
    if (deepest > kMissedDepth) ++st.missed;
  }
}

TEST(DistanceAccuracy, ContactsAgainstExactGeometry) {
  const uint64_t seed = test_seed();
  std::printf("distance accuracy \n");
  const std::pair<const char*, const char*> cases[] = {
      {"sphere", "cube"}, {"torus", "stellated"}, {"stellated", "torus"}, {"polytope36", "sphere"}, {"cube", "torus"}};
  size_t k = 0;
  for (const auto& [a, b] : cases) {
    Stats st;
    run_pair(a, b, seed + k++, st);
    std::printf("%-10s in %-10s poses %zu touching %zu contacts %zu checked %zu (%zu in conservative cells): farthest "
                "outside %.3f voxel, worst depth error %.3f voxel (deep: short by %.3f), deepest without contact %.3f "
                "voxel\n",
                a, b, st.poses, st.touching, st.contacts, st.checked, st.conservative, st.worst_outside,
                st.worst_depth_error, st.worst_deep_short, st.deepest_missed);
    EXPECT_GT(st.touching, st.poses / 5) << a << " / " << b << ": the poses must exercise contacts";
    EXPECT_EQ(st.outside_bound, 0u) << a << " / " << b << ": contacts farther than " << kContactBound
                                    << " voxel outside the other object (worst " << st.worst_outside << ")";
    EXPECT_EQ(st.depth_off, 0u) << a << " / " << b << ": depths off by more than " << kDepthBound << " voxel (worst "
                                << st.worst_depth_error << ")";
    EXPECT_EQ(st.missed, 0u) << a << " / " << b << ": poses deeper than " << kMissedDepth
                             << " voxel without a contact (deepest " << st.deepest_missed << ")";
  }
}

TEST(DistanceAccuracy, ContainmentIsFound) {
  // A sphere a fifth of the cube's size wholly inside it, far from its faces: every shell point is deep inside
  // (clamped far inside), and still a contact.
  Eigen::Vector3d lo, hi;
  load_source("cube").bounds(lo, hi);
  const double cube_side = (hi - lo).maxCoeff();
  load_source("sphere").bounds(lo, hi);
  const double scale = 0.2 * cube_side / (hi - lo).maxCoeff();
  const double voxel = cube_side / 40;
  const Loaded big = load("cube", voxel, 8), small = load("sphere", voxel, 8, scale);
  const DeviceConfig cfg = device_config_for("cpu", 4, {big.type.get(), small.type.get()}, 8);
  PairCollider col(make_device("cpu", cfg), {big.type, small.type});
  PairRequest r;
  r.a = 1;
  r.b = 0;
  r.pose_a.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()));
  r.pose_a.translation = big.type->centre - r.pose_a.rotation * small.type->centre;
  PairOptions one_way;  // the sphere's shell in the cube's field
  one_way.both_directions = false;
  const PairResult res = col.collide({r}, one_way)[0];
  EXPECT_EQ(res.contacts.size(), small.type->shell().size()) << "every shell point of the contained sphere";
  for (const Contact& c : res.contacts) EXPECT_GT(c.depth, 2 * voxel);
}

}  // namespace
}  // namespace voxcd
