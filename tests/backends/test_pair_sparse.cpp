// Pairs of objects stored sparse (docs/pairs.md, "Sparse objects"): on the sparse device device_config_for picks, a
// 2-bit pair finds exactly the contacts of the same objects stored dense (the same shell points in the same voxels
// with the same states and depths, whatever order the sparse shell's blocks run in), and every backend that has the
// configuration gives the same contacts and cycles. A sparse distance field (refined bricks) runs the same on every
// backend. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <tuple>
#include <vector>

#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

std::shared_ptr<const ObjectType> type_of(const std::string& shape, double voxel, ObjectStorage storage,
                                          int distance_bits = 0) {
  ObjectOptions o;
  o.voxel = voxel;
  o.distance_bits = distance_bits;
  set_storage(o, storage);
  const Mesh mesh = make_shape(shape);
  return std::make_shared<ObjectType>(make_object_type(make_object(mesh, "shape:" + shape, 0, o), shape));
}

std::vector<PairRequest> touching_poses(uint64_t seed, int n, double spread) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(-spread, spread);
  std::vector<PairRequest> reqs;
  for (int k = 0; k < n; ++k) {
    PairRequest r;
    r.a = 0, r.b = 1;
    r.pose_a.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    r.pose_b.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    r.pose_b.translation = Eigen::Vector3d(u(rng), u(rng), u(rng));
    reqs.push_back(r);
  }
  return reqs;
}

// A pair's contacts: direction, shell point, voxel, state and depth, in the order reported (each direction's in
// ascending point order, whatever order the device's slots hold them in).
using ContactKey = std::tuple<bool, uint32_t, uint32_t, uint32_t, uint32_t, int, double>;
std::vector<ContactKey> contact_set(const PairResult& r) {
  std::vector<ContactKey> s;
  for (const Contact& c : r.contacts)
    s.emplace_back(c.a_in_b, c.point, c.voxel[0], c.voxel[1], c.voxel[2], int(c.state), c.depth);
  return s;
}

std::vector<PairResult> run(const std::string& backend, const DeviceConfig& cfg,
                            const std::vector<std::shared_ptr<const ObjectType>>& types,
                            const std::vector<PairRequest>& reqs, Mode mode) {
  PairOptions opt;
  opt.mode = mode;
  opt.both_directions = true;
  PairCollider col(make_device(backend, cfg), types);
  return col.collide(reqs, opt);
}

std::vector<const ObjectType*> raw(const std::vector<std::shared_ptr<const ObjectType>>& types) {
  std::vector<const ObjectType*> v;
  for (const auto& t : types) v.push_back(t.get());
  return v;
}

// The backends with a model of cfg: ref and cpu, and rtl where the build lists cfg among its sparse models.
std::vector<std::string> backends_for(const DeviceConfig& cfg) {
  std::vector<std::string> b = {"ref", "cpu"};
  for (const DeviceConfig& c : rtl_sparse_configs())
    if (c == cfg && rtl_unavailable().empty()) b.push_back("rtl");
  return b;
}

uint64_t seed() {
  const uint64_t s = test::seed();
  return s;
}

TEST(SparsePairs, DeviceConfigForTakesTheBricksOfSparseTypes) {
  const auto dense = type_of("torus", 0.15, ObjectStorage::kDense), sparse = type_of("torus", 0.15, ObjectStorage::kSparse);
  EXPECT_EQ(device_config_for("ref", 4, {dense.get()}).BL, 0);
  const DeviceConfig cfg = device_config_for("ref", 4, {dense.get(), sparse.get()});
  EXPECT_EQ(cfg.BL, sparse->object.sparse_voxmap.bl());
  EXPECT_TRUE(map_is_sparse(cfg, *sparse));
  EXPECT_FALSE(map_is_sparse(cfg, *dense));
  EXPECT_TRUE(shell_is_sparse(cfg, *sparse));
  EXPECT_FALSE(shell_is_sparse(cfg, *dense));  // a type stored dense keeps its dense jobs
  // The sparse shell holds fewer words than points (a 4^3 brick a word, an origin word a block).
  EXPECT_LT(type_shell_words(cfg, *sparse), sparse->shell().size());
  const detail::ShellOrder o = shell_order(cfg, *sparse);
  ASSERT_TRUE(o.sparse());
  std::vector<uint32_t> points = o.point;
  std::sort(points.begin(), points.end());
  for (uint32_t k = 0; k < points.size(); ++k) ASSERT_EQ(points[k], k) << "the slots are a permutation of the points";
}

