// The voxeliser: volume brackets on every built-in solid and on loaded meshes, every voxel against brute force,
// and the hard cases (faces on voxel-centre planes, rays through vertices and edges, far-away coordinates,
// duplicated vertices, grids too large).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

// interior * V <= volume <= (interior + surface) * V.
void expect_bracket(const Mesh& m, const Voxmap& vm, const std::string& what) {
  const auto c = vm.counts();
  const double v3 = std::pow(vm.voxel(), 3);
  const double vol = m.volume();
  EXPECT_LE(double(c[kInterior]) * v3, vol) << what;
  EXPECT_GE(double(c[kInterior] + c[kSurface]) * v3, vol) << what;
  EXPECT_EQ(c[kReserved], 0u) << what;
  EXPECT_GT(c[kSurface], 0u) << what;
}

// Every voxel on the outer layer of the grid is empty (the padding the object file documents).
void expect_padding(const Voxmap& vm) {
  const auto& d = vm.dims();
  for (uint32_t z = 0; z < d[2]; ++z)
    for (uint32_t y = 0; y < d[1]; ++y)
      for (uint32_t x = 0; x < d[0]; ++x)
        if (x == 0 || y == 0 || z == 0 || x == d[0] - 1 || y == d[1] - 1 || z == d[2] - 1) {
          ASSERT_EQ(vm.at(x, y, z), kEmpty) << x << " " << y << " " << z;
        }
}

Eigen::Vector3d random_shift(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.01, 1.0);
  return Eigen::Vector3d(u(rng), u(rng), u(rng));
}

TEST(Voxelize, VolumeBracketBuiltins) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed);
  for (const auto& name : shape_names()) {
    const Mesh m = make_shape(name);
    for (double s : {0.25, 0.07, 0.02})
      for (int rep = 0; rep < 3; ++rep) {
        VoxelizeOptions o;
        o.voxel = s;
        o.shift = random_shift(rng);
        const Voxmap vm = voxelize(m, o);
        expect_bracket(m, vm, name + " voxel " + std::to_string(s) + " seed " + std::to_string(seed));
        if (s == 0.25) expect_padding(vm);
      }
  }
}

TEST(Voxelize, VolumeBracketLoadedMeshes) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed + 1);
  for (const char* shape : {"torus", "stellated", "polytope36"})
    for (const char* ext : {".obj", ".stl", ".ply", ".raw"}) {
      const std::string path = test::tmp_path(std::string(shape) + ext);
      const Mesh src = make_shape(shape);
      if (ext == std::string(".obj")) test::write_obj(src, path);
      if (ext == std::string(".stl")) test::write_stl(src, path);
      if (ext == std::string(".ply")) test::write_ply(src, path);
      if (ext == std::string(".raw")) {
        std::ofstream o(path);
        write_raw(src, o);
      }
      const Mesh m = load_mesh(path);
      std::remove(path.c_str());
      ASSERT_EQ(m.size(), src.size()) << path;
      for (double s : {0.2, 0.1, 0.05, 0.03})
        for (int rep = 0; rep < 2; ++rep) {
          VoxelizeOptions o;
          o.voxel = s;
          o.shift = random_shift(rng);
          expect_bracket(m, voxelize(m, o), path + " voxel " + std::to_string(s) + " seed " + std::to_string(seed));
        }
    }
}

TEST(Voxelize, EveryVoxelAgainstBruteForce) {
  const uint64_t seed = test::seed();
  std::mt19937_64 rng(seed + 2);
  for (const auto& name : shape_names()) {
    if (name == "sphere" || name == "torus") continue;  // many triangles: the meshes below cover curved ones
    const Mesh m = make_shape(name);
    VoxelizeOptions o;
    o.voxel = 0.11;
    o.shift = random_shift(rng);
    EXPECT_EQ(test::check_voxels(m, voxelize(m, o)), 0) << name << " seed " << seed;
  }
  const Mesh sph = make_icosphere(Eigen::Vector3d(0.1, 0.2, 0.3), 1.0, 2);
  VoxelizeOptions o;
  o.voxel = 0.13;
  o.shift = random_shift(rng);
  EXPECT_EQ(test::check_voxels(sph, voxelize(sph, o)), 0) << "seed " << seed;
}

