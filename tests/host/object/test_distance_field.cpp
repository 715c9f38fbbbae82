// Distance fields and shells on the surface (host/object/distance_field.h, surface_shell): every node value against
// an independent brute force (point-triangle distance over every triangle, the sign from the winding number summed
// over every triangle), the device's memory image read back through ref/'s fetch_nodes, object files of version 3
// and the unchanged version 2, shell points on the surface within the rounding bound, and the errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>

#include "tests/defects.h"
#include "tests/error_text.h"
#include "tests/host/test_util.h"
#include "voxcd/host/object/detail/unresolved.h"
#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {
namespace {

// ---- Brute force, written apart from the library ----

// Distance from p to segment ab.
double segment_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

// Distance from p to triangle abc: to the plane when p projects inside, else to the nearest edge.
double triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                         const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (n2 > 0) {
    const Eigen::Vector3d q = p - n * (n.dot(p - a) / n2);
    const bool in = n.dot((b - a).cross(q - a)) >= 0 && n.dot((c - b).cross(q - b)) >= 0 &&
                    n.dot((a - c).cross(q - c)) >= 0;
    if (in) return std::abs(n.dot(p - a)) / std::sqrt(n2);
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

double mesh_distance(const Mesh& m, const Eigen::Vector3d& p) {
  double d = HUGE_VAL;
  for (size_t t = 0; t < m.size(); ++t) d = std::min(d, triangle_distance(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)));
  return d;
}

// The generalized winding number at p: the solid angles of the (non-sheet) triangles over 4 pi, each by
// l'Huilier's theorem on the spherical triangle's sides, signed by orientation.
double winding_number(const Mesh& m, const Eigen::Vector3d& p) {
  double w = 0;
  for (size_t t = 0; t < m.size(); ++t) {
    if (m.is_sheet(t)) continue;
    const Eigen::Vector3d a = (m.corner(t, 0) - p).normalized(), b = (m.corner(t, 1) - p).normalized(),
                          c = (m.corner(t, 2) - p).normalized();
    auto side = [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) { return 2 * std::asin(std::min(1.0, (u - v).norm() / 2)); };
    const double x = side(b, c), y = side(c, a), z = side(a, b), s = (x + y + z) / 2;
    const double e = 4 * std::atan(std::sqrt(std::max(0.0, std::tan(s / 2) * std::tan((s - x) / 2) *
                                                             std::tan((s - y) / 2) * std::tan((s - z) / 2))));
    const double sign = a.dot(b.cross(c)) >= 0 ? 1 : -1;
    w += sign * e;
  }
  return w / (4 * M_PI);
}

Eigen::Vector3d node_position(const Voxmap& vm, uint64_t X, uint64_t Y, uint64_t Z) {
  return vm.origin() + vm.voxel() * Eigen::Vector3d(double(X), double(Y), double(Z));
}

struct Checked {
  uint64_t nodes = 0, in_band = 0, inside = 0, ties = 0, skipped = 0;
};

// The brute force at every node of vm's grid (node index order): distance in voxels and winding number.
struct Brute {
  std::vector<double> d, w;
};

Brute brute_force(const Mesh& m, const Voxmap& vm) {
  Brute b;
  for (uint64_t Z = 0; Z <= vm.dims()[2]; ++Z)
    for (uint64_t Y = 0; Y <= vm.dims()[1]; ++Y)
      for (uint64_t X = 0; X <= vm.dims()[0]; ++X) {
        const Eigen::Vector3d p = node_position(vm, X, Y, Z);
        b.d.push_back(mesh_distance(m, p) / vm.voxel());
        b.w.push_back(winding_number(m, p));
      }
  return b;
}

// Every node against clamp(round(d / s)), d the brute-force signed distance in voxels; +-1 only where d / s is within
// 1e-9 of a half-integer. Nodes whose winding number lies within `ambiguous` of 1/2 (only near holes) are skipped.
Checked check_field(const Mesh& m, const Voxmap& vm, const DistanceField& f, const Brute& b, double ambiguous = 0) {
  Checked c;
  EXPECT_EQ(f.dims, vm.dims());
  EXPECT_EQ(f.q.size(), uint64_t(vm.dims()[0] + 1) * (vm.dims()[1] + 1) * (vm.dims()[2] + 1));
  EXPECT_EQ(f.q.size(), b.d.size());
  int failures = 0;
  for (uint64_t Z = 0; Z <= f.dims[2]; ++Z)
    for (uint64_t Y = 0; Y <= f.dims[1]; ++Y)
      for (uint64_t X = 0; X <= f.dims[0]; ++X) {
        const uint64_t i = f.node_index(X, Y, Z);
        const double w = b.w[i];
        if (ambiguous > 0 && std::abs(w - 0.5) < ambiguous) {
          ++c.skipped;
          continue;
        }
        const double d = b.d[i];
        const double sd = w >= 0.5 ? -d : d;
        const double x = sd / f.step;
        const double want = std::clamp(std::round(x), double(f.qmin()), double(f.qmax()));
        const int got = f.at(X, Y, Z);
        ++c.nodes;
        c.in_band += std::abs(x) < f.qmax();
        c.inside += w >= 0.5;
        if (got == want) continue;
        const bool tie = std::abs(std::abs(x - std::trunc(x)) - 0.5) < 1e-9 && std::abs(got - want) == 1;
        // A node on the surface (d ~ 0) may take either sign: both round to 0.
        if (tie) {
          ++c.ties;
          continue;
        }
        if (++failures <= 5)
          ADD_FAILURE() << m.name << ": node (" << X << ", " << Y << ", " << Z << ") holds " << got << ", brute force "
                        << want << " (d = " << sd << " voxels, step " << f.step << ", winding number " << w << ")";
      }
  EXPECT_EQ(failures, 0) << m.name;
  return c;
}

Voxmap voxmap_of(const Mesh& m, double voxel, const Eigen::Vector3d& shift = Eigen::Vector3d::Constant(0.5)) {
  VoxelizeOptions o;
  o.voxel = voxel;
  o.shift = shift;
  return voxelize(m, o);
}

// The measured field, without conservative cells (ConservativeCells* below checks those).
DistanceField field_of(const Mesh& m, const Voxmap& vm, int bits = 8, double band = 4, unsigned threads = 0,
                       bool conservative = false) {
  DistanceOptions o;
  o.bits = bits;
  o.band = band;
  o.threads = threads;
  o.conservative = conservative;
  return distance_field(m, vm, o);
}

double longest(const Mesh& m) {
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  return (hi - lo).maxCoeff();
}

// ---- Node values against brute force ----

TEST(DistanceField, CubeOnAndOffTheNodes) {
  const Mesh m = make_shape("cube");
  // Shift 1 puts the faces exactly on nodes (d = 0 there), shift 0.5 half-way between.
  for (double shift : {1.0, 0.5, 0.3}) {
    const Voxmap vm = voxmap_of(m, 0.25, Eigen::Vector3d::Constant(shift));
    const Brute b = brute_force(m, vm);
    for (int bits : {4, 8, 16}) {
      const DistanceField f = field_of(m, vm, bits, 2.5);
      EXPECT_EQ(f.bits, bits);
      EXPECT_DOUBLE_EQ(f.step, 2.5 / (1 << (bits - 1)));
      const Checked c = check_field(m, vm, f, b);
      EXPECT_GT(c.inside, 0u);
      EXPECT_GT(c.in_band, 0u);
    }
  }
}

TEST(DistanceField, SphereTorusAndStellated) {
  for (const char* name : {"sphere", "torus", "stellated"}) {
    SCOPED_TRACE(name);
    const Mesh m = make_shape(name);
    const Voxmap vm = voxmap_of(m, longest(m) / 16);
    const Brute b = brute_force(m, vm);
    const DistanceField f = field_of(m, vm, 8, 4);
    const Checked c = check_field(m, vm, f, b);
    EXPECT_GT(c.inside, 100u);
    // Inside and outside both clamp somewhere at a band of 1.5 voxels.
    const DistanceField g = field_of(m, vm, 8, 1.5);
    check_field(m, vm, g, b);
    EXPECT_NE(std::find(g.q.begin(), g.q.end(), int16_t(g.qmin())), g.q.end());
    EXPECT_NE(std::find(g.q.begin(), g.q.end(), int16_t(g.qmax())), g.q.end());
  }
}

TEST(DistanceField, RotatedBoxOffTheGrid) {
  std::mt19937_64 rng(test::seed());
  std::printf("seed %llu (VOXCD_SEED)\n", static_cast<unsigned long long>(test::seed()));
  for (int round = 0; round < 3; ++round) {
    Mesh m = make_box(Eigen::Vector3d(-0.7, -0.4, -0.25), Eigen::Vector3d(0.7, 0.4, 0.25));
    std::uniform_real_distribution<double> u(-1, 1);
    Eigen::Quaterniond q(u(rng), u(rng), u(rng), u(rng));
    q.normalize();
    const Eigen::Vector3d t(u(rng) * 3, u(rng) * 3, u(rng) * 3);
    for (auto& v : m.vertices) v = q * v + t;
    m.name = "rotated box " + std::to_string(round);
    const Voxmap vm = voxmap_of(m, 0.1, Eigen::Vector3d(0.1 + 0.3 * round, 0.77, 0.5));
    const Brute b = brute_force(m, vm);
    check_field(m, vm, field_of(m, vm, 16, 3), b);
    check_field(m, vm, field_of(m, vm, 4, 3), b);
  }
}

TEST(DistanceField, MeshWithAHoleAfterRepair) {
  // An icosphere with one hole of 12 triangles, through load-time repair: the winding number closes it, the distance
  // is to the triangles that are there.
  Mesh m = test::icosphere(3);
  std::vector<std::array<uint32_t, 3>> kept;
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  for (size_t t = 0; t < m.size(); ++t) {
    const Eigen::Vector3d c = (m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / 3;
    if (c.normalized().dot(Eigen::Vector3d(0.36, 0.48, 0.8)) > 0.97) continue;
    kept.push_back(m.triangles[t]);
  }
  ASSERT_LT(kept.size(), m.size());
  m.triangles = kept;
  m.name = "icosphere with a hole";
  const MeshReport rep = repair(m);
  ASSERT_GT(rep.open_edges, 0u);
  const Voxmap vm = voxmap_of(m, longest(m) / 16);
  const DistanceField f = field_of(m, vm, 8, 4);
  const Checked c = check_field(m, vm, f, brute_force(m, vm), 0.02);
  EXPECT_GT(c.inside, 100u);
  EXPECT_LT(c.skipped, 20u);
}

TEST(DistanceField, SheetsAreUnsigned) {
  // A square sheet (two triangles): repair marks it a sheet, the field is the unsigned distance.
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0.2}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.name = "sheet";
  repair(m);
  ASSERT_TRUE(m.is_sheet(0));
  const Voxmap vm = voxmap_of(m, 0.1);
  const DistanceField f = field_of(m, vm, 8, 2);
  for (int16_t v : f.q) ASSERT_GE(v, 0);
  const Checked c = check_field(m, vm, f, brute_force(m, vm));
  EXPECT_EQ(c.inside, 0u);
  EXPECT_GT(c.in_band, 0u);
}

TEST(DistanceField, ThreadCountNeverChangesTheField) {
  const Mesh m = make_shape("torus");
  const Voxmap vm = voxmap_of(m, longest(m) / 40);
  for (bool conservative : {false, true}) {
    const DistanceField a = field_of(m, vm, 16, 4, 1, conservative), b = field_of(m, vm, 16, 4, 3, conservative);
    EXPECT_EQ(a.q, b.q);
  }
}

// ---- Conservative cells ----

// The conservative field against the measured one: it only lowers nodes, and only to 0; every lowered node is a
// corner of a cell the surface crosses whose eight nodes are all <= 0 (so every point in it is a hit); and in every
// other cell the surface crosses, the interpolant is at most 1/4 voxel (plus rounding) at random points of the
// surface (sheets: no such cell). Returns the cells whose nodes are all <= 0 among the surface cells.
uint64_t check_conservative(const Mesh& m, const Voxmap& vm, uint64_t seed) {
  const DistanceField raw = field_of(m, vm, 8, 4, 0, false), f = field_of(m, vm, 8, 4, 0, true);
  EXPECT_EQ(raw.q.size(), f.q.size());
  auto all_hit = [&](uint64_t x, uint64_t y, uint64_t z) {
    for (int k = 0; k < 8; ++k)
      if (f.at(x + (k & 1), y + (k >> 1 & 1), z + (k >> 2 & 1)) > 0) return false;
    return true;
  };
  const std::vector<uint64_t> sb = surface_bits(m, vm.grid());
  auto surface = [&](uint64_t x, uint64_t y, uint64_t z) {
    const uint64_t i = vm.index(uint32_t(x), uint32_t(y), uint32_t(z));
    return (sb[i >> 6] >> (i & 63)) & 1;
  };
  int failures = 0;
  for (uint64_t Z = 0; Z <= f.dims[2]; ++Z)
    for (uint64_t Y = 0; Y <= f.dims[1]; ++Y)
      for (uint64_t X = 0; X <= f.dims[0]; ++X) {
        const int a = raw.at(X, Y, Z), b = f.at(X, Y, Z);
        if (a == b) continue;
        bool explained = false;
        for (int k = 0; k < 8 && !explained; ++k) {
          const int64_t x = int64_t(X) - (k & 1), y = int64_t(Y) - (k >> 1 & 1), z = int64_t(Z) - (k >> 2 & 1);
          if (x < 0 || y < 0 || z < 0 || x >= f.dims[0] || y >= f.dims[1] || z >= f.dims[2]) continue;
          explained = surface(x, y, z) && all_hit(x, y, z);
        }
        if (!(a > 0 && b == 0 && explained) && ++failures <= 5)
          ADD_FAILURE() << m.name << ": node (" << X << ", " << Y << ", " << Z << ") measured " << a << ", stored " << b;
      }
  // Random points of the surface.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  for (size_t t = 0; t < m.size(); ++t)
    for (int k = 0; k < 40; ++k) {
      double r1 = u(rng), r2 = u(rng);
      if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
      const Eigen::Vector3d p = m.corner(t, 0) + r1 * (m.corner(t, 1) - m.corner(t, 0)) + r2 * (m.corner(t, 2) - m.corner(t, 0));
      const Eigen::Vector3d g = (p - vm.origin()) / vm.voxel();
      const uint64_t x = uint64_t(g.x()), y = uint64_t(g.y()), z = uint64_t(g.z());
      if (all_hit(x, y, z)) continue;
      EXPECT_FALSE(m.is_sheet(t)) << m.name << ": a sheet's cell is not conservative";
      const double v = f.sample(g);
      if (v > detail::kResolvedTolerance + f.step && ++failures <= 10)
        ADD_FAILURE() << m.name << ": the interpolant is " << v << " voxels at a surface point in cell (" << x << ", "
                      << y << ", " << z << "), which is not conservative";
    }
  EXPECT_EQ(failures, 0) << m.name;
  uint64_t conservative = 0;
  for (uint64_t z = 0; z < f.dims[2]; ++z)
    for (uint64_t y = 0; y < f.dims[1]; ++y)
      for (uint64_t x = 0; x < f.dims[0]; ++x) conservative += surface(x, y, z) && all_hit(x, y, z);
  return conservative;
}

TEST(DistanceField, ConservativeCellsWhereTheNodesDoNotResolveTheSurface) {
  // A plate a quarter voxel thick: no node lies inside it, so every cell it crosses is conservative.
  Mesh plate = make_box(Eigen::Vector3d(-1, -1, -0.0125), Eigen::Vector3d(1, 1, 0.0125));
  plate.name = "plate a quarter voxel thick";
  const Voxmap pv = voxmap_of(plate, 0.1);
  EXPECT_EQ(check_conservative(plate, pv, test::seed()), pv.counts()[kSurface]);
  // A sheet: the same.
  Mesh sheet;
  sheet.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0.2}};
  sheet.triangles = {{0, 1, 2}, {0, 2, 3}};
  sheet.name = "sheet";
  repair(sheet);
  const Voxmap sv = voxmap_of(sheet, 0.1);
  EXPECT_EQ(check_conservative(sheet, sv, test::seed() + 1), sv.counts()[kSurface]);
  // Smooth and sharp closed shapes: some conservative cells at most, and the rest resolved.
  for (const char* name : {"sphere", "torus", "cube", "stellated"}) {
    const Mesh m = make_shape(name);
    const Voxmap vm = voxmap_of(m, longest(m) / 24);
    const uint64_t n = check_conservative(m, vm, test::seed() + 2);
    std::printf("%s: %llu of %llu surface cells conservative\n", name, (unsigned long long)n,
                (unsigned long long)vm.counts()[kSurface]);
    EXPECT_LT(n, vm.counts()[kSurface]) << name;
  }
}

