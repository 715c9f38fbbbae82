// Mesh loading, welding and validation: every format through its loader, and every kind of bad input gives an
// error that names the problem.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/shapes.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

using test::tmp_path;

// The message of the MeshError that fn throws ("" when it throws none).
template <class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const MeshError& e) {
    return e.what();
  }
  return "";
}

Mesh raw_mesh(const std::string& text) {
  std::istringstream in(text);
  Mesh m = parse_raw(in, "test.raw");
  return m;
}

TEST(Shapes, AllClosedAndOutward) {
  for (const auto& name : shape_names()) {
    const Mesh m = make_shape(name);
    EXPECT_GT(m.volume(), 0) << name;
    EXPECT_EQ(m.name, name);
  }
  EXPECT_EQ(make_shape("polytope36").size(), 36u);
  EXPECT_EQ(make_shape("stellated").size(), 60u);
  EXPECT_EQ(make_shape("icosahedron").size(), 20u);
  EXPECT_NEAR(make_shape("cube").volume(), 8.0, 1e-12);
  EXPECT_NEAR(make_shape("plate").volume(), 0.2, 1e-12);
  // The sphere approximates 4/3 pi from inside.
  const double vs = make_shape("sphere").volume();
  EXPECT_LT(vs, 4.0 / 3 * M_PI);
  EXPECT_GT(vs, 0.98 * 4.0 / 3 * M_PI);
  // The stellation is concave: its volume is well below its convex hull's (the icosahedron of its tips).
  const Mesh st = make_shape("stellated");
  double r = 0;
  for (const auto& v : st.vertices) r = std::max(r, v.norm());
  EXPECT_NEAR(r, 1.0, 1e-12);
  const double ico_circum = std::sqrt(1 + std::pow((1 + std::sqrt(5.0)) / 2, 2));
  EXPECT_LT(st.volume(), 0.7 * make_shape("icosahedron").volume() / std::pow(ico_circum, 3));
  EXPECT_NE(error_of([] { make_shape("teapot"); }).find("unknown shape 'teapot'"), std::string::npos);
}

TEST(Mesh, RawRoundTripAndWelding) {
  const Mesh cube = make_shape("cube");
  std::ostringstream out;
  write_raw(cube, out);
  Mesh m = raw_mesh("# a comment\nObject1\n" + out.str());
  EXPECT_EQ(m.vertices.size(), 36u);  // RAW repeats every vertex
  const MeshReport r = prepare(m);
  EXPECT_EQ(r.welded, 28u);
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_NEAR(m.volume(), 8.0, 1e-12);
}

TEST(Mesh, EveryFormatLoads) {
  const Mesh src = make_shape("stellated");
  const std::string base = tmp_path("stellated");
  {
    std::ofstream o(base + ".raw");
    write_raw(src, o);
  }
  test::write_obj(src, base + ".obj");
  test::write_stl(src, base + ".stl");
  test::write_ply(src, base + ".ply");
  for (const char* ext : {".raw", ".obj", ".stl", ".ply"}) {
    MeshReport rep;
    const Mesh m = load_mesh(base + ext, &rep);
    EXPECT_EQ(m.size(), src.size()) << ext;
    EXPECT_EQ(m.vertices.size(), src.vertices.size()) << ext;
    // STL stores single precision.
    EXPECT_NEAR(m.volume(), src.volume(), 1e-5) << ext;
    std::remove((base + ext).c_str());
  }
}

