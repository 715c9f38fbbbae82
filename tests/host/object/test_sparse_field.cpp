// Sparse distance fields (host/object/sparse_field.h): a level-0 field holds the dense field's node values (built
// brick by brick, from one solid or layer by layer, and converted); ref's look_up reads the same D from its sparse
// image as from the dense image at every point of a random cloud, and the host's sample is the device's interpolant
// at every level; refined bricks resolve what the coarse nodes cannot (boxes, thin plates) with conservative
// sub-cells left only on sheets; the file section round-trips and every damaged or truncated copy is an error that
// names the offset; bad options and configurations are errors.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "tests/defects.h"
#include "tests/error_text.h"
#include "tests/host/test_util.h"
#include "voxcd/host/object/detail/unresolved.h"
#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/sparse_field.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

namespace voxcd {
namespace {

Voxmap voxmap_of(const Mesh& m, double voxel, const Eigen::Vector3d& shift = Eigen::Vector3d::Constant(0.5)) {
  VoxelizeOptions o;
  o.voxel = voxel;
  o.shift = shift;
  return voxelize(m, o);
}

double longest(const Mesh& m) {
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  return (hi - lo).maxCoeff();
}

DistanceOptions distance_options(int bits, double band, bool conservative) {
  DistanceOptions o;
  o.bits = bits;
  o.band = band;
  o.conservative = conservative;
  return o;
}

SparseDistanceField sparse_of(const Mesh& m, const Voxmap& vm, int bits, double band, bool conservative, int max_level,
                              uint64_t whole = uint64_t{1} << 27) {
  SparseFieldOptions o;
  o.distance = distance_options(bits, band, conservative);
  o.max_level = max_level;
  o.whole_solid_nodes = whole;
  return sparse_distance_field(m, vm.grid(), o);
}

Mesh named_shape(const std::string& name) {
  Mesh m = make_shape(name);
  repair(m);
  return m;
}

// A plate of the given thickness (1 x 1 across), closed.
Mesh plate(double thickness) {
  Mesh m = make_box(Eigen::Vector3d(-0.5, -0.5, -thickness / 2), Eigen::Vector3d(0.5, 0.5, thickness / 2));
  m.name = "plate " + std::to_string(thickness);
  repair(m);
  return m;
}

// A square sheet, slightly tilted (two triangles): repair marks it a sheet.
Mesh sheet() {
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0.2}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.name = "sheet";
  repair(m);
  return m;
}

// Every node of the dense field equals the sparse field's (at the level-0 nodes).
void expect_same_nodes(const DistanceField& d, const SparseDistanceField& s, const std::string& what) {
  const DistanceField back = dense_from_sparse(s);
  ASSERT_EQ(back.q.size(), d.q.size()) << what;
  uint64_t differ = 0;
  for (size_t i = 0; i < d.q.size(); ++i)
    if (back.q[i] != d.q[i] && ++differ <= 5)
      ADD_FAILURE() << what << ": node " << i << " dense " << d.q[i] << " sparse " << back.q[i];
  EXPECT_EQ(differ, 0u) << what;
}

TEST(SparseField, LevelZeroHoldsTheDenseFieldsNodes) {
  for (const char* name : {"cube", "sphere", "torus", "stellated"}) {
    const Mesh m = named_shape(name);
    for (double shift : {0.5, 1.0}) {
      const Voxmap vm = voxmap_of(m, longest(m) / 40, Eigen::Vector3d::Constant(shift));
      for (int bits : {4, 8, 16}) {
        const std::string what = std::string(name) + " SB " + std::to_string(bits) + " shift " + std::to_string(shift);
        const DistanceField d = distance_field(m, vm, distance_options(bits, 3, false));
        // One solid over every node, and one layer of cells at a time.
        const SparseDistanceField whole = sparse_of(m, vm, bits, 3, false, 0);
        const SparseDistanceField layers = sparse_of(m, vm, bits, 3, false, 0, 0);
        expect_same_nodes(d, whole, what + " (whole)");
        expect_same_nodes(d, layers, what + " (layers)");
        EXPECT_EQ(whole.codes(), layers.codes()) << what;
        EXPECT_EQ(whole.nodes(), layers.nodes()) << what;
        // The dense field converted: the same cells and bricks as the field built brick by brick.
        const SparseDistanceField conv = sparse_from_dense(d);
        EXPECT_EQ(conv.codes(), whole.codes()) << what;
        expect_same_nodes(d, conv, what + " (converted)");
        const SparseFieldCounts c = whole.counts();
        EXPECT_GT(c.far + c.deep, 0u) << what;
        EXPECT_GT(c.bricks[0], 0u) << what;
        EXPECT_EQ(c.bricks[1] + c.bricks[2] + c.bricks[3], 0u) << what;
      }
    }
  }
}

TEST(SparseField, LevelZeroConservativeCellsAreAmongTheDenseFields) {
  // At max_level 0 a brick's test differs from the dense field's only in where it samples the inside (half a thin
  // part's thickness rather than past it; not on a convex edge's next face), so its conservative cells are among the
  // dense field's (cells whose nodes the dense field lowered, which the measured field alone does not hit everywhere).
  for (const char* name : {"cube", "plate", "stellated"}) {
    const Mesh m = named_shape(name);
    const Voxmap vm = voxmap_of(m, longest(m) / 24);
    uint64_t lowered = 0;
    const DistanceField d = distance_field(m, vm, distance_options(8, 4, true), &lowered);
    const DistanceField raw = distance_field(m, vm, distance_options(8, 4, false));
    const SparseDistanceField s = sparse_of(m, vm, 8, 4, true, 0);
    uint64_t in_dense = 0;
    for (uint64_t key : s.conservative()) {
      const uint64_t t = key >> 18, cx = t % s.cells()[0], cy = t / s.cells()[0] % s.cells()[1],
                     cz = t / (uint64_t(s.cells()[0]) * s.cells()[1]);
      const uint64_t x = cx * 8 + (key & 63), y = cy * 8 + (key >> 6 & 63), z = cz * 8 + (key >> 12 & 63);
      in_dense += d.hits_everywhere(x, y, z) && !raw.hits_everywhere(x, y, z);
    }
    std::printf("%-10s conservative cells: dense %llu, sparse at level 0 %llu\n", name, (unsigned long long)lowered,
                (unsigned long long)s.counts().conservative);
    EXPECT_EQ(in_dense, s.counts().conservative) << name;
    EXPECT_LE(s.counts().conservative, lowered) << name;
    EXPECT_GT(s.counts().conservative, 0u) << name;
  }
}

TEST(SparseField, HolesAndSheetsKeepTheDenseSigns) {
  Mesh holed = test::icosphere(3);
  std::vector<std::array<uint32_t, 3>> kept;
  for (size_t t = 0; t < holed.size(); ++t) {
    const Eigen::Vector3d c = (holed.corner(t, 0) + holed.corner(t, 1) + holed.corner(t, 2)) / 3;
    if (c.normalized().dot(Eigen::Vector3d(0.36, 0.48, 0.8)) <= 0.97) kept.push_back(holed.triangles[t]);
  }
  holed.triangles = kept;
  holed.name = "icosphere with a hole";
  repair(holed);
  for (const Mesh& m : {holed, sheet()}) {
    const Voxmap vm = voxmap_of(m, longest(m) / 19);
    const DistanceField d = distance_field(m, vm, distance_options(8, 2, false));
    expect_same_nodes(d, sparse_of(m, vm, 8, 2, false, 0), m.name);
    expect_same_nodes(d, sparse_of(m, vm, 8, 2, false, 0, 0), m.name + " (layers)");
  }
}

// A job that reads grid point coordinates straight from the shell words: M the identity, t 0, one voxel a unit.
Job identity_job(const DeviceConfig& cfg, const std::array<uint32_t, 3>& dims) {
  Job j;
  j.nx = dims[0];
  j.ny = dims[1];
  j.nz = dims[2];
  for (int i = 0; i < 3; ++i) j.M[i][i] = int64_t{1} << cfg.MF;
  return j;
}

DeviceConfig sparse_config() {
  DeviceConfig cfg;
  cfg.SB = 8;
  cfg.BL = 3;
  cfg.MAW = 24;
  cfg.validate();
  return cfg;
}

// Random points over the grid and a little beyond it, as shell words (PF fraction bits).
std::vector<ShellWord> cloud(const std::array<uint32_t, 3>& dims, int pf, size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<ShellWord> out;
  for (size_t k = 0; k < n; ++k) {
    ShellWord w;
    int64_t* c[3] = {&w.x, &w.y, &w.z};
    for (int i = 0; i < 3; ++i) {
      std::uniform_int_distribution<int64_t> u(-(int64_t{1} << pf), (int64_t(dims[size_t(i)]) + 1) << pf);
      *c[i] = u(rng);
    }
    out.push_back(w);
  }
  return out;
}

// Table at word 0, bricks from the next multiple of 8; the job that reads it (grid coordinates from the shell words).
struct SparseMap {
  std::vector<uint64_t> words;
  Job job;
};
SparseMap sparse_map(const DeviceConfig& cfg, const SparseDistanceField& s) {
  const SparseImage im = s.device_image(cfg);
  SparseMap m{im.table, identity_job(cfg, s.dims())};
  m.words.resize((m.words.size() + 7) / 8 * 8, 0);
  m.job.sparse = kSparseMap;
  m.job.brick_base = uint32_t(m.words.size());
  m.job.brick_units = uint32_t(im.brick_units);
  m.words.insert(m.words.end(), im.bricks.begin(), im.bricks.end());
  return m;
}

// Every point of a random cloud over the grid (and a little beyond) reads the same D from both images.
void expect_same_lookups(const DeviceConfig& cfg, const DistanceField& d, const SparseDistanceField& s,
                         const std::string& what) {
  const SparseMap sm = sparse_map(cfg, s);
  const std::vector<uint64_t> dense_words = d.device_words(cfg);
  const Job dj = identity_job(cfg, d.dims);
  uint64_t inside = 0;
  for (const ShellWord& p : cloud(d.dims, cfg.PF, 20000, test::seed())) {
    const Lookup a = look_up(cfg, dense_words, dj, p), b = look_up(cfg, sm.words, sm.job, p);
    ASSERT_EQ(a.loc.inside, b.loc.inside);
    ASSERT_EQ(a.dist, b.dist) << what << ": point (" << p.x << ", " << p.y << ", " << p.z << ")";
    inside += a.loc.inside;
  }
  EXPECT_GT(inside, 10000u) << what;
}

TEST(SparseField, LookUpOnTheSparseImageGivesTheDenseD) {
  std::printf("seed %llu (VOXCD_SEED)\n", static_cast<unsigned long long>(test::seed()));
  const DeviceConfig cfg = sparse_config();
  for (const char* name : {"torus", "stellated"}) {
    const Mesh m = named_shape(name);
    const Voxmap vm = voxmap_of(m, longest(m) / 30);
    // The dense field converted (its conservative cells included), and a level-0 field built brick by brick.
    const DistanceField d = distance_field(m, vm, distance_options(8, 4, true));
    expect_same_lookups(cfg, d, sparse_from_dense(d), std::string(name) + " (converted)");
    const DistanceField raw = distance_field(m, vm, distance_options(8, 4, false));
    expect_same_lookups(cfg, raw, sparse_of(m, vm, 8, 4, false, 0), std::string(name) + " (built)");
  }
}

TEST(SparseField, SampleIsTheDevicesInterpolantAtEveryLevel) {
  // Refined bricks (a cube's edges, a thin plate): the host's sample at the point the device's truncated weights
  // stand for equals D / 2^(3 WB) times the step, and ref reads the same cell codes and levels.
  const DeviceConfig cfg = sparse_config();
  std::mt19937_64 rng(test::seed() + 1);
  for (const Mesh& m : {named_shape("cube"), plate(0.03)}) {
    const Voxmap vm = voxmap_of(m, longest(m) / 24);
    const SparseDistanceField s = sparse_of(m, vm, 8, 4, true, 3);
    const SparseFieldCounts c = s.counts();
    EXPECT_GT(c.bricks[1] + c.bricks[2] + c.bricks[3], 0u) << m.name << ": nothing refined";
    const SparseMap sm = sparse_map(cfg, s);
    const std::vector<uint64_t>& map = sm.words;
    const Job& j = sm.job;
    // Points near the surface, where the bricks are: vertices and edge midpoints moved a little.
    std::normal_distribution<double> n(0, 0.7);
    uint64_t refined = 0;
    for (int k = 0; k < 4000; ++k) {
      const size_t t = size_t(rng() % m.size());
      const Eigen::Vector3d p = (m.corner(t, k % 3) * 0.7 + m.corner(t, (k + 1) % 3) * 0.3 - vm.origin()) / vm.voxel() +
                                Eigen::Vector3d(n(rng), n(rng), n(rng));
      ShellWord w;
      w.x = std::llround(std::ldexp(p.x(), cfg.PF));
      w.y = std::llround(std::ldexp(p.y(), cfg.PF));
      w.z = std::llround(std::ldexp(p.z(), cfg.PF));
      const Lookup r = look_up(cfg, map, j, w);
      if (!r.loc.inside) continue;
      const Transformed tr = transform(cfg, j, w);
      const Cell cell = read_cell(cfg, map, j, table_ref(cfg, j, r.loc));
      const uint64_t t_index =
          s.cell_index(uint64_t(r.loc.index[0]) / 8, uint64_t(r.loc.index[1]) / 8, uint64_t(r.loc.index[2]) / 8);
      ASSERT_EQ(cell.level, s.level(t_index));
      const SubCell sc = sub_cell(cfg, cell, r.loc, tr);
      const int l = std::max(0, cell.level);
      Eigen::Vector3d g;
      for (int i = 0; i < 3; ++i)
        g[i] =
            double(r.loc.index[i] / 8 * 8) + std::ldexp(double(sc.X[i]) + std::ldexp(double(sc.f.f[i]), -cfg.WB), -l);
      const double want = double(r.dist) * s.step() / std::ldexp(1.0, 3 * cfg.WB);
      ASSERT_NEAR(s.sample(g), want, 1e-9) << m.name << " at (" << g.transpose() << "), level " << cell.level;
      refined += cell.level > 0;
    }
    EXPECT_GT(refined, 100u) << m.name;
  }
}

TEST(SparseField, GradientIsTheInterpolantsSlope) {
  const Mesh m = named_shape("cube");
  const Voxmap vm = voxmap_of(m, longest(m) / 24);
  const SparseDistanceField s = sparse_of(m, vm, 16, 4, true, 3);
  std::mt19937_64 rng(test::seed() + 2);
  std::uniform_real_distribution<double> u(1, 25);
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d g(u(rng), u(rng), u(rng));
    Eigen::Vector3d grad;
    s.sample(g, &grad);
    for (int i = 0; i < 3; ++i) {
      // A step of 1e-6 voxel stays in the sub-cell but where g lies within it of a face.
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[i] = 1e-6;
      const double fd = (s.sample(g + e) - s.sample(g - e)) / 2e-6;
      const double frac = std::ldexp(g[i], 3) - std::floor(std::ldexp(g[i], 3));
      if (frac < 1e-4 || frac > 1 - 1e-4) continue;
      ASSERT_NEAR(grad[i], fd, 1e-4) << "at (" << g.transpose() << ") axis " << i;
    }
  }
}

