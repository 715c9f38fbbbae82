// Pair tests against exact geometry (brute force on the meshes): every contact lies inside the other object or
// within sqrt(3) of its voxels of its surface, and within one voxel along each of its grid's axes; its depth estimate is within sqrt(3) voxels of the true depth; and
// wherever one mesh's surface reaches deeper into the other than the documented depth, contacts are reported,
// also when one object lies wholly inside the other. All backends give the same contacts. docs/pairs.md states
// the bounds. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/pairs/detail/cull.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/ref/float_model.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

// Signed depth of a point in a closed mesh: + inside, - outside.
double signed_depth(const Mesh& m, const Eigen::Vector3d& p) {
  const double d = test::mesh_distance(m, p);
  return test::inside_reference(m, p) ? d : -d;
}

Mesh transformed(const Mesh& m, const RigidPose& pose) {
  Mesh out = m;
  for (auto& v : out.vertices) v = pose.rotation * v + pose.translation;
  return out;
}

std::shared_ptr<const ObjectType> type_of(const Mesh& mesh, double voxel) {
  ObjectOptions o;
  o.voxel = voxel;
  return std::make_shared<ObjectType>(make_object_type(make_object(mesh, mesh.name, 0, o), mesh.name));
}

Eigen::Quaterniond random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

// Points on a mesh's surface: its vertices and `per_triangle` random points on every triangle.
std::vector<Eigen::Vector3d> surface_samples(const Mesh& m, int per_triangle, std::mt19937_64& rng) {
  std::vector<Eigen::Vector3d> s = m.vertices;
  std::uniform_real_distribution<double> u(0, 1);
  for (size_t t = 0; t < m.size(); ++t)
    for (int k = 0; k < per_triangle; ++k) {
      double a = u(rng), b = u(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      s.push_back(m.corner(t, 0) + a * (m.corner(t, 1) - m.corner(t, 0)) + b * (m.corner(t, 2) - m.corner(t, 0)));
    }
  return s;
}

// A lower bound on how deep `a`'s surface reaches into `b`: the deepest of the samples that lie inside b.
double reach_into(const std::vector<Eigen::Vector3d>& samples_a, const Mesh& b) {
  double best = 0;
  for (const auto& p : samples_a)
    if (test::inside_reference(b, p)) best = std::max(best, test::mesh_distance(b, p));
  return best;
}

uint64_t seed() {
  const uint64_t s = test::seed();
  return s;
}

struct Case {
  const char* a;
  const char* b;
};

TEST(Pairs, ContactsAgreeWithExactGeometry) {
  const uint64_t s = seed();
  std::mt19937_64 rng(s);
  const double voxel = 0.12;
  const Case cases[] = {{"torus", "stellated"}, {"sphere", "torus"}, {"polytope36", "cube"}, {"plate", "stellated"}};
  size_t checked = 0, deep = 0;
  for (const Case& c : cases) {
    const Mesh ma = make_shape(c.a), mb = make_shape(c.b);
    auto ta = type_of(ma, voxel), tb = type_of(mb, voxel);
    PairCollider col(make_device("cpu", DeviceConfig{}), {ta, tb});
    const DeviceConfig& cfg = col.device().config();
    // The fixed-point error, in B's voxels, for shell coordinates up to the largest shell grid.
    const double max_p = 2.0 * double(std::max(ta->shell().grid.dims[0], std::max(ta->shell().grid.dims[1], ta->shell().grid.dims[2])));
    const double slack = 3 * std::ldexp(1.0, -(cfg.MF + 1)) * max_p + std::ldexp(1.0, -(cfg.TF() + 1)) + 1e-9;
    std::vector<PairRequest> reqs;
    std::uniform_real_distribution<double> u(-1, 1);
    for (int k = 0; k < 12; ++k) {
      PairRequest r;
      r.a = 0;
      r.b = 1;
      r.pose_a.rotation = random_rotation(rng);
      r.pose_b.rotation = random_rotation(rng);
      r.pose_b.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.2;
      reqs.push_back(r);
    }
    PairOptions opt;
    opt.both_directions = true;
    const std::vector<PairResult> res = col.collide(reqs, opt);
    for (size_t i = 0; i < reqs.size(); ++i) {
      const Mesh wa = transformed(ma, reqs[i].pose_a), wb = transformed(mb, reqs[i].pose_b);
      for (const Contact& ct : res[i].contacts) {
        const Mesh& other = ct.a_in_b ? wb : wa;
        const double v = (ct.a_in_b ? tb : ta)->voxmap().voxel();
        const double sd = signed_depth(other, ct.position);
        // A hit voxel is a surface voxel (within sqrt(3) voxels of the surface) or wholly inside.
        ASSERT_GE(sd, -(std::sqrt(3.0) + slack) * v)
            << c.a << "/" << c.b << " pair " << i << " seed " << s << ": contact at " << ct.position.transpose()
            << " is " << -sd / v << " voxels outside the other object";
        if (sd < 0) {
          // ... and so within one voxel of the surface along each axis of the other object's grid (the max norm in
          // its own frame, where its mesh is `m`).
          const RigidPose& pose = ct.a_in_b ? reqs[i].pose_b : reqs[i].pose_a;
          const Mesh& m = ct.a_in_b ? mb : ma;
          const double dmax =
              test::mesh_distance_max_norm(m, pose.rotation.conjugate() * (ct.position - pose.translation));
          ASSERT_LE(dmax, (1 + slack + 1e-5) * v)
              << c.a << "/" << c.b << " pair " << i << " seed " << s << ": contact at " << ct.position.transpose()
              << " is " << dmax / v << " voxels (max norm) outside the other object";
        }
        ASSERT_LE(std::fabs(ct.depth - std::max(sd, 0.0)), (std::sqrt(3.0) + slack) * v)
            << c.a << "/" << c.b << " pair " << i << " seed " << s << ": depth estimate " << ct.depth
            << " against the true depth " << sd;
        ++checked;
      }
      // Completeness: a surface reaching deeper than the bound into the other object must be seen.
      const auto sa = surface_samples(wa, 3, rng), sb = surface_samples(wb, 3, rng);
      const double ha = ta->shell().grid.voxel, hb = tb->shell().grid.voxel;
      const double need_a = std::sqrt(3.0) / 2 * ha + slack * tb->voxmap().voxel();
      const double need_b = std::sqrt(3.0) / 2 * hb + slack * ta->voxmap().voxel();
      if (reach_into(sa, wb) > need_a || reach_into(sb, wa) > need_b) {
        ++deep;
        EXPECT_GT(res[i].hits, 0u) << c.a << "/" << c.b << " pair " << i << " seed " << s
                                   << ": the meshes interpenetrate deeper than the bound but no contact";
      }
    }
  }
  std::printf("%zu contacts checked, %zu deep poses\n", checked, deep);
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(deep, 5u) << "the random poses must include deep interpenetrations";
}

TEST(Pairs, FullContainmentIsSeenFromTheInsideObject) {
  // A small box wholly inside a large sphere, touching nothing: the box's shell lies in the sphere's interior;
  // the sphere's shell lies outside the box.
  const Mesh big = make_icosphere(Eigen::Vector3d::Zero(), 1.0, 3);
  const Mesh small = make_box(Eigen::Vector3d::Constant(-0.2), Eigen::Vector3d::Constant(0.2));
  auto tbig = type_of(big, 0.1), tsmall = type_of(small, 0.1);
  PairCollider col(make_device("cpu", DeviceConfig{}), {tbig, tsmall});
  PairRequest r;
  r.a = 0;  // the sphere is A
  r.b = 1;
  r.pose_b.translation = Eigen::Vector3d(0.1, -0.15, 0.05);
  PairOptions one_way;
  one_way.both_directions = false;
  const PairResult a_in_b = col.collide({r}, one_way)[0];
  EXPECT_EQ(a_in_b.hits, 0u) << "the sphere's shell is outside the box: one direction alone misses containment";
  PairOptions both;
  both.both_directions = true;
  const PairResult res = col.collide({r}, both)[0];
  ASSERT_GT(res.hits, 0u) << "the box's shell lies inside the sphere";
  for (const Contact& c : res.contacts) {
    EXPECT_FALSE(c.a_in_b);
    EXPECT_EQ(c.state, kInterior);
    // Deep inside: the estimate is within sqrt(3) voxels of the true depth (at least 1 - 0.2*sqrt(3) - 0.3).
    EXPECT_GT(c.depth, 0.3);
  }
}

TEST(Pairs, EveryBackendGivesTheSameContacts) {
  const uint64_t s = seed();
  std::mt19937_64 rng(s + 1);
  auto ta = type_of(make_shape("stellated"), 0.15), tb = type_of(make_shape("torus"), 0.15);
  std::vector<PairRequest> reqs;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 40; ++k) {
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_a.rotation = random_rotation(rng);
    r.pose_b.rotation = random_rotation(rng);
    r.pose_b.translation = Eigen::Vector3d(u(rng), u(rng), u(rng));
    reqs.push_back(r);
  }
  std::vector<std::string> backends = {"ref", "cpu"};
  if (!rtl_lanes().empty()) backends.push_back("rtl");
  for (Mode mode : {Mode::All, Mode::First, Mode::Count}) {
    PairOptions opt;
    opt.mode = mode;
    opt.both_directions = true;
    std::vector<std::vector<PairResult>> all;
    for (const auto& b : backends) {
      PairCollider col(make_device(b, DeviceConfig{}), {ta, tb});
      all.push_back(col.collide(reqs, opt));
    }
    size_t hits = 0;
    for (size_t bi = 1; bi < backends.size(); ++bi)
      for (size_t i = 0; i < reqs.size(); ++i) {
        const PairResult &x = all[0][i], &y = all[bi][i];
        ASSERT_EQ(x.hits, y.hits) << backends[bi] << " pair " << i << " mode " << mode_name(mode);
        ASSERT_EQ(x.device_cycles, y.device_cycles) << backends[bi] << " pair " << i << " mode " << mode_name(mode);
        ASSERT_EQ(x.contacts.size(), y.contacts.size());
        for (size_t k = 0; k < x.contacts.size(); ++k) {
          EXPECT_EQ(x.contacts[k].point, y.contacts[k].point);
          EXPECT_EQ(x.contacts[k].voxel, y.contacts[k].voxel);
          EXPECT_EQ(x.contacts[k].state, y.contacts[k].state);
          EXPECT_EQ(x.contacts[k].position, y.contacts[k].position);
        }
        if (bi == 1) hits += x.hits;
      }
    EXPECT_GT(hits, 50u) << mode_name(mode) << ": the poses must touch for the comparison to mean something";
  }
}