// ---- The device's memory image ----

TEST(DistanceField, DeviceWordsReadBackThroughFetchNodes) {
  const Mesh m = make_shape("stellated");
  const Voxmap vm = voxmap_of(m, longest(m) / 13);
  for (int bits : {4, 8, 16}) {
    const DistanceField f = field_of(m, vm, bits, 3);
    for (int memw : {64, 32}) {
      DeviceConfig cfg;
      cfg.SB = bits;
      cfg.MEMW = memw;
      if (bits == 16 && memw == 32) cfg.MEMW = 16;
      const std::vector<uint64_t> words = f.device_words(cfg);
      Job j;
      j.nx = f.dims[0];
      j.ny = f.dims[1];
      j.nz = f.dims[2];
      ASSERT_EQ(words.size(), map_words(cfg, j));
      for (uint32_t z = 0; z < f.dims[2]; ++z)
        for (uint32_t y = 0; y < f.dims[1]; ++y)
          for (uint32_t x = 0; x < f.dims[0]; ++x) {
            Located l{};
            l.index[0] = x, l.index[1] = y, l.index[2] = z;
            l.inside = true;
            const Nodes n = fetch_nodes(cfg, words, j, l);
            for (int c = 0; c < 8; ++c)
              ASSERT_EQ(n.q[c], f.at(x + (c & 1), y + (c >> 1 & 1), z + (c >> 2 & 1)))
                  << "SB " << bits << " MEMW " << cfg.MEMW << " cell " << x << " " << y << " " << z << " node " << c;
          }
    }
  }
}

