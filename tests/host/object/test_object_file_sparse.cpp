// Object files of sparse objects (version 5): a round trip keeps the sparse forms and gives the dense object's states
// and points; dense objects keep versions 2 to 4 byte for byte; auto picks each part's smaller form; and every damaged
// version 5 file gives an ObjectFileError naming the file and a byte, never a crash or a different object.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/shapes.h"
#include "tests/error_text.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

ObjectFile object_of(const std::string& shape, double voxel, ObjectStorage storage) {
  ObjectOptions o;
  o.voxel = voxel;
  o.shift = Eigen::Vector3d(0.3, 0.7, 0.55);
  set_storage(o, storage);
  MeshReport rep;
  std::string src;
  uint64_t hash = 0;
  const Mesh m = load_source(shape, &src, &hash, &rep);
  return make_object(m, src, hash, o, &rep);
}

uint32_t version_of(const std::string& path) {
  uint32_t v = 0;
  std::memcpy(&v, test::read_file(path).data() + 8, 4);
  return v;
}

TEST(SparseObjectFile, RoundTripKeepsTheSparseFormsAndTheDenseStates) {
  const std::string p = test::tmp_path("sparse_round.vox");
  for (const char* shape : {"torus", "stellated", "plate", "sphere"}) {
    const ObjectFile s = object_of(shape, 0.03, ObjectStorage::kSparse);
    const ObjectFile d = object_of(shape, 0.03, ObjectStorage::kDense);
    ASSERT_TRUE(s.voxmap_sparse() && s.shell_sparse() && !s.has_dense_voxmap()) << shape;
    write_object(p, s);
    EXPECT_EQ(version_of(p), 5u) << shape;
    const ObjectFile stored = read_object(p, ObjectRead::kStored);
    EXPECT_TRUE(stored.sparse_voxmap == s.sparse_voxmap) << shape;
    EXPECT_EQ(stored.sparse_shell.bricks, s.sparse_shell.bricks) << shape;
    EXPECT_EQ(stored.sparse_shell.masks, s.sparse_shell.masks) << shape;
    EXPECT_EQ(stored.sparse_shell.normals, s.sparse_shell.normals) << shape;
    EXPECT_TRUE(stored.sparse_shell.grid.dims == s.sparse_shell.grid.dims) << shape;
    EXPECT_FALSE(stored.has_dense_voxmap()) << shape;
    EXPECT_EQ(stored.shell.size(), 0u) << shape;
    EXPECT_EQ(stored.voxelize_report.evaluated, d.voxelize_report.evaluated) << shape;
    EXPECT_EQ(stored.mesh_report.triangles, d.mesh_report.triangles) << shape;
    const ObjectFile with = read_object(p);
    EXPECT_EQ(with.voxmap.words(), d.voxmap.words()) << shape;
    EXPECT_EQ(with.shell.cells, d.shell.cells) << shape;
    EXPECT_EQ(with.shell.points, d.shell.points) << shape;
    // Written again as read, the file is the same.
    const std::string again = test::tmp_path("sparse_again.vox");
    write_object(again, with);
    EXPECT_TRUE(test::read_file(again) == test::read_file(p)) << shape;
    std::remove(again.c_str());
  }
  std::remove(p.c_str());
}

// Dense objects are the files they were; auto takes each part's smaller form.
TEST(SparseObjectFile, DenseFilesKeepTheirVersionsAndAutoPicksTheSmallerForm) {
  const std::string p = test::tmp_path("dense_kept.vox");
  write_object(p, object_of("icosahedron", 0.15, ObjectStorage::kDense));
  EXPECT_EQ(version_of(p), 2u);
  const DeviceConfig cfg;
  for (double voxel : {0.5, 0.1, 0.02}) {
    const ObjectFile a = object_of("torus", voxel, ObjectStorage::kAuto);
    const ObjectFile s = object_of("torus", voxel, ObjectStorage::kSparse);
    const ObjectFile d = object_of("torus", voxel, ObjectStorage::kDense);
    const uint64_t dense_map = d.voxmap.device_words(cfg.MEMW).size() * 8, dense_shell = d.shell.size() * 9;
    EXPECT_EQ(a.voxmap_sparse(), s.sparse_voxmap.bytes() < dense_map) << voxel;
    EXPECT_EQ(a.shell_sparse(), s.sparse_shell.bytes() < dense_shell) << voxel;
    // Whatever auto picked, the dense parts are the dense object's exactly (the shell's normals too).
    if (!a.voxmap_sparse()) {
      EXPECT_EQ(a.voxmap.words(), d.voxmap.words()) << voxel;
    }
    if (!a.shell_sparse()) {
      EXPECT_EQ(a.shell.normals, d.shell.normals) << voxel;
    }
    write_object(p, a);
    EXPECT_EQ(version_of(p), a.voxmap_sparse() || a.shell_sparse() ? 5u : 2u) << voxel;
  }
  std::remove(p.c_str());
}

// A sparse object larger than a dense voxmap takes: stored and read sparse; its object type says why it cannot be one.
TEST(SparseObjectFile, LargeObjectsStaySparse) {
  ObjectOptions o;
  o.resolution = 1100;
  set_storage(o, ObjectStorage::kAuto);
  const ObjectFile big = make_object(make_shape("torus"), "shape:torus", hash_bytes("shape:torus"), o);
  EXPECT_TRUE(big.voxmap_sparse() && big.shell_sparse());
  EXPECT_EQ(big.voxmap_grid().dims[0], 1103u);
  const std::string p = test::tmp_path("sparse_big.vox");
  write_object(p, big);
  const ObjectFile back = read_object(p);
  EXPECT_FALSE(back.has_dense_voxmap());
  EXPECT_TRUE(back.sparse_voxmap == big.sparse_voxmap);
  const std::string e = test::error_text<MeshError>([&] { make_object_type(back, "big"); });
  EXPECT_NE(e.find("big: the object is stored sparse (voxmap 1103x1103x"), std::string::npos) << e;
  std::remove(p.c_str());
}