// The surface's resolution in every brick: at random points of each non-sheet triangle, the interpolant is at most
// kResolvedTolerance + step / 2 (the test's bound, sampled elsewhere than the test samples), unless the point's
// sub-cell is conservative. Returns the sub-cells made conservative.
uint64_t check_resolved(const Mesh& m, const Voxmap& vm, const SparseDistanceField& s, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  int failures = 0;
  for (size_t t = 0; t < m.size(); ++t) {
    if (m.is_sheet(t)) continue;
    for (int k = 0; k < 60; ++k) {
      double r1 = u(rng), r2 = u(rng);
      if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
      const Eigen::Vector3d p =
          m.corner(t, 0) + r1 * (m.corner(t, 1) - m.corner(t, 0)) + r2 * (m.corner(t, 2) - m.corner(t, 0));
      const Eigen::Vector3d g = (p - vm.origin()) / vm.voxel();
      if (s.near_conservative(g)) continue;
      const double v = s.sample(g);
      if (v > detail::kResolvedTolerance + s.step() && ++failures <= 10)
        ADD_FAILURE() << m.name << ": the interpolant is " << v << " voxels at a surface point (" << g.transpose()
                      << ") outside conservative sub-cells";
    }
  }
  EXPECT_EQ(failures, 0) << m.name;
  return s.counts().conservative;
}