// ---- Shells on the surface ----

ShellOptions surface_options(double voxel, unsigned threads = 0) {
  ShellOptions so;
  so.target_voxel = voxel;
  so.on_surface = true;
  so.threads = threads;
  return so;
}

TEST(SurfaceShell, PointsLieOnTheSurfaceWithinTheRoundingBound) {
  for (const char* name : {"cube", "sphere", "stellated", "torus"}) {
    SCOPED_TRACE(name);
    const Mesh m = make_shape(name);
    const double voxel = longest(m) / 12;
    const PointShell s = point_shell(m, surface_options(voxel));
    ASSERT_TRUE(s.on_surface);
    ASSERT_GT(s.size(), 100u);
    ASSERT_EQ(s.coords.size(), s.size());
    const double D = s.grid.voxel;
    const double bound = std::sqrt(3.0) * std::ldexp(1.0, -(kShellFrac + 1)) * D;
    double worst = 0;
    for (size_t k = 0; k < s.size(); ++k) {
      const Eigen::Vector3d g = s.grid_point(k);
      for (int a = 0; a < 3; ++a) {
        // The point is exactly its stored coordinate, inside the closed cube of its cell.
        ASSERT_EQ(g[a] * (1 << kShellFrac), double(s.coords[k][a]));
        ASSERT_GE(g[a], double(s.cells[k][a]));
        ASSERT_LE(g[a], double(s.cells[k][a]) + 1);
      }
      ASSERT_EQ(s.points[k], s.grid.origin + D * g);
      ASSERT_NEAR(s.normals[k].norm(), 1.0, 1e-12);
      worst = std::max(worst, mesh_distance(m, s.points[k]));
    }
    EXPECT_LE(worst, bound * (1 + 1e-9) + 1e-12) << "bound " << bound;
    // Order: voxels' linear index, then z, y, x; no two points equal.
    for (size_t k = 1; k < s.size(); ++k) {
      auto key = [&](size_t i) {
        const auto& c = s.cells[i];
        const uint64_t lin = c[0] + uint64_t(s.grid.dims[0]) * (c[1] + uint64_t(s.grid.dims[1]) * c[2]);
        return std::make_tuple(lin, s.coords[i][2], s.coords[i][1], s.coords[i][0]);
      };
      ASSERT_LT(key(k - 1), key(k)) << k;
    }
  }
}

