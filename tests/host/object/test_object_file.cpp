// The object file: a round trip keeps every field, the byte layout is the one docs/objects.md gives, and every
// damaged file (truncated anywhere, any byte changed, wrong magic or version, bytes appended) gives an
// ObjectFileError that names the file and a byte offset, never a crash or a silently different object.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <fstream>
#include <random>
#include <sstream>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "tests/defects.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

ObjectFile small_object(const std::string& shape, double voxel) {
  ObjectOptions o;
  o.voxel = voxel;
  o.shift = Eigen::Vector3d(0.3, 0.7, 0.55);
  MeshReport rep;
  const Mesh m = load_source(shape, nullptr, nullptr, &rep);
  return make_object(m, "shape:" + shape, hash_bytes("shape:" + shape), o, &rep);
}

// The message of the ObjectFileError that reading `path` throws ("" when it reads).
std::string read_error(const std::string& path) {
  try {
    read_object(path);
  } catch (const ObjectFileError& e) {
    return e.what();
  }
  return "";
}

void expect_same(const ObjectFile& a, const ObjectFile& b) {
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.source_hash, b.source_hash);
  EXPECT_EQ(a.shell_ratio, b.shell_ratio);
  EXPECT_EQ(a.shift, b.shift);
  EXPECT_EQ(a.voxmap.dims(), b.voxmap.dims());
  EXPECT_EQ(a.voxmap.voxel(), b.voxmap.voxel());
  EXPECT_EQ(a.voxmap.origin(), b.voxmap.origin());
  EXPECT_EQ(a.voxmap.words(), b.voxmap.words());
  EXPECT_EQ(a.shell.grid.dims, b.shell.grid.dims);
  EXPECT_EQ(a.shell.grid.voxel, b.shell.grid.voxel);
  EXPECT_EQ(a.shell.grid.origin, b.shell.grid.origin);
  EXPECT_EQ(a.shell.cells, b.shell.cells);
  EXPECT_EQ(a.shell.points, b.shell.points);
  EXPECT_EQ(a.shell.normals, b.shell.normals);
}

TEST(ObjectFile, RoundTrip) {
  for (const char* shape : {"stellated", "torus", "plate"}) {
    const ObjectFile a = small_object(shape, 0.09);
    const std::string p = test::tmp_path(std::string(shape) + ".vox");
    write_object(p, a);
    const ObjectFile b = read_object(p);
    expect_same(a, b);
    // The shell read back gives the same device words as the one built.
    const DeviceConfig cfg;
    const auto wa = a.shell.words(cfg), wb = b.shell.words(cfg);
    ASSERT_EQ(wa.size(), wb.size());
    for (size_t k = 0; k < wa.size(); ++k) ASSERT_TRUE(wa[k] == wb[k]) << shape << " point " << k;
    std::remove(p.c_str());
  }
  // A file's own hash.
  const std::string p = test::tmp_path("hash.txt");
  test::write_file(p, "abc");
  EXPECT_EQ(hash_file(p), hash_bytes("abc"));
  EXPECT_EQ(hash_bytes(""), 0xcbf29ce484222325ull);  // FNV-1a 64 offset basis
  EXPECT_EQ(hash_bytes("a"), 0xaf63dc4c8601ec8cull);  // published FNV-1a 64 test vector
  std::remove(p.c_str());
}

// Reads the file by the byte layout of docs/objects.md, independently of read_object.
struct LayoutReader {
  const std::string& b;
  size_t pos = 0;
  template <class T>
  T get() {
    T v;
    EXPECT_LE(pos + sizeof(T), b.size());
    if (pos + sizeof(T) > b.size()) throw std::out_of_range("layout");
    std::memcpy(&v, b.data() + pos, sizeof(T));
    pos += sizeof(T);
    return v;
  }
};