TEST(Mesh, ErrorsNameTheProblem) {
  // Truncated RAW: the last line lost three numbers.
  EXPECT_NE(error_of([] { raw_mesh("0 0 0 1 0 0 0 1 0\n0 0 0 0 1 0\n"); }).find("test.raw:2"), std::string::npos);
  EXPECT_NE(error_of([] { raw_mesh("0 0 0 1 0 0 0 1 zero\n"); }).find("test.raw:1"), std::string::npos);
  // NaN vertex.
  {
    Mesh m = make_shape("icosahedron");
    m.vertices[3].y() = std::nan("");
    const std::string e = error_of([&] { prepare(m); });
    EXPECT_NE(e.find("not a finite number"), std::string::npos) << e;
  }
  {
    Mesh m = raw_mesh("0 0 0 1 0 0 0 1 nan\n");
    EXPECT_NE(error_of([&] { prepare(m); }).find("not a finite number"), std::string::npos);
  }
  // Degenerate: a repeated vertex, and three collinear ones.
  {
    Mesh m = make_shape("cube");
    m.triangles[4][1] = m.triangles[4][0];
    const std::string e = error_of([&] { validate(m); });
    EXPECT_NE(e.find("triangle 4 is degenerate"), std::string::npos) << e;
  }
  {
    Mesh m = raw_mesh("0 0 0 1 1 1 2 2 2\n");
    const std::string e = error_of([&] { prepare(m); });
    EXPECT_NE(e.find("collinear"), std::string::npos) << e;
  }
  // Empty.
  {
    Mesh m = raw_mesh("# nothing\n");
    EXPECT_NE(error_of([&] { prepare(m); }).find("no triangles"), std::string::npos);
  }
  // Open: one triangle missing.
  {
    Mesh m = make_shape("torus");
    m.triangles.erase(m.triangles.begin() + 100);
    const std::string e = error_of([&] { validate(m); });
    EXPECT_NE(e.find("open"), std::string::npos) << e;
    EXPECT_NE(e.find("edge"), std::string::npos) << e;
  }
  // Non-manifold: two tetrahedra sharing an edge (four triangles on it).
  {
    Mesh m;
    m.name = "bowtie";
    m.vertices = {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    m.triangles = {{0, 2, 3}, {1, 3, 2}, {0, 1, 2}, {0, 3, 1}, {0, 4, 5}, {1, 5, 4}, {0, 1, 4}, {0, 5, 1}};
    const std::string e = error_of([&] { validate(m); });
    EXPECT_NE(e.find("not manifold"), std::string::npos) << e;
  }
  // Inconsistent orientation: one triangle flipped.
  {
    Mesh m = make_shape("icosahedron");
    std::swap(m.triangles[7][1], m.triangles[7][2]);
    const std::string e = error_of([&] { validate(m); });
    EXPECT_NE(e.find("inconsistent orientation"), std::string::npos) << e;
  }
  // Files: missing, truncated OBJ (faces refer to vertices that never came), garbage.
  EXPECT_NE(error_of([] { load_mesh("/nonexistent/x.obj"); }).find("cannot open"), std::string::npos);
  {
    const std::string p = tmp_path("trunc.obj");
    test::write_file(p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4");
    EXPECT_NE(error_of([&] { load_mesh(p); }), "");
    test::write_file(p, "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
    EXPECT_NE(error_of([&] { load_mesh(p); }), "");
    std::remove(p.c_str());
  }
  {
    const std::string p = tmp_path("trunc.stl");
    test::write_stl(make_shape("cube"), p);
    std::string text;
    {
      std::ifstream in(p);
      std::stringstream ss;
      ss << in.rdbuf();
      text = ss.str();
    }
    test::write_file(p, text.substr(0, text.size() / 2));
    const std::string e = error_of([&] { load_mesh(p, nullptr, LoadOptions{true}); });
    EXPECT_NE(e, "");
    // Without --strict the triangles that arrived are kept, and the report says the surface is open.
    MeshReport r;
    const Mesh m = load_mesh(p, &r);
    EXPECT_LT(m.size(), 12u);
    EXPECT_GT(r.open_edges, 0u);
    EXPECT_FALSE(r.closed);
    std::remove(p.c_str());
  }
  // An inside-out mesh is reversed, not rejected.
  {
    Mesh m = make_shape("cube");
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    MeshReport r;
    validate(m, &r);
    EXPECT_TRUE(r.flipped);
    EXPECT_NEAR(m.volume(), 8.0, 1e-12);
  }
}

// Binary STL: 80-byte header, triangle count, 50 bytes per triangle.
void write_binary_stl(const Mesh& m, const std::string& path) {
  std::ofstream o(path, std::ios::binary);
  o << std::string(80, ' ');
  const uint32_t n = uint32_t(m.size());
  o.write(reinterpret_cast<const char*>(&n), 4);
  for (size_t t = 0; t < m.size(); ++t) {
    float f[12] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) f[3 + 3 * k + a] = float(m.corner(t, k)[a]);
    o.write(reinterpret_cast<const char*>(f), sizeof f);
    o.write("\0\0", 2);
  }
}

void write_format(const Mesh& m, const std::string& path, const std::string& fmt) {
  if (fmt == "obj") test::write_obj(m, path);
  if (fmt == "stl") test::write_stl(m, path);
  if (fmt == "bin.stl") write_binary_stl(m, path);
  if (fmt == "ply") test::write_ply(m, path);
  if (fmt == "raw") {
    std::ofstream o(path);
    write_raw(m, o);
  }
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Files cut short anywhere, in every format: strictly, a MeshError that names the file, or (cut in trailing
// whitespace) the whole mesh; repaired, the same error or the triangles that arrived, reported open when some are
// missing; never a crash (a crash fails the whole test program).
TEST(Mesh, TruncatedFilesAreErrors) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED)\n", (unsigned long long)seed);
  std::mt19937_64 rng(seed + 30);
  const Mesh src = make_shape("icosahedron");
  for (const std::string fmt : {"obj", "stl", "bin.stl", "ply", "raw"}) {
    const std::string p = tmp_path("trunc_all." + fmt);
    write_format(src, p, fmt);
    const std::string bytes = file_bytes(p);
    std::uniform_int_distribution<size_t> len(0, bytes.size() - 1);
    std::vector<size_t> lengths = {0, 1, bytes.size() / 2, bytes.size() - 1};
    for (int i = 0; i < 60; ++i) lengths.push_back(len(rng));
    int errors = 0;
    for (size_t n : lengths) {
      test::write_file(p, bytes.substr(0, n));
      try {
        const Mesh m = load_mesh(p, nullptr, LoadOptions{true});
        EXPECT_EQ(m.size(), src.size()) << fmt << " cut at " << n << " seed " << seed;
      } catch (const MeshError& e) {
        ++errors;
        EXPECT_EQ(std::string(e.what()).rfind(p + ":", 0), 0u) << e.what();  // "file: " or "file:line: "
      }
      try {
        MeshReport r;
        const Mesh m = load_mesh(p, &r);
        EXPECT_LE(m.size(), src.size()) << fmt << " cut at " << n;
        // (A cut inside the last number can also change a vertex or an index: the count stays, the surface opens.)
        // (An OBJ cut before its first face is a point cloud: its vertices alone.)
        if (m.size() == 0) {
          EXPECT_TRUE(r.points_only && !m.vertices.empty()) << fmt << " cut at " << n;
        } else if (m.size() < src.size()) {
          EXPECT_GT(r.open_edges, 0u) << fmt << " cut at " << n;
        }
      } catch (const MeshError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(p + ":", 0), 0u) << e.what();
      }
    }
    EXPECT_GE(errors, 50) << fmt;  // nearly every cut loses a triangle
    std::remove(p.c_str());
  }
}

// PLY counts are checked against the rest of the file before assimp sees them (it allocates and loops for them
// first): valid files of every encoding, with extra properties, comments and an empty element, load; counts the
// file cannot hold are refused with the element and the room there is, and so are header lines PLY does not have.
TEST(Mesh, PlyHeadersAndCountsAreCheckedAndValidFilesLoad) {
  const std::vector<std::array<float, 3>> V = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<std::array<int32_t, 3>> F = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                                                 {2, 3, 7}, {2, 7, 6}, {1, 2, 6}, {1, 6, 5}, {0, 4, 7}, {0, 7, 3}};
  auto put = [](std::string& out, const void* p, size_t n, bool big) {
    const char* c = static_cast<const char*>(p);
    for (size_t i = 0; i < n; ++i) out += c[big ? n - 1 - i : i];  // this machine is little-endian
  };
  // face_count: the list length written for the last face (3 for a valid file).
  auto ply = [&](const std::string& format, uint32_t face_count, const std::string& vertex_count = "8") {
    std::string s = "ply\nformat " + format + " 1.0\ncomment a cube\nelement vertex " + vertex_count +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                    "element face 12\nproperty list " + std::string(format == "ascii" ? "uchar" : "uint") +
                    " int vertex_indices\nelement edge 0\nproperty int a\nend_header\n";
    const bool ascii = format == "ascii", big = format == "binary_big_endian";
    for (const auto& v : V) {
      if (ascii) {
        s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + " 7\n";
      } else {
        for (float x : v) put(s, &x, 4, big);
        s += char(7);
      }
    }
    for (size_t k = 0; k < F.size(); ++k) {
      const uint32_t n = k + 1 == F.size() ? face_count : 3;
      if (ascii) {
        s += std::to_string(n) + " " + std::to_string(F[k][0]) + " " + std::to_string(F[k][1]) + " " +
             std::to_string(F[k][2]) + "\n";
      } else {
        put(s, &n, 4, big);
        for (int32_t i : F[k]) put(s, &i, 4, big);
      }
    }
    return s;
  };
  const std::string p = tmp_path("counts.ply");
  for (const std::string format : {"ascii", "binary_little_endian", "binary_big_endian"}) {
    test::write_file(p, ply(format, 3));
    EXPECT_EQ(load_mesh(p).size(), F.size()) << format;
    test::write_file(p, ply(format, 4000000000u));
    std::string e = error_of([&] { load_mesh(p); });
    EXPECT_NE(e.find(p + ": the PLY file declares 4000000000 list values in element 'face', more than the "),
              std::string::npos)
        << format << ": " << e;
    test::write_file(p, ply(format, 3, "123456789012"));
    e = error_of([&] { load_mesh(p); });
    EXPECT_NE(e.find(p + ": the PLY file declares 123456789012 items in element 'vertex'"), std::string::npos)
        << format << ": " << e;
  }
  // Header lines the format does not have are refused (assimp reads them loosely, then counts from the wrong bytes).
  const std::string good = ply("binary_little_endian", 3);
  for (const auto& [from, to, says] : std::vector<std::array<std::string, 3>>{
           {"format binary_little_endian", "format binary_littleA_endian", "line 2 of the PLY header"},
           {"property float y", "profloaperty float y", "not a PLY header line"},
           {"property float y", "property flaot y", "unknown property type 'flaot'"},
           {"element face 12", "element face", "an element needs a name and a count"}}) {
    std::string bad = good;
    bad.replace(bad.find(from), from.size(), to);
    test::write_file(p, bad);
    const std::string e = error_of([&] { load_mesh(p); });
    EXPECT_EQ(e.rfind(p + ": line ", 0), 0u) << to << ": " << e;
    EXPECT_NE(e.find(says), std::string::npos) << to << ": " << e;
  }
  std::remove(p.c_str());
}