TEST(SparseField, RefinedBricksResolveBoxesAndThinPlates) {
  // Boxes (sharp edges) and plates down to a fifth of a voxel: every brick resolves at some level, no sub-cell is
  // conservative, and the levels used are the coarsest that resolve (some bricks stay at level 0).
  const Mesh cube = named_shape("cube");
  for (const Mesh& m : {cube, plate(0.03), plate(0.012)}) {
    const Voxmap vm = voxmap_of(m, longest(m) / 24);
    uint64_t dense_conservative = 0;
    distance_field(m, vm, distance_options(8, 4, true), &dense_conservative);
    const SparseDistanceField s = sparse_of(m, vm, 8, 4, true, 3);
    const SparseFieldCounts c = s.counts();
    std::printf(
        "%-16s dense conservative cells %llu; sparse: far %llu deep %llu bricks %llu %llu %llu %llu, "
        "conservative sub-cells %llu, %llu bytes\n",
        m.name.c_str(), (unsigned long long)dense_conservative, (unsigned long long)c.far, (unsigned long long)c.deep,
        (unsigned long long)c.bricks[0], (unsigned long long)c.bricks[1], (unsigned long long)c.bricks[2],
        (unsigned long long)c.bricks[3], (unsigned long long)c.conservative, (unsigned long long)s.bytes());
    EXPECT_GT(dense_conservative, 0u) << m.name << ": the dense field needs conservative cells here";
    EXPECT_EQ(check_resolved(m, vm, s, test::seed() + 3), 0u) << m.name;
    EXPECT_GT(c.bricks[1] + c.bricks[2] + c.bricks[3], 0u) << m.name;
  }
}