TEST(SparsePairs, TwoBitContactsAreThoseOfTheDenseObjects) {
  const uint64_t s = seed();
  const std::vector<std::shared_ptr<const ObjectType>> dense = {type_of("stellated", 0.15, ObjectStorage::kDense),
                                                                type_of("torus", 0.15, ObjectStorage::kDense)};
  const std::vector<std::shared_ptr<const ObjectType>> sparse = {type_of("stellated", 0.15, ObjectStorage::kSparse),
                                                                 type_of("torus", 0.15, ObjectStorage::kSparse)};
  const DeviceConfig cfg = device_config_for("ref", 4, raw(sparse));
  ASSERT_GT(cfg.BL, 0);
  const std::vector<PairRequest> reqs = touching_poses(s, 30, 1.0);
  for (Mode mode : {Mode::All, Mode::Count, Mode::First}) {
    const std::vector<PairResult> want = run("ref", DeviceConfig{}, dense, reqs, mode);
    std::vector<std::vector<PairResult>> got;
    const std::vector<std::string> backends = backends_for(cfg);
    for (const std::string& b : backends) got.push_back(run(b, cfg, sparse, reqs, mode));
    size_t touching = 0;
    uint64_t dense_cycles = 0, sparse_cycles = 0;
    for (size_t i = 0; i < reqs.size(); ++i) {
      touching += want[i].hits > 0;
      dense_cycles += want[i].device_cycles, sparse_cycles += got[0][i].device_cycles;
      for (size_t b = 0; b < backends.size(); ++b) {
        const PairResult& r = got[b][i];
        const std::string where = backends[b] + " pair " + std::to_string(i) + " " + mode_name(mode);
        if (mode == Mode::First) {
          ASSERT_EQ(r.hits > 0, want[i].hits > 0) << where;
        } else {
          ASSERT_EQ(r.hits, want[i].hits) << where;
          EXPECT_EQ(contact_set(r), contact_set(want[i])) << where;
        }
        EXPECT_EQ(r.device_cycles, got[0][i].device_cycles) << where << ": cycles against ref's";
        EXPECT_EQ(r.lookups, got[0][i].lookups) << where;
      }
    }
    EXPECT_GT(touching, reqs.size() / 4) << "the poses must touch for the comparison to mean something";
    EXPECT_LT(touching, reqs.size()) << "and some must not";
    // The sparse device times its shells by their words (docs/contract.md, "Sparse timing"): not the dense cycles.
    EXPECT_NE(sparse_cycles, dense_cycles) << mode_name(mode);
    std::printf("%s: dense %llu cycles, sparse %llu\n", mode_name(mode), (unsigned long long)dense_cycles,
                (unsigned long long)sparse_cycles);
  }
}

TEST(SparsePairs, ADenseAndASparseTypeShareOneSparseDevice) {
  const uint64_t s = seed();
  const std::vector<std::shared_ptr<const ObjectType>> dense = {type_of("cube", 0.1, ObjectStorage::kDense),
                                                                type_of("torus", 0.15, ObjectStorage::kDense)};
  const std::vector<std::shared_ptr<const ObjectType>> mixed = {dense[0], type_of("torus", 0.15, ObjectStorage::kSparse)};
  const DeviceConfig cfg = device_config_for("cpu", 2, raw(mixed));
  const std::vector<PairRequest> reqs = touching_poses(s + 7, 20, 0.8);
  const std::vector<PairResult> want = run("cpu", DeviceConfig{}, dense, reqs, Mode::All);
  const std::vector<PairResult> got = run("cpu", cfg, mixed, reqs, Mode::All);
  size_t contacts = 0;
  for (size_t i = 0; i < reqs.size(); ++i) {
    EXPECT_EQ(contact_set(got[i]), contact_set(want[i])) << "pair " << i;
    contacts += want[i].contacts.size();
  }
  EXPECT_GT(contacts, 100u);
}

TEST(SparsePairs, SparseDistanceFieldsRunAlikeOnEveryBackend) {
  const uint64_t s = seed();
  const std::vector<std::shared_ptr<const ObjectType>> types = {type_of("cube", 0.12, ObjectStorage::kSparse, 8),
                                                                type_of("torus", 0.12, ObjectStorage::kSparse, 8)};
  ASSERT_TRUE(types[0]->object.distance_sparse());
  const DeviceConfig cfg = device_config_for("ref", 2, raw(types), 8);
  ASSERT_TRUE(cfg.distance() && cfg.sparse());
  const std::vector<PairRequest> reqs = touching_poses(s + 11, 20, 0.9);
  const std::vector<std::string> backends = backends_for(cfg);
  const std::vector<PairResult> want = run("ref", cfg, types, reqs, Mode::All);
  size_t contacts = 0;
  for (size_t i = 0; i < reqs.size(); ++i) contacts += want[i].contacts.size();
  EXPECT_GT(contacts, 50u);
  for (size_t b = 1; b < backends.size(); ++b) {
    const std::vector<PairResult> got = run(backends[b], cfg, types, reqs, Mode::All);
    for (size_t i = 0; i < reqs.size(); ++i) {
      EXPECT_EQ(contact_set(got[i]), contact_set(want[i])) << backends[b] << " pair " << i;
      EXPECT_EQ(got[i].device_cycles, want[i].device_cycles) << backends[b] << " pair " << i;
    }
  }
}

TEST(SparsePairs, ASparseFieldOnADenseDeviceIsRefusedSayingWhy) {
  const auto t = type_of("torus", 0.12, ObjectStorage::kSparse, 8);
  ASSERT_TRUE(t->object.distance.empty()) << "the field is held sparse only";
  DeviceConfig cfg;
  cfg.SB = 8;
  try {
    PairCollider col(make_device("ref", cfg), {t, t});
    FAIL() << "a dense distance device took a sparse field";
  } catch (const CapacityError& e) {
    EXPECT_NE(std::string(e.what()).find("needs a sparse device (BL = 3)"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace voxcd