// Bad meshes in files: the error names the file and the problem.
TEST(Mesh, BadMeshFilesNameTheFile) {
  auto load_error = [](const std::string& path, const std::string& text) {
    test::write_file(path, text);
    const std::string e = error_of([&] { load_mesh(path, nullptr, LoadOptions{true}); });
    std::remove(path.c_str());
    return e;
  };
  const std::string tet_v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  const std::string tet_f = "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  const std::string p = tmp_path("bad.obj");
  EXPECT_EQ(load_error(p, tet_v + tet_f), "");  // the good tetrahedron
  std::string e = load_error(p, "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\n" + tet_f);
  EXPECT_EQ(e.rfind(p + ": triangle 0 has a vertex that is not a finite number", 0), 0u) << e;
  e = load_error(p, "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 1\n" + tet_f);
  EXPECT_EQ(e.rfind(p + ": triangle 0 is degenerate", 0), 0u) << e;
  e = load_error(p, tet_v + "f 1 3 2\nf 1 2 4\nf 2 3 4\n");
  EXPECT_EQ(e.rfind(p + ": the mesh is open: edge", 0), 0u) << e;
  for (const char* ext : {".obj", ".stl", ".ply", ".raw", ".off"}) {
    const std::string q = tmp_path(std::string("empty") + ext);
    e = load_error(q, "");
    EXPECT_EQ(e.rfind(q + ": ", 0), 0u) << e;
  }
  const std::string r = tmp_path("comments.raw");
  e = load_error(r, "# no triangles\n");
  EXPECT_EQ(e, r + ": the mesh has no triangles");
  // A PLY that declares more faces than it holds.
  const std::string ply = tmp_path("short.ply");
  e = load_error(ply, "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                      "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n");
  EXPECT_EQ(e.rfind(ply + ": ", 0), 0u) << e;
  // Without --strict the same defects are repaired and reported; files that hold nothing still fail.
  auto repaired = [](const std::string& path, const std::string& text) {
    test::write_file(path, text);
    MeshReport rep;
    load_mesh(path, &rep);
    std::remove(path.c_str());
    return rep;
  };
  MeshReport rr = repaired(p, "v 0 0 0\nv 1 0 0\nv nan 1 0\nv 0 0 1\n" + tet_f);
  EXPECT_EQ(rr.dropped_nonfinite, 3u);  // vertex 3 is a corner of three faces
  EXPECT_EQ(rr.triangles, 1u);
  EXPECT_TRUE(rr.surface_only);  // one triangle encloses nothing
  rr = repaired(p, "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 0 1\n" + tet_f);
  EXPECT_EQ(rr.dropped_collinear, 1u);
  rr = repaired(p, tet_v + "f 1 3 2\nf 1 2 4\nf 2 3 4\n");
  EXPECT_EQ(rr.open_edges, 3u);
  EXPECT_FALSE(rr.closed);
  EXPECT_FALSE(rr.surface_only);  // the hole is 27% of the area left: below the 40% that makes a sheet
  rr = repaired(p, tet_v + tet_f);
  EXPECT_TRUE(rr.closed);
  EXPECT_FALSE(rr.repaired());
  test::write_file(r, "# no triangles\n");
  EXPECT_EQ(error_of([&] { load_mesh(r); }), r + ": the file holds no triangles and no points");
  std::remove(r.c_str());
}

}  // namespace
}  // namespace voxcd