TEST(SparseField, SheetsAloneKeepConservativeSubCells) {
  // A sheet has no inside at any level: every sub-cell it crosses is conservative at level 3, and a point of the
  // sheet reads at most 0 (a hit at margin 0).
  const Mesh m = sheet();
  const Voxmap vm = voxmap_of(m, 0.1);
  const SparseDistanceField s = sparse_of(m, vm, 8, 2, true, 3);
  const SparseFieldCounts c = s.counts();
  EXPECT_GT(c.conservative, 0u);
  EXPECT_GT(c.bricks[3], 0u);
  EXPECT_EQ(c.bricks[1] + c.bricks[2], 0u) << "a sheet's bricks go straight to level 3";
  std::mt19937_64 rng(test::seed() + 4);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 2000; ++k) {
    double r1 = u(rng), r2 = u(rng);
    if (r1 + r2 > 1) r1 = 1 - r1, r2 = 1 - r2;
    const size_t t = k % 2;
    const Eigen::Vector3d p =
        m.corner(t, 0) + r1 * (m.corner(t, 1) - m.corner(t, 0)) + r2 * (m.corner(t, 2) - m.corner(t, 0));
    const Eigen::Vector3d g = (p - vm.origin()) / vm.voxel();
    ASSERT_LE(s.sample(g), 0.0) << "at (" << g.transpose() << ")";
    ASSERT_TRUE(s.near_conservative(g));
  }
}