TEST(Pairs, CullingChangesLookupsButNoContact) {
  // PairOptions::cull submits only the clusters of shell points that can land in the other voxmap. Every hit must
  // survive it, in every mode, also with PF = 0 (shell words rounded by half a cell) and narrow matrix formats.
  const uint64_t s = seed();
  std::mt19937_64 rng(s + 2);
  auto ta = type_of(make_shape("stellated"), 0.1), tb = type_of(make_shape("torus"), 0.12);
  std::vector<PairRequest> reqs;
  std::uniform_real_distribution<double> u(-1, 1), dist(0, 3.5);
  for (int k = 0; k < 80; ++k) {
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_a.rotation = random_rotation(rng);
    r.pose_b.rotation = random_rotation(rng);
    r.pose_b.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * dist(rng);
    reqs.push_back(r);
  }
  DeviceConfig narrow;
  narrow.PF = 0;
  narrow.MF = 10;
  narrow.MW = 12;
  for (const DeviceConfig& cfg : {DeviceConfig{}, narrow}) {
    for (Mode mode : {Mode::All, Mode::First, Mode::Count}) {
      PairOptions on, off;
      on.mode = off.mode = mode;
      on.both_directions = off.both_directions = true;
      off.cull = false;
      PairCollider col(make_device("cpu", fit_memory(cfg, {ta.get(), tb.get()})), {ta, tb});
      const std::vector<PairResult> x = col.collide(reqs, on), y = col.collide(reqs, off);
      uint64_t lookups_on = 0, lookups_off = 0, hits = 0;
      for (size_t i = 0; i < reqs.size(); ++i) {
        SCOPED_TRACE("pair " + std::to_string(i) + " mode " + mode_name(mode) + " PF " + std::to_string(cfg.PF));
        ASSERT_EQ(x[i].hits, y[i].hits);
        ASSERT_EQ(x[i].contacts.size(), y[i].contacts.size());
        for (size_t k = 0; k < x[i].contacts.size(); ++k) {
          EXPECT_EQ(x[i].contacts[k].a_in_b, y[i].contacts[k].a_in_b);
          EXPECT_EQ(x[i].contacts[k].point, y[i].contacts[k].point);
          EXPECT_EQ(x[i].contacts[k].voxel, y[i].contacts[k].voxel);
          EXPECT_EQ(x[i].contacts[k].depth, y[i].contacts[k].depth);
        }
        EXPECT_LE(x[i].lookups, y[i].lookups);
        lookups_on += x[i].lookups, lookups_off += y[i].lookups, hits += x[i].hits;
      }
      EXPECT_GT(hits, 50u) << mode_name(mode);
      EXPECT_LT(4 * lookups_on, 3 * lookups_off) << "culling should leave out a quarter of the points of these poses";
      if (mode == Mode::All && cfg.PF == 8)
        std::printf("culling: %llu of %llu lookups, %llu hits\n", (unsigned long long)lookups_on,
                    (unsigned long long)lookups_off, (unsigned long long)hits);
    }
  }
}