TEST(SurfaceShell, NormalsPointOutwardAndEverySurfacePointHasOneNear) {
  const Mesh m = make_shape("sphere");
  const PointShell s = point_shell(m, surface_options(0.1));
  for (size_t k = 0; k < s.size(); ++k) ASSERT_GT(s.normals[k].dot(s.points[k].normalized()), 0.99) << k;
  // Every point of the surface lies within sqrt(3) spacings (plus the rounding) of a shell point.
  std::mt19937_64 rng(test::seed());
  std::uniform_real_distribution<double> u(0, 1);
  const double reach = std::sqrt(3.0) * s.grid.voxel * (1 + std::ldexp(1.0, -kShellFrac)) + 1e-12;
  for (int i = 0; i < 2000; ++i) {
    const size_t t = size_t(u(rng) * double(m.size())) % m.size();
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Eigen::Vector3d p = m.corner(t, 0) + a * (m.corner(t, 1) - m.corner(t, 0)) + b * (m.corner(t, 2) - m.corner(t, 0));
    double best = HUGE_VAL;
    for (const auto& q : s.points) best = std::min(best, (q - p).norm());
    ASSERT_LE(best, reach) << "seed " << test::seed() << " sample " << i;
  }
}

TEST(SurfaceShell, CubeEdgesAndCornersTakePseudoNormals) {
  const Mesh m = make_shape("cube");
  const PointShell s = point_shell(m, surface_options(0.3));
  // A point lies "on" every face whose plane is within twice the rounding bound (its closest point before rounding
  // may be within the bound of an edge, and then takes the edge's normal).
  const double tol = 2 * std::sqrt(3.0) * std::ldexp(s.grid.voxel, -(kShellFrac + 1)) * (1 + 1e-9) + 1e-12;
  int faces = 0, edges = 0, corners = 0, edge_normals = 0;
  for (size_t k = 0; k < s.size(); ++k) {
    const Eigen::Vector3d& p = s.points[k];
    bool on[3];
    int count = 0;
    for (int a = 0; a < 3; ++a) count += on[a] = std::abs(std::abs(p[a]) - 1) <= tol;
    ASSERT_GE(count, 1) << "point " << k << " is not on the cube";
    (count == 1 ? faces : count == 2 ? edges : corners)++;
    // The normal is the normalised sum of the outward normals of some of the faces the point is on (a point within
    // the rounding bound of an edge or a corner takes its pseudo-normal): the face's own when on one face only.
    const Eigen::Vector3d& n = s.normals[k];
    int used = 0;
    for (int a = 0; a < 3; ++a) {
      if (std::abs(n[a]) < 1e-12) continue;
      ++used;
      ASSERT_TRUE(on[a]) << k << " at " << p.transpose() << ": normal " << n.transpose();
      ASSERT_GT(n[a] * p[a], 0) << k;
    }
    ASSERT_GE(used, 1);
    for (int a = 0; a < 3; ++a)
      if (std::abs(n[a]) >= 1e-12) {
        ASSERT_NEAR(std::abs(n[a]), 1 / std::sqrt(double(used)), 1e-12) << k;
      }
    if (count == 1) {
      ASSERT_EQ(used, 1) << k;
    }
    edge_normals += count == 2 && used == 2;
  }
  EXPECT_GT(faces, 0);
  EXPECT_GT(edges, 0);
  EXPECT_GT(edge_normals, edges / 2);
  // The grid puts the faces at x, y, z = -1 on voxel centres: the points of the cells around those corners land on
  // them and merge into one each. (The other corners need not have a point: no voxel centre lies outside them.)
  EXPECT_GE(corners, 1);
  EXPECT_LE(corners, 8);
}