TEST(SparseField, ThreadCountNeverChangesTheField) {
  const Mesh m = named_shape("stellated");
  const Voxmap vm = voxmap_of(m, longest(m) / 20);
  SparseFieldOptions o;
  o.distance = distance_options(8, 4, true);
  o.distance.threads = 1;
  const SparseDistanceField one = sparse_distance_field(m, vm.grid(), o);
  o.distance.threads = 3;
  const SparseDistanceField three = sparse_distance_field(m, vm.grid(), o);
  EXPECT_EQ(one.codes(), three.codes());
  EXPECT_EQ(one.nodes(), three.nodes());
  EXPECT_EQ(one.conservative(), three.conservative());
}

// ---- The file section ----

SparseDistanceField small_refined_field() {
  const Mesh m = named_shape("cube");
  const Voxmap vm = voxmap_of(m, longest(m) / 12);
  return sparse_of(m, vm, 8, 4, true, 2);
}

TEST(SparseFieldFile, RoundTrip) {
  const Mesh s = sheet();
  const Voxmap sv = voxmap_of(s, 0.1);
  for (const SparseDistanceField& f :
       {small_refined_field(), sparse_of(s, sv, 4, 2, true, 3), sparse_of(s, sv, 16, 2, true, 1)}) {
    std::vector<uint8_t> bytes = {1, 2, 3};  // appended after what is there
    write_sparse_field(bytes, f);
    const SparseDistanceField g = read_sparse_field(bytes.data() + 3, bytes.size() - 3, "f.voxcd");
    EXPECT_EQ(g.bits(), f.bits());
    EXPECT_EQ(g.step(), f.step());
    EXPECT_EQ(g.dims(), f.dims());
    EXPECT_EQ(g.codes(), f.codes());
    EXPECT_EQ(g.nodes(), f.nodes());
    EXPECT_EQ(g.conservative(), f.conservative());
  }
}