// Damaged version 5 files.
class DamagedSparseFile : public ::testing::Test {
 protected:
  void SetUp() override {
    write_object(good_, object_of("torus", 0.08, ObjectStorage::kSparse));
    bytes_ = test::read_file(good_);
  }
  void TearDown() override {
    std::remove(good_.c_str());
    std::remove(bad_.c_str());
  }
  // The error reading `b` (with its CRC made right when fix_crc), which must name the file, a byte and `what`.
  std::string expect_error(std::string b, const std::string& what, bool fix_crc, const std::string& why) {
    if (fix_crc) {
      const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(b.data()), uInt(b.size() - 4)));
      std::memcpy(&b[b.size() - 4], &crc, 4);
    }
    test::write_file(bad_, b);
    std::string e;
    try {
      read_object(bad_);
    } catch (const ObjectFileError& x) {
      e = x.what();
    }
    EXPECT_EQ(e.rfind(bad_ + ": ", 0), 0u) << why << ": " << e;
    EXPECT_NE(e.find("byte "), std::string::npos) << why << ": " << e;
    EXPECT_NE(e.find(what), std::string::npos) << why << ": " << e;
    return e;
  }
  // Where the sparse voxmap section starts: after the header, source, ratio, shift and the voxmap grid.
  size_t voxmap_at() const { return 28 + std::string("shape:torus").size() + 32 + 44; }
  const std::string good_ = test::tmp_path("sparse_good.vox"), bad_ = test::tmp_path("sparse_bad.vox");
  std::string bytes_;
};

TEST_F(DamagedSparseFile, TruncatedOrChangedAnywhere) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed + 50);
  std::uniform_int_distribution<size_t> any(0, bytes_.size() - 1);
  std::uniform_int_distribution<int> bit(0, 7);
  for (size_t n = 0; n < 400; ++n) {
    const size_t len = n < 200 ? voxmap_at() + n : any(rng);
    expect_error(bytes_.substr(0, len), "truncated at byte", false, "length " + std::to_string(len));
  }
  for (int i = 0; i < 300; ++i) {
    std::string c = bytes_;
    const size_t at = any(rng);
    c[at] = char(c[at] ^ (1 << bit(rng)));
    expect_error(c, "", false, "byte " + std::to_string(at) + " changed, seed " + std::to_string(seed));
  }
}

TEST_F(DamagedSparseFile, EachCheckNamesWhatIsWrong) {
  const size_t at = voxmap_at();
  std::string c = bytes_;
  c[at] = 7;  // BL
  expect_error(c, "the sparse voxmap's BL 7 is not 2..4", true, "BL");
  c = bytes_;
  c[at + 4] = char(c[at + 4] + 1);  // the empty count
  expect_error(c, "state counts do not match the sparse voxmap", true, "counts");
  c = bytes_;
  c[at + 28] = char(c[at + 28] + 1);  // the cell count
  expect_error(c, "cell count", true, "cells");
  // An empty cell made a brick: the brick count no longer matches.
  const SparseVoxmap sm = read_object(good_, ObjectRead::kStored).sparse_voxmap;
  uint64_t t = 0;
  while (sm.code(t) != kEmpty) ++t;
  c = bytes_;
  c[at + 44 + t / 4] = char(c[at + 44 + t / 4] | 3 << (2 * (t % 4)));
  expect_error(c, "brick count", true, "bricks");
  // The flags: a shell on the surface and sparse; version 5 with neither part sparse.
  c = bytes_;
  c[12] = char(c[12] | 1);
  expect_error(c, "a shell on the surface is never sparse", true, "flags");
  c = bytes_;
  c[12] = 0;
  expect_error(c, "its flags say none", true, "no sparse part");
  // The sparse distance section, 12 bytes before the checksum: a field of no bytes.
  c = bytes_;
  c[c.size() - 16] = 1;
  expect_error(c, "the sparse distance field: truncated", true, "distance kind");
  c = bytes_;
  c[c.size() - 12] = 5;
  expect_error(c, "an absent sparse distance section has a length of 5", true, "distance length");
}

TEST_F(DamagedSparseFile, NonCanonicalBricksAndRepeatedShellBricks) {
  const ObjectFile s = read_object(good_, ObjectRead::kStored);
  const size_t codes_at = voxmap_at() + 4 + 24 + 16;
  const size_t bricks_at = codes_at + 8 * s.sparse_voxmap.code_words().size() + 8;
  // Brick 0 made every voxel surface: a uniform cell written as a brick.
  std::string c = bytes_;
  for (size_t k = 0; k < 128; ++k) c[bricks_at + k] = 0x55;
  expect_error(c, "brick 0 (cell ", true, "uniform brick");
  // Shell brick 1 written as brick 0.
  const size_t shell_at = bricks_at + s.sparse_voxmap.brick_data().size() * 8;
  const size_t shell_bricks_at = shell_at + 44 + 8;
  c = bytes_;
  std::memcpy(&c[shell_bricks_at + 6], &c[shell_bricks_at], 6);
  expect_error(c, "holds a brick twice", true, "repeated brick");
}

}  // namespace
}  // namespace voxcd