TEST(SurfaceShell, WordsAreTheGridPointsAndThreadsNeverMatter) {
  const Mesh m = make_shape("torus");
  const PointShell a = point_shell(m, surface_options(0.1, 1)), b = point_shell(m, surface_options(0.1, 3));
  ASSERT_EQ(a.coords, b.coords);
  ASSERT_EQ(a.normals, b.normals);
  DeviceConfig cfg;
  const std::vector<ShellWord> w = a.words(cfg);
  for (size_t k = 0; k < a.size(); ++k)
    for (int i = 0; i < 3; ++i) ASSERT_EQ(w[k][i], int64_t(a.coords[k][size_t(i)]) << (cfg.PF - kShellFrac));
  EXPECT_NEAR(a.max_grid_coordinate(), [&] {
    double mx = 0;
    for (size_t k = 0; k < a.size(); ++k) mx = std::max(mx, a.grid_point(k).maxCoeff());
    return mx;
  }(), 0);
}

// A shell point's own field value is ~0: the node values' rounding, the interpolation of a bending distance (at most
// sqrt(3)/2 voxel, far less on smooth parts) and the point's rounding.
TEST(SurfaceShell, FieldIsNearZeroAtShellPoints) {
  const Mesh m = make_shape("sphere");
  ObjectOptions opt;
  opt.voxel = 0.1;
  opt.distance_bits = 16;
  const ObjectFile obj = make_object(m, "shape:sphere", 0, opt);
  double worst = 0;
  for (size_t k = 0; k < obj.shell.size(); ++k) {
    const Eigen::Vector3d g = (obj.shell.points[k] - obj.voxmap.origin()) / obj.voxmap.voxel();
    worst = std::max(worst, std::abs(obj.distance.sample(g)));
  }
  // Measured 0.054 voxel on this sphere of 10 voxels' radius: the interpolation of a distance that bends (the
  // facets' edges and the curvature), well below the sqrt(3)/2 voxel that bounds it for any mesh.
  EXPECT_LT(worst, 0.1);
}