TEST(Voxelize, FacesOnVoxelCentrePlanes) {
  // Box [0, 4]^3 at voxel 1 with shift 0.5: its faces lie on the centre planes 1.5 and 5.5 of the grid.
  const Mesh box = make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Constant(4));
  VoxelizeOptions o;
  o.voxel = 1;
  const Voxmap vm = voxelize(box, o);
  ASSERT_EQ(vm.dims()[0], 7u);
  for (uint32_t z = 0; z < 7; ++z)
    for (uint32_t y = 0; y < 7; ++y)
      for (uint32_t x = 0; x < 7; ++x) {
        const auto in = [](uint32_t i) { return i >= 1 && i <= 5; };
        const auto deep = [](uint32_t i) { return i >= 2 && i <= 4; };
        const VoxelState want =
            deep(x) && deep(y) && deep(z) ? kInterior : in(x) && in(y) && in(z) ? kSurface : kEmpty;
        ASSERT_EQ(vm.at(x, y, z), want) << x << " " << y << " " << z;
      }
  // The same with faces on voxel boundaries (shift 1): the voxels on both sides of a face are surface.
  o.shift = Eigen::Vector3d::Ones();
  const Voxmap vb = voxelize(box, o);
  EXPECT_EQ(test::check_voxels(box, vb), 0);
  expect_bracket(box, vb, "box on voxel boundaries");
}

// A closed heightfield slab whose vertices all lie on voxel-column centres, so that rays along x go through
// every vertex and along many edges.
Mesh lattice_slab(std::mt19937_64& rng, int n) {
  Mesh m;
  m.name = "lattice slab";
  std::uniform_int_distribution<int> h(0, 3);
  auto vid = [&](int j, int k, int top) { return uint32_t((top * (n + 1) + k) * (n + 1) + j); };
  for (int top = 0; top < 2; ++top)
    for (int k = 0; k <= n; ++k)
      for (int j = 0; j <= n; ++j)
        m.vertices.emplace_back(top ? 4.5 + h(rng) + 0.5 * (h(rng) == 0) : 0.5, j + 0.5, k + 0.5);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j) {
      const bool diag = (j + k) % 2;
      for (int top = 0; top < 2; ++top) {
        uint32_t a = vid(j, k, top), b = vid(j + 1, k, top), c = vid(j + 1, k + 1, top), d = vid(j, k + 1, top);
        std::array<uint32_t, 3> t1 = diag ? std::array<uint32_t, 3>{a, b, c} : std::array<uint32_t, 3>{a, b, d};
        std::array<uint32_t, 3> t2 = diag ? std::array<uint32_t, 3>{a, c, d} : std::array<uint32_t, 3>{b, c, d};
        if (!top) {
          std::swap(t1[1], t1[2]);
          std::swap(t2[1], t2[2]);
        }
        m.triangles.push_back(t1);
        m.triangles.push_back(t2);
      }
    }
  // Side walls: quads between the bottom and top rims.
  auto wall = [&](uint32_t a0, uint32_t a1) {  // rim edge a0 -> a1 (bottom indices), walls face outward
    const uint32_t off = uint32_t((n + 1) * (n + 1));
    m.triangles.push_back({a0, a1, a1 + off});
    m.triangles.push_back({a0, a1 + off, a0 + off});
  };
  for (int j = 0; j < n; ++j) {
    wall(vid(j, 0, 0), vid(j + 1, 0, 0));
    wall(vid(j + 1, n, 0), vid(j, n, 0));
  }
  for (int k = 0; k < n; ++k) {
    wall(vid(n, k, 0), vid(n, k + 1, 0));
    wall(vid(0, k + 1, 0), vid(0, k, 0));
  }
  prepare(m);
  return m;
}