TEST(ObjectFile, ByteLayoutIsTheDocumentedOne) {
  const ObjectFile a = small_object("icosahedron", 0.15);
  const std::string p = test::tmp_path("layout.vox");
  write_object(p, a);
  const std::string b = test::read_file(p);
  std::remove(p.c_str());
  LayoutReader r{b};
  EXPECT_EQ(b.substr(0, 8), "VOXCDOBJ");
  r.pos = 8;
  EXPECT_EQ(r.get<uint32_t>(), 2u);  // version
  EXPECT_EQ(r.get<uint32_t>(), 0u);  // flags
  EXPECT_EQ(r.get<uint64_t>(), a.source_hash);
  const uint32_t len = r.get<uint32_t>();
  EXPECT_EQ(b.substr(r.pos, len), a.source);
  r.pos += len;
  EXPECT_EQ(r.get<double>(), a.shell_ratio);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.get<double>(), a.shift[i]);
  auto grid = [&](const GridPlacement& g) {
    EXPECT_EQ(r.get<double>(), g.voxel);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.get<double>(), g.origin[i]);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.get<uint32_t>(), g.dims[i]);
  };
  grid(a.voxmap.grid());
  const auto c = a.voxmap.counts();
  EXPECT_EQ(r.get<uint64_t>(), c[kEmpty]);
  EXPECT_EQ(r.get<uint64_t>(), c[kSurface]);
  EXPECT_EQ(r.get<uint64_t>(), c[kInterior]);
  EXPECT_EQ(r.get<uint32_t>(), 64u);
  const uint64_t nw = r.get<uint64_t>();
  ASSERT_EQ(nw, (a.voxmap.size() + 31) / 32);
  // The device's packing: voxel i at word i / 32, bits 2 * (i % 32).
  std::vector<uint64_t> words(nw);
  for (auto& w : words) w = r.get<uint64_t>();
  for (uint64_t i = 0; i < a.voxmap.size(); ++i)
    ASSERT_EQ((words[i / 32] >> (2 * (i % 32))) & 3, uint64_t(a.voxmap.at(i))) << i;
  grid(a.shell.grid);
  EXPECT_EQ(r.get<uint32_t>(), 8u);
  const uint64_t n = r.get<uint64_t>();
  ASSERT_EQ(n, a.shell.size());
  for (uint64_t k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) ASSERT_EQ(r.get<int32_t>(), int32_t((2 * a.shell.cells[k][i] + 1) * 128)) << k;
  for (uint64_t k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) ASSERT_EQ(r.get<double>(), a.shell.points[k][i]);
  for (uint64_t k = 0; k < n; ++k)
    for (int i = 0; i < 3; ++i) ASSERT_EQ(r.get<double>(), a.shell.normals[k][i]);
  // The report (version 2): flags (16: present, 1: closed), weld tolerance, 19 counts.
  const MeshReport& m = a.mesh_report;
  ASSERT_TRUE(a.has_report);
  EXPECT_EQ(r.get<uint32_t>(), 16u | 1u);
  EXPECT_EQ(r.get<double>(), m.weld_tolerance);
  for (uint64_t v : {m.input_vertices, m.input_triangles, m.vertices, m.triangles, m.welded, m.welded_near, m.dropped_nonfinite,
                     m.dropped_repeated, m.dropped_collinear, m.dropped_duplicate, m.reoriented, m.open_edges,
                     m.nonmanifold_edges, m.inconsistent_edges, m.components, m.closed_components,
                     m.sheet_components, a.voxelize_report.uncertain, a.voxelize_report.evaluated})
    EXPECT_EQ(r.get<uint64_t>(), v);
  EXPECT_EQ(m.input_triangles, 20u);
  EXPECT_EQ(m.components, 1u);
  const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(b.data()), uInt(r.pos)));
  EXPECT_EQ(r.get<uint32_t>(), crc);
  EXPECT_EQ(r.pos, b.size());
}

// Version 4: an object with non-manifold parts or conservative distance cells keeps those counts in the report's
// second section, the last field before the checksum; damaged, it is refused with the byte.
TEST(ObjectFile, Version4KeepsTheSecondReportSection) {
  const test::Defect d = test::face_sharing_boxes();
  Mesh m = d.mesh;
  const MeshReport rep = repair(m);
  ObjectOptions o;
  o.resolution = 24;
  o.distance_bits = 8;
  const ObjectFile a = make_object(m, "faces.raw", 7, o, &rep);
  ASSERT_EQ(a.mesh_report.dropped_internal, 2u);
  ASSERT_GT(a.voxelize_report.conservative, 0u);
  const std::string p = test::tmp_path("v4.vox");
  write_object(p, a);
  const std::string b = test::read_file(p);
  uint32_t version = 0;
  std::memcpy(&version, b.data() + 8, 4);
  EXPECT_EQ(version, 4u);
  // Count, four counts, checksum.
  LayoutReader r{b};
  r.pos = b.size() - 4 - 32 - 4;
  EXPECT_EQ(r.get<uint32_t>(), 4u);
  for (uint64_t v : {uint64_t(a.mesh_report.nonmanifold_parts), uint64_t(a.mesh_report.dropped_internal),
                     uint64_t(a.mesh_report.fin_triangles), a.voxelize_report.conservative})
    EXPECT_EQ(r.get<uint64_t>(), v);
  const ObjectFile back = read_object(p);
  EXPECT_EQ(back.mesh_report.nonmanifold_parts, 1u);
  EXPECT_EQ(back.mesh_report.dropped_internal, 2u);
  EXPECT_EQ(back.voxelize_report.conservative, a.voxelize_report.conservative);
  EXPECT_EQ(back.distance.q, a.distance.q);
  // A count that is not 4 (checksum fixed up), and the file cut inside the section.
  std::string c = b;
  c[b.size() - 40] = 5;
  const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(c.data()), uInt(c.size() - 4)));
  std::memcpy(&c[c.size() - 4], &crc, 4);
  test::write_file(p, c);
  EXPECT_NE(read_error(p).find("holds 5 counts; version 4 has 4 (byte " + std::to_string(b.size() - 40) + ")"),
            std::string::npos)
      << read_error(p);
  test::write_file(p, b.substr(0, b.size() - 20));
  EXPECT_NE(read_error(p).find("truncated"), std::string::npos) << read_error(p);
  std::remove(p.c_str());
  // An object without either keeps its version: a closed shape without a field is version 2.
  const ObjectFile plain = small_object("icosahedron", 0.15);
  write_object(p, plain);
  std::memcpy(&version, test::read_file(p).data() + 8, 4);
  EXPECT_EQ(version, 2u);
  std::remove(p.c_str());
}