// ---- Object files ----

uint32_t version_of(const std::string& bytes) {
  uint32_t v;
  std::memcpy(&v, bytes.data() + 8, 4);
  return v;
}

TEST(DistanceObjectFile, Version3RoundTrip) {
  for (int bits : {4, 8, 16}) {
    SCOPED_TRACE(bits);
    const Mesh m = make_shape("stellated");
    ObjectOptions opt;
    opt.voxel = 0.15;
    opt.distance_bits = bits;
    opt.band = 2.5;
    const ObjectFile a = make_object(m, "shape:stellated", hash_bytes("shape:stellated"), opt);
    ASSERT_EQ(a.distance.bits, bits);
    ASSERT_TRUE(a.shell.on_surface);
    const std::string path = test::tmp_path("distance_" + std::to_string(bits) + ".vxo");
    write_object(path, a);
    const std::string bytes = test::read_file(path);
    EXPECT_EQ(version_of(bytes), 3u);
    const ObjectFile b = read_object(path);
    EXPECT_EQ(b.distance.bits, bits);
    EXPECT_EQ(b.distance.step, a.distance.step);
    EXPECT_EQ(b.distance.dims, a.distance.dims);
    EXPECT_EQ(b.distance.q, a.distance.q);
    EXPECT_TRUE(b.shell.on_surface);
    EXPECT_EQ(b.shell.coords, a.shell.coords);
    EXPECT_EQ(b.shell.cells, a.shell.cells);
    EXPECT_EQ(b.shell.points, a.shell.points);
    EXPECT_EQ(b.shell.normals, a.shell.normals);
    EXPECT_EQ(b.voxmap.words(), a.voxmap.words());
    // Written again, the same bytes.
    write_object(path + "2", b);
    EXPECT_EQ(test::read_file(path + "2"), bytes);
    std::remove(path.c_str());
    std::remove((path + "2").c_str());
  }
}