TEST(Voxelize, RaysThroughVerticesAndEdges) {
  const uint64_t seed = test::seed();
  std::mt19937_64 rng(seed + 3);
  for (int rep = 0; rep < 3; ++rep) {
    const Mesh m = lattice_slab(rng, 6);
    // Grid coordinate = mesh coordinate + 1 - ... : choose shift so that mesh lattice points are column centres.
    Eigen::Vector3d lo, hi;
    m.bounds(lo, hi);
    VoxelizeOptions o;
    o.voxel = 1;
    o.shift = Eigen::Vector3d::Constant(0.5);  // lo = 0.5 lands on grid 1.5: lattice points on column centres
    const Voxmap vm = voxelize(m, o);
    EXPECT_EQ(test::check_voxels(m, vm), 0) << "seed " << seed;
    expect_bracket(m, vm, "lattice slab");
  }
  // An octahedron with its tips on column centres, rays along x through both axial tips.
  Mesh oct;
  oct.name = "octahedron";
  oct.vertices = {{3, 0, 0}, {-3, 0, 0}, {0, 3, 0}, {0, -3, 0}, {0, 0, 3}, {0, 0, -3}};
  oct.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  prepare(oct);
  VoxelizeOptions o;
  o.voxel = 1;
  const Voxmap vo = voxelize(oct, o);
  EXPECT_EQ(test::check_voxels(oct, vo), 0);
  expect_bracket(oct, vo, "octahedron");
}

TEST(Voxelize, FarFromOrigin) {
  const uint64_t seed = test::seed();
  std::mt19937_64 rng(seed + 4);
  for (const char* name : {"stellated", "torus", "sphere"}) {
    const Mesh m = make_shape(name);
    Mesh far = m;
    for (auto& v : far.vertices) v += Eigen::Vector3d(1e6, -1e6, 1e6);
    VoxelizeOptions o;
    o.voxel = 0.05;
    o.shift = random_shift(rng);
    const Voxmap a = voxelize(m, o), b = voxelize(far, o);
    expect_bracket(far, b, std::string(name) + " at 1e6");
    EXPECT_EQ(a.dims(), b.dims());
    const auto ca = a.counts(), cb = b.counts();
    // The far grid is placed with rounding of order 1e-10 voxel: at most a voxel grazed differently.
    EXPECT_NEAR(double(ca[kInterior]), double(cb[kInterior]), 2) << name;
    EXPECT_NEAR(double(ca[kSurface]), double(cb[kSurface]), 2) << name;
  }
}

TEST(Voxelize, DuplicatedVerticesGiveTheSameMap) {
  const Mesh indexed = make_shape("stellated");
  Mesh soup;  // every triangle with its own vertices, as STL and RAW store them
  soup.name = "soup";
  for (size_t t = 0; t < indexed.size(); ++t) {
    const uint32_t b = uint32_t(soup.vertices.size());
    for (int k = 0; k < 3; ++k) soup.vertices.push_back(indexed.corner(t, k));
    soup.triangles.push_back({b, b + 1, b + 2});
  }
  prepare(soup);
  VoxelizeOptions o;
  o.voxel = 0.04;
  EXPECT_EQ(voxelize(indexed, o).words(), voxelize(soup, o).words());
}

TEST(Voxelize, ThreadCountDoesNotMatter) {
  const Mesh m = make_shape("torus");
  VoxelizeOptions o;
  o.voxel = 0.02;
  o.threads = 1;
  const Voxmap a = voxelize(m, o);
  o.threads = 3;
  EXPECT_EQ(a.words(), voxelize(m, o).words());
}

TEST(Voxelize, DeviceWordLayout) {
  const Mesh m = make_shape("icosahedron");
  VoxelizeOptions o;
  o.voxel = 0.3;
  const Voxmap vm = voxelize(m, o);
  for (int memw : {2, 8, 16, 32, 64}) {
    const auto w = vm.device_words(memw);
    const uint64_t per = uint64_t(memw) / 2;
    ASSERT_EQ(w.size(), (vm.size() + per - 1) / per);
    for (uint64_t i = 0; i < vm.size(); ++i)
      ASSERT_EQ((w[i / per] >> (2 * (i % per))) & 3, uint64_t(vm.at(i))) << memw << " " << i;
  }
}

TEST(Voxelize, BadRequestsAreErrors) {
  const Mesh m = make_shape("cube");
  VoxelizeOptions o;
  o.voxel = 0.001;  // 2000+ voxels per axis
  try {
    voxelize(m, o);
    ADD_FAILURE() << "no error";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("at most 1024 per axis"), std::string::npos) << e.what();
  }
  for (double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    o.voxel = bad;
    EXPECT_THROW(voxelize(m, o), MeshError) << bad;
  }
  Mesh empty;
  o.voxel = 1;
  EXPECT_THROW(voxelize(empty, o), MeshError);
}

}  // namespace
}  // namespace voxcd