TEST(ObjectFile, DamagedFilesNameTheFileAndTheByte) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed + 20);
  const ObjectFile a = small_object("stellated", 0.2);
  const std::string good = test::tmp_path("good.vox"), bad = test::tmp_path("bad.vox");
  write_object(good, a);
  const std::string b = test::read_file(good);
  const std::string where = bad + ": ";
  auto expect_error = [&](const std::string& bytes, const std::string& what, const std::string& why) {
    test::write_file(bad, bytes);
    const std::string e = read_error(bad);
    EXPECT_EQ(e.rfind(where, 0), 0u) << why << ": " << e;
    EXPECT_NE(e.find("byte "), std::string::npos) << why << ": " << e;
    EXPECT_NE(e.find(what), std::string::npos) << why << ": " << e;
    return e;
  };
  // Truncated: at every length up to the voxmap words, then at random lengths.
  std::vector<size_t> lengths;
  for (size_t n = 0; n < 260; ++n) lengths.push_back(n);
  std::uniform_int_distribution<size_t> len(0, b.size() - 1);
  for (int i = 0; i < 200; ++i) lengths.push_back(len(rng));
  lengths.push_back(b.size() - 1);
  for (size_t n : lengths) expect_error(b.substr(0, n), "truncated at byte", "length " + std::to_string(n));
  EXPECT_EQ(expect_error(b.substr(0, 3), "", "3 bytes"),
            where + "truncated at byte 0 while reading the magic number (8 bytes needed, 3 left)");
  // Every single changed byte is found (structure checks, or else the CRC), and reading never crashes.
  std::uniform_int_distribution<int> bit(0, 7);
  for (int i = 0; i < 400; ++i) {
    std::string c = b;
    const size_t at = i < 200 ? size_t(i) : len(rng);
    c[at] = char(c[at] ^ (1 << bit(rng)));
    expect_error(c, "", "byte " + std::to_string(at) + " changed, seed " + std::to_string(seed));
  }
  // Wrong magic, wrong version, unknown flags, bytes after the checksum.
  {
    std::string c = b;
    c[0] = 'W';
    EXPECT_EQ(expect_error(c, "bad magic", "magic"), where + "not a voxcd object file (bad magic) (byte 0)");
    c = b;
    c[8] = 6;
    EXPECT_EQ(expect_error(c, "version 6 is not supported", "version"),
              where + "object file version 6 is not supported (this reader knows versions 1 to 5) (byte 8)");
    c = b;
    c[12] = 1;
    expect_error(c, "unknown flags 1", "flags");
    expect_error(b + "x", "1 unexpected bytes after the checksum", "appended");
  }
  // A consistent file (correct CRC) with a wrong state count or a reserved state is still refused.
  {
    auto with_crc = [](std::string c) {
      const uint32_t crc = uint32_t(crc32(0, reinterpret_cast<const Bytef*>(c.data()), uInt(c.size() - 4)));
      std::memcpy(&c[c.size() - 4], &crc, 4);
      return c;
    };
    const size_t counts_at = 28 + a.source.size() + 32 + 44;
    std::string c = b;
    c[counts_at] = char(c[counts_at] + 1);
    EXPECT_NE(expect_error(with_crc(c), "state counts do not match", "count")
                  .find("(byte " + std::to_string(counts_at) + ")"),
              std::string::npos);
    c = b;
    const size_t words_at = counts_at + 24 + 4 + 8;
    c[words_at] = char(0xff);  // voxels 0..3 in state 3
    expect_error(with_crc(c), "reserved state 3", "reserved");
  }
  EXPECT_EQ(read_error("/nonexistent/x.vox"), "/nonexistent/x.vox: cannot open");
  std::remove(good.c_str());
  std::remove(bad.c_str());
}

TEST(ObjectFile, SourcesAndErrors) {
  std::string source;
  uint64_t hash = 0;
  const Mesh m = load_source("torus", &source, &hash);
  EXPECT_EQ(source, "shape:torus");
  EXPECT_EQ(hash, hash_bytes("shape:torus"));
  EXPECT_EQ(m.size(), make_shape("torus").size());
  // A file wins over a shape name, and its hash is its bytes'.
  const std::string p = test::tmp_path("cube.obj");
  test::write_obj(make_shape("cube"), p);
  load_source(p, &source, &hash);
  EXPECT_EQ(source, p);
  EXPECT_EQ(hash, hash_file(p));
  std::remove(p.c_str());
  try {
    load_source("teapot");
    ADD_FAILURE() << "no error";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("teapot: no such file, and not a built-in shape (polytope36"),
              std::string::npos)
        << e.what();
  }
  // Writing where no file can be: an error naming it, no temporary left behind.
  try {
    write_object("/nonexistent/dir/x.vox", small_object("cube", 0.5));
    ADD_FAILURE() << "no error";
  } catch (const ObjectFileError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/x.vox"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace voxcd