// The cluster cull's two kernels (AVX-512 where the processor has it, the portable loop) keep the same boxes, and
// keep every box with a point that lands in the map: its centre, its corners and random points inside it are tried.
TEST(Pairs, CullKernelsAgreeAndKeepEveryBoxThatCanLand) {
  std::printf("cull kernel: %s\n", detail::cull_is_vector() ? "avx512" : "portable");
  std::mt19937_64 rng(seed() + 7);
  std::uniform_real_distribution<double> u(0, 1);
  const double n[3] = {11, 9, 8};
  uint64_t kept = 0, culled = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const size_t nb = 1 + size_t(u(rng) * 150);  // one box to three words, tails of every length
    std::vector<double> centre[3], half[3];
    for (int i = 0; i < 3; ++i)
      for (size_t k = 0; k < nb; ++k) centre[i].push_back(40 * u(rng)), half[i].push_back(0.5 + 6 * u(rng));
    const Eigen::Matrix3d R = random_rotation(rng).toRotationMatrix() * (0.5 + 1.5 * u(rng));
    double M[3][3], aM[3][3], t[3];
    // The middle of the boxes' region lands near the map's middle, within 12 cells.
    const Eigen::Vector3d mid = R * Eigen::Vector3d(20, 20, 20);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) M[i][j] = R(i, j), aM[i][j] = std::abs(R(i, j));
      t[i] = 0.5 * n[i] - mid[i] + 24 * u(rng) - 12;
    }
    const detail::ClusterBoxes boxes{{centre[0].data(), centre[1].data(), centre[2].data()},
                                     {half[0].data(), half[1].data(), half[2].data()},
                                     nb};
    std::vector<uint64_t> vec((nb + 63) / 64, ~uint64_t(0)), port((nb + 63) / 64, ~uint64_t(0));
    detail::cull_clusters(boxes, M, aM, t, n, vec.data(), true);
    detail::cull_clusters(boxes, M, aM, t, n, port.data(), false);
    ASSERT_EQ(vec, port) << "trial " << trial << ", " << nb << " boxes";
    for (size_t k = 0; k < nb; ++k) {
      const bool bit = (vec[k / 64] >> (k % 64)) & 1;
      (bit ? kept : culled) += 1;
      if (bit) continue;
      for (int s = 0; s < 40; ++s) {
        double p[3];
        for (int i = 0; i < 3; ++i) {
          // the centre, the eight corners, then random points of the box
          const double f = s == 0 ? 0 : s <= 8 ? (((s - 1) >> i) & 1 ? 1 : -1) : 2 * u(rng) - 1;
          p[i] = centre[i][k] + f * half[i][k];
        }
        bool inside = true;
        for (int i = 0; i < 3; ++i) {
          const double q = M[i][0] * p[0] + M[i][1] * p[1] + M[i][2] * p[2] + t[i];
          inside &= q >= 0 && q < n[i];
        }
        ASSERT_FALSE(inside) << "trial " << trial << ": box " << k << " was culled but its point " << s
                             << " lands in the map";
      }
    }
  }
  // Both outcomes are common, so the comparison above means something.
  EXPECT_GT(kept, 1000u);
  EXPECT_GT(culled, 1000u);
}