// FNV-1a 64 of `voxcd voxelize torus --voxel 0.2 -o F` as written before distance fields existed.
constexpr uint64_t kTorusV2Hash = 0x4ff9324bfa40b43aull;

TEST(DistanceObjectFile, Version2ObjectsAreWrittenAsBefore) {
  std::string source;
  uint64_t hash = 0;
  MeshReport report;
  const Mesh m = load_source("torus", &source, &hash, &report);
  ObjectOptions opt;
  opt.voxel = 0.2;
  const ObjectFile plain = make_object(m, source, hash, opt, &report);
  EXPECT_TRUE(plain.distance.empty());
  EXPECT_FALSE(plain.shell.on_surface);
  const std::string path = test::tmp_path("plain.vxo");
  write_object(path, plain);
  const std::string bytes = test::read_file(path);
  EXPECT_EQ(version_of(bytes), 2u);
  // The version 2 layout: nothing after the report section but the checksum.
  const size_t L = plain.source.size(), W = plain.voxmap.words().size(), N = plain.shell.size();
  EXPECT_EQ(bytes.size(), 140 + L + 8 * W + 220 + 60 * N + 4);
  EXPECT_EQ(hash_bytes(bytes), kTorusV2Hash);
  std::remove(path.c_str());
}

TEST(DistanceObjectFile, DamagedVersion3FilesNameTheOffset) {
  const Mesh m = make_shape("cube");
  ObjectOptions opt;
  opt.voxel = 0.4;
  opt.distance_bits = 4;
  const ObjectFile a = make_object(m, "shape:cube", 1, opt);
  ASSERT_EQ(a.distance.q.size() % 2, 1u);  // an odd count of 4-bit values: half of the last byte is padding
  const std::string path = test::tmp_path("damaged.vxo");
  write_object(path, a);
  const std::string good = test::read_file(path);
  const size_t section = good.size() - 4 - (a.distance.q.size() * 4 + 7) / 8 - 20;
  // Every truncation inside the distance section, and changed bytes there.
  for (size_t len = section; len < good.size(); ++len) {
    test::write_file(path, good.substr(0, len));
    EXPECT_THROW(read_object(path), ObjectFileError) << len;
  }
  auto damaged = [&](size_t at, char v, const char* what) {
    std::string bad = good;
    bad[at] = v;
    test::write_file(path, bad);
    try {
      read_object(path);
      ADD_FAILURE() << "no error for " << what;
    } catch (const ObjectFileError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("byte"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  damaged(section, 5, "distance bits 5");
  damaged(section + 12, 1, "node count");
  damaged(good.size() - 5, char(0xf0), "beyond the last node");
  damaged(8, 4, "version 4");
  std::remove(path.c_str());
}

// ---- Errors ----

TEST(DistanceField, BadBitsAndBandsAreErrors) {
  const Mesh m = make_shape("cube");
  const Voxmap vm = voxmap_of(m, 0.5);
  for (int bits : {0, 2, 5, 12, 32}) {
    const std::string e = test::error_text<MeshError>([&] { field_of(m, vm, bits, 4); });
    EXPECT_NE(e.find("4, 8 or 16"), std::string::npos) << e;
    EXPECT_NE(e.find(std::to_string(bits)), std::string::npos) << e;
  }
  for (double band : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    const std::string e = test::error_text<MeshError>([&] { field_of(m, vm, 8, band); });
    EXPECT_NE(e.find("band"), std::string::npos) << e;
  }
  ObjectOptions opt;
  opt.voxel = 0.5;
  opt.distance_bits = 6;
  EXPECT_NE(test::error_text<MeshError>([&] { make_object(m, "shape:cube", 0, opt); }).find("4, 8 or 16"),
            std::string::npos);
  opt.distance_bits = 8;
  opt.band = -2;
  EXPECT_NE(test::error_text<MeshError>([&] { make_object(m, "shape:cube", 0, opt); }).find("band"),
            std::string::npos);
}

TEST(DistanceField, PointCloudsAreRefused) {
  Mesh cloud;
  cloud.name = "cloud.ply";
  std::mt19937_64 rng(test::seed());
  std::normal_distribution<double> g;
  for (int i = 0; i < 200; ++i) cloud.vertices.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
  const Voxmap vm = voxmap_of(cloud, 0.25);
  const std::string e = test::error_text<MeshError>([&] { field_of(cloud, vm); });
  EXPECT_NE(e.find("cloud.ply"), std::string::npos) << e;
  EXPECT_NE(e.find("point cloud"), std::string::npos) << e;
  EXPECT_THROW(point_shell(cloud, surface_options(0.25)), MeshError);
}

}  // namespace
}  // namespace voxcd