TEST(SparseFieldFile, TruncatedAndDamagedCopiesNameTheOffset) {
  const SparseDistanceField f = small_refined_field();
  std::vector<uint8_t> bytes;
  write_sparse_field(bytes, f);
  auto fails = [&](const std::vector<uint8_t>& b, const std::string& expect) {
    try {
      read_sparse_field(b.data(), b.size(), "f.voxcd");
      ADD_FAILURE() << "no error for " << expect;
    } catch (const ObjectFileError& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind("f.voxcd: the sparse distance field: ", 0), 0u) << m;
      EXPECT_NE(m.find("(byte "), std::string::npos) << m;
      EXPECT_NE(m.find(expect), std::string::npos) << m;
    }
  };
  // Every shorter copy up to the node values, then every 97th length.
  for (size_t n = 0; n < bytes.size(); n += n < 400 ? 1 : 97)
    fails(std::vector<uint8_t>(bytes.begin(), bytes.begin() + long(n)), "truncated");
  std::vector<uint8_t> longer = bytes;
  longer.push_back(0);
  fails(longer, "follow the field's end");
  auto damaged = [&](size_t at, uint8_t value) {
    std::vector<uint8_t> b = bytes;
    b[at] = value;
    return b;
  };
  fails(damaged(0, 5), "bits per node value 5");
  fails(damaged(11, 0xff), "the step");  // the step's sign and exponent: NaN
  fails(damaged(12, 0), "grid dimension 0");
  fails(damaged(24, 9), "brick edge 9");
  fails(damaged(28, 1), "the cell count");
  fails(damaged(36, 0x77), "has code 7");
  // The node count field follows the codes.
  const size_t node_count = 36 + (f.codes().size() + 1) / 2;
  fails(damaged(node_count, uint8_t(bytes[node_count] + 1)), "node count");
  // The conservative keys (none here): a count past the end.
  fails(damaged(bytes.size() - 8, 1), "truncated");
}

TEST(SparseField, BadOptionsAndConfigurationsAreErrors) {
  const Mesh m = named_shape("cube");
  const Voxmap vm = voxmap_of(m, longest(m) / 8);
  EXPECT_NE(test::error_text<MeshError>([&] { sparse_of(m, vm, 8, 4, true, 4); }).find("levels 0 to 3, not 4"),
            std::string::npos);
  EXPECT_NE(test::error_text<MeshError>([&] {
              sparse_of(m, vm, 5, 4, true, 3);
            }).find("distance bits must be 4, 8 or 16, got 5"),
            std::string::npos);
  EXPECT_NE(
      test::error_text<MeshError>([&] { sparse_of(m, vm, 8, -1, true, 3); }).find("positive finite number of voxels"),
      std::string::npos);
  const SparseDistanceField f = sparse_of(m, vm, 8, 4, true, 1);
  DeviceConfig cfg = sparse_config();
  cfg.SB = 16;
  EXPECT_NE(
      test::error_text<std::invalid_argument>([&] { f.device_image(cfg); }).find("needs a distance device with SB = 8"),
      std::string::npos);
  cfg.SB = 8;
  cfg.BL = 2;
  EXPECT_NE(test::error_text<std::invalid_argument>([&] { f.device_image(cfg); }).find("need BL = 3, not BL = 2"),
            std::string::npos);
  EXPECT_NE(test::error_text<std::invalid_argument>([&] {
              SparseDistanceField(8, 0.1, {8, 8, 8}, {7}, {}, {});
            }).find("cell 0 has code 7"),
            std::string::npos);
  EXPECT_NE(test::error_text<std::invalid_argument>([&] {
              SparseDistanceField(8, 0.1, {8, 8, 8}, {2}, {}, {});
            }).find("0 node values for bricks of 729 nodes"),
            std::string::npos);
}

}  // namespace
}  // namespace voxcd