TEST(Pairs, BadPosesAndFullMemoryAreErrorsThatNameThePair) {
  auto t = type_of(make_shape("cube"), 0.25);
  PairCollider col(make_device("cpu", DeviceConfig{}), {t, t});
  PairRequest r;
  r.pose_b.translation.x() = std::nan("");
  try {
    col.collide({PairRequest{}, r});
    ADD_FAILURE() << "a NaN pose was accepted";
  } catch (const RangeError& e) {
    EXPECT_NE(std::string(e.what()).find("pair 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
  r = PairRequest{};
  r.pose_b.translation.x() = 1e9;  // far beyond TW = 48 bits of voxels
  EXPECT_THROW(col.collide({r}), RangeError);
  DeviceConfig tiny;
  tiny.SAW = 6;  // 64 shell words
  try {
    PairCollider small(make_device("cpu", tiny), {t});
    ADD_FAILURE() << "a shell of " << t->shell().size() << " points fit 64 words";
  } catch (const CapacityError& e) {
    EXPECT_NE(std::string(e.what()).find("2^SAW = 64"), std::string::npos) << e.what();
  }
  const DeviceConfig fitted = fit_memory(tiny, {t.get(), t.get()});
  EXPECT_GE(fitted.shell_depth(), 2 * t->shell().size());
  EXPECT_LT(fitted.shell_depth(), 4 * t->shell().size()) << "grown to fit, not beyond";
}

}  // namespace
}  // namespace voxcd
