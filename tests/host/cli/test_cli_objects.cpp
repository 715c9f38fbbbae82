// `voxcd voxelize` and `voxcd info` as users run them: the numbers `info --json` prints are the library's, the
// picture is a PNG, and bad input exits non-zero with a message that names what and where.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/ref/config.h"
#include "tests/host/test_util.h"

#ifndef VOXCD_BIN
#error "VOXCD_BIN: path of the voxcd tool"
#endif

namespace voxcd {
namespace {

struct CliRun {
  int rc = -1;
  std::string out;  // stdout and stderr
};

CliRun run(const std::string& args) {
  CliRun r;
  const std::string cmd = std::string(VOXCD_BIN) + " " + args + " 2>&1";
  FILE* f = popen(cmd.c_str(), "r");
  if (!f) return r;
  char buf[4096];
  for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) r.out.append(buf, n);
  const int st = pclose(f);
  r.rc = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

// The number after "key": in flat JSON text (ADD_FAILURE and NaN when missing).
double json_number(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9.eE+-]+)"))) {
    ADD_FAILURE() << "no key " << key << " in\n" << json;
    return std::nan("");
  }
  return std::stod(m[1]);
}
std::array<double, 3> json_triple(const std::string& json, const std::string& key) {
  std::smatch m;
  const std::string n = "(-?[0-9.eE+-]+)";
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": \\[" + n + ", " + n + ", " + n + "\\]"))) {
    ADD_FAILURE() << "no key " << key << " in\n" << json;
    return {};
  }
  return {std::stod(m[1]), std::stod(m[2]), std::stod(m[3])};
}

// Every number `info --json` prints, against the object the library makes from the same input (with the tool's
// default storage, auto: each of the voxmap and the shell in whichever form is smaller).
void expect_matches(const std::string& json, const ObjectFile& obj) {
  const auto c = obj.voxmap_counts();
  const GridPlacement& g = obj.voxmap_grid();
  const auto d = json_triple(json, "dims");
  for (int a = 0; a < 3; ++a) EXPECT_EQ(d[a], g.dims[a]);
  EXPECT_EQ(json_number(json, "voxel_size"), g.voxel);
  const auto o = json_triple(json, "origin");
  for (int a = 0; a < 3; ++a) EXPECT_EQ(o[a], g.origin[a]);
  EXPECT_EQ(json_number(json, "empty"), c[kEmpty]);
  EXPECT_EQ(json_number(json, "surface"), c[kSurface]);
  EXPECT_EQ(json_number(json, "interior"), c[kInterior]);
  EXPECT_EQ(json_number(json, "voxels"), g.size());
  EXPECT_EQ(json_number(json, "shell_points"), obj.shell_count());
  EXPECT_EQ(json_number(json, "shell_spacing"), obj.shell_grid().voxel);
  // Default device widths: MEMW-bit voxmap words, three PW-bit coordinates per shell point; or the sparse forms'
  // table and bricks, and shell words.
  const DeviceConfig cfg;
  const double dense_v = std::ceil(double(g.size()) / 32) * 8;
  const double dense_s = std::ceil(double(obj.shell_count()) * 3 * cfg.PW / 8);
  const double vbytes = obj.voxmap_sparse() ? double(obj.sparse_voxmap.bytes()) : dense_v;
  const double sbytes = obj.shell_sparse() ? double(obj.sparse_shell.words() * 9) : dense_s;
  EXPECT_EQ(json_number(json, "voxmap_bytes"), vbytes);
  EXPECT_EQ(json_number(json, "shell_bytes"), sbytes);
  EXPECT_EQ(json_number(json, "memory_bytes"), vbytes + sbytes);
  EXPECT_NE(json.find(std::string("\"voxmap\": \"") + (obj.voxmap_sparse() ? "sparse" : "dense")), std::string::npos);
  EXPECT_NE(json.find("\"dense\": {\"voxmap_bytes\": " + std::to_string(uint64_t(dense_v)) + ", \"shell_bytes\": " +
                      std::to_string(uint64_t(dense_s))),
            std::string::npos)
      << json;
}

// The library's object as voxcd voxelize makes it by default.
ObjectFile tool_object(const Mesh& m, const std::string& source, uint64_t hash, ObjectOptions opt) {
  set_storage(opt, ObjectStorage::kAuto);
  return make_object(m, source, hash, opt);
}

TEST(Cli, VoxelizeShapeThenInfo) {
  const std::string vox = test::tmp_path("cli_torus.vox"), png = test::tmp_path("cli_torus.png");
  const CliRun v = run("voxelize torus --voxel 0.07 -o " + vox + " --png " + png);
  ASSERT_EQ(v.rc, 0) << v.out;
  EXPECT_NE(v.out.find("object of shape:torus"), std::string::npos) << v.out;
  const CliRun i = run("info " + vox + " --json");
  ASSERT_EQ(i.rc, 0) << i.out;
  ObjectOptions opt;
  opt.voxel = 0.07;
  const ObjectFile lib = tool_object(make_shape("torus"), "shape:torus", hash_bytes("shape:torus"), opt);
  expect_matches(i.out, lib);
  EXPECT_NE(i.out.find("\"source\": \"shape:torus\""), std::string::npos) << i.out;
  // The file holds exactly the library's object (the shell sparse here), and the dense object's states and points.
  ASSERT_TRUE(lib.shell_sparse());
  const ObjectFile back = read_object(vox);
  EXPECT_EQ(back.voxmap_sparse(), lib.voxmap_sparse());
  EXPECT_TRUE(back.sparse_voxmap == lib.sparse_voxmap);
  EXPECT_EQ(back.sparse_shell.bricks, lib.sparse_shell.bricks);
  EXPECT_EQ(back.sparse_shell.normals, lib.sparse_shell.normals);
  const ObjectFile dense = make_object(make_shape("torus"), "shape:torus", hash_bytes("shape:torus"), opt);
  EXPECT_EQ(back.voxmap.words(), dense.voxmap.words());
  EXPECT_EQ(back.shell.cells, dense.shell.cells);
  // The text form says the same numbers.
  const CliRun t = run("info " + vox);
  ASSERT_EQ(t.rc, 0) << t.out;
  const auto c = lib.voxmap_counts();
  EXPECT_NE(t.out.find("empty " + std::to_string(c[kEmpty]) + ", surface " + std::to_string(c[kSurface]) +
                       ", interior " + std::to_string(c[kInterior])),
            std::string::npos)
      << t.out;
  // The picture: a PNG whose width and height hold three slices and the shell view.
  std::ifstream in(png, std::ios::binary);
  std::string head(24, '\0');
  in.read(&head[0], 24);
  ASSERT_TRUE(in) << png;
  EXPECT_EQ(head.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(head.substr(12, 4), "IHDR");
  const auto be32 = [&](size_t at) {
    return uint32_t(uint8_t(head[at])) << 24 | uint32_t(uint8_t(head[at + 1])) << 16 |
           uint32_t(uint8_t(head[at + 2])) << 8 | uint32_t(uint8_t(head[at + 3]));
  };
  EXPECT_GE(be32(16), 3 * dense.voxmap.dims()[0]);
  EXPECT_GE(be32(20), dense.voxmap.dims()[1]);
  // info --png draws from the object file alone (the shape is regenerated for the mesh).
  const std::string png2 = test::tmp_path("cli_torus_info.png");
  EXPECT_EQ(run("info " + vox + " --png " + png2).rc, 0);
  EXPECT_TRUE(std::ifstream(png2).good());
  for (const auto& p : {vox, png, png2}) std::remove(p.c_str());
}

TEST(Cli, VoxelizeMeshFileThenInfo) {
  const std::string mesh = test::tmp_path("cli_stellated.stl"), vox = test::tmp_path("cli_stellated.vox");
  test::write_stl(make_shape("stellated"), mesh);
  const CliRun v = run("voxelize " + mesh + " --voxel 0.05 --shell-ratio 2 -o " + vox);
  ASSERT_EQ(v.rc, 0) << v.out;
  const CliRun i = run("info --json " + vox);
  ASSERT_EQ(i.rc, 0) << i.out;
  std::string source;
  uint64_t hash = 0;
  const Mesh m = load_source(mesh, &source, &hash);
  ObjectOptions opt;
  opt.voxel = 0.05;
  opt.shell_ratio = 2;
  expect_matches(i.out, tool_object(m, source, hash, opt));
  EXPECT_EQ(json_number(i.out, "shell_ratio"), 2.0);
  char hex[20];
  std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)hash_file(mesh));
  EXPECT_NE(i.out.find(std::string("\"source_hash\": \"") + hex + "\""), std::string::npos) << i.out;
  std::remove(mesh.c_str());
  std::remove(vox.c_str());
}

std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// --storage: dense is the file the library wrote before sparse objects existed (version 2), sparse holds the same
// states and points, auto picks per part, and a grid larger than a dense voxmap takes is sparse.
TEST(Cli, StorageDenseSparseAndAuto) {
  const std::string d = test::tmp_path("cli_dense.vox"), sp = test::tmp_path("cli_sparse.vox"),
                    lib = test::tmp_path("cli_lib.vox"), big = test::tmp_path("cli_big.vox"),
                    png = test::tmp_path("cli_big.png");
  ASSERT_EQ(run("voxelize torus --voxel 0.07 --storage dense -o " + d).rc, 0);
  ObjectOptions opt;
  opt.voxel = 0.07;
  std::string src;
  uint64_t hash = 0;
  MeshReport report;
  const Mesh torus = load_source("torus", &src, &hash, &report);
  const ObjectFile dense = make_object(torus, src, hash, opt, &report);
  write_object(lib, dense);
  EXPECT_TRUE(file_bytes(d) == file_bytes(lib)) << "--storage dense is the library's dense object file";
  EXPECT_EQ(uint8_t(file_bytes(d)[8]), 2u) << "version 2";
  const CliRun s = run("voxelize torus --voxel 0.07 --storage sparse --json -o " + sp);
  ASSERT_EQ(s.rc, 0) << s.out;
  EXPECT_NE(s.out.find("\"voxmap\": \"sparse\", \"shell\": \"sparse\""), std::string::npos) << s.out;
  EXPECT_EQ(uint8_t(file_bytes(sp)[8]), 5u) << "version 5";
  const ObjectFile back = read_object(sp);
  EXPECT_EQ(back.voxmap.words(), dense.voxmap.words());
  EXPECT_EQ(back.shell.cells, dense.shell.cells);
  double worst = 0;
  for (size_t k = 0; k < dense.shell.size(); ++k)
    worst = std::max(worst, std::acos(std::min(1.0, back.shell.normals[k].dot(dense.shell.normals[k]))));
  EXPECT_LT(worst, 1e-4) << "the normals' encoding";
  // A tiny object: its dense voxmap is smaller than a table and one brick.
  const CliRun a = run("voxelize cube --voxel 0.5 --json -o " + sp);
  ASSERT_EQ(a.rc, 0) << a.out;
  EXPECT_NE(a.out.find("\"voxmap\": \"dense\""), std::string::npos) << a.out;
  // A dense voxmap has at most 1024 voxels per axis; an unknown storage names the option.
  CliRun r = run("voxelize cube --voxel 0.001 --storage dense -o " + sp);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("at most 1024 per axis"), std::string::npos) << r.out;
  r = run("voxelize cube --voxel 0.1 --storage thin -o " + sp);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("--storage"), std::string::npos) << r.out;
  // A sparse distance field: refined bricks, read back the same.
  const CliRun e = run("voxelize torus --voxel 0.07 --storage sparse --distance-bits 8 -o " + sp);
  ASSERT_EQ(e.rc, 0) << e.out;
  EXPECT_NE(e.out.find("stored sparse: 6 x 6 x 2 cells of 8^3"), std::string::npos) << e.out;
  const ObjectFile with_field = read_object(sp);
  EXPECT_TRUE(with_field.distance_sparse());
  EXPECT_TRUE(with_field.distance.empty());
  EXPECT_EQ(with_field.distance_bits(), 8);
  // 1,100 voxels across: more than a dense voxmap takes, so sparse; a picture needs the dense one.
  const CliRun b = run("voxelize torus --resolution 1100 -o " + big);
  ASSERT_EQ(b.rc, 0) << b.out;
  EXPECT_NE(b.out.find("voxmap   1103 x 1103 x"), std::string::npos) << b.out;
  EXPECT_NE(b.out.find("storage  voxmap stored sparse"), std::string::npos) << b.out;
  const ObjectFile stored = read_object(big, ObjectRead::kStored);
  EXPECT_TRUE(stored.voxmap_sparse() && !stored.has_dense_voxmap());
  const CliRun p = run("info " + big + " --png " + png);
  EXPECT_NE(p.rc, 0);
  EXPECT_NE(p.out.find("no picture of an object stored sparse at 1103 x 1103"), std::string::npos) << p.out;
  for (const auto& f : {d, sp, lib, big, png}) std::remove(f.c_str());
}

TEST(Cli, ErrorsNameWhatAndWhere) {
  const std::string vox = test::tmp_path("cli_err.vox");
  // Unknown shape, missing file.
  CliRun r = run("voxelize teapot --voxel 0.1 -o " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("teapot: no such file, and not a built-in shape"), std::string::npos) << r.out;
  // An open mesh file: the file and the open edge.
  const std::string open = test::tmp_path("cli_open.obj");
  Mesh m = make_shape("cube");
  m.triangles.pop_back();
  test::write_obj(m, open);
  r = run("voxelize " + open + " --voxel 0.1 --strict -o " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find(open + ": the mesh is open: edge"), std::string::npos) << r.out;
  EXPECT_FALSE(std::ifstream(vox).good()) << "no object file after an error";
  // Without --strict it is repaired and voxelised, and the report says what was open.
  r = run("voxelize " + open + " --voxel 0.1 -o " + vox + " --json");
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("\"closed\": false"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"open_edges\": 3"), std::string::npos) << r.out;
  std::remove(vox.c_str());
  // Neither --voxel nor --resolution, both, and a resolution below 4.
  r = run("voxelize cube -o " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("--voxel or --resolution"), std::string::npos) << r.out;
  r = run("voxelize cube --voxel 0.1 --resolution 64 -o " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("excludes"), std::string::npos) << r.out;
  r = run("voxelize cube --resolution 3 -o " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("at least 4 voxels must span the longest side"), std::string::npos) << r.out;
  r = run("voxelize cube --voxel 0.6 -o " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("use a voxel size of at most 0.5"), std::string::npos) << r.out;
  EXPECT_FALSE(std::ifstream(vox).good()) << "no object file after an error";
  // Bad voxel sizes, a grid too large.
  for (const char* bad : {"0", "-1", "nan", "abc"}) {
    r = run(std::string("voxelize cube --voxel ") + bad + " -o " + vox);
    EXPECT_NE(r.rc, 0) << bad;
    EXPECT_NE(r.out.find("--voxel"), std::string::npos) << r.out;
  }
  r = run("voxelize cube --voxel 0.0001 -o " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("at most 4100 per axis"), std::string::npos) << r.out;
  EXPECT_FALSE(std::ifstream(vox).good()) << "no object file after an error";
  // info on a missing, a truncated and a non-object file.
  r = run("info /nonexistent/x.vox");
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find("/nonexistent/x.vox: cannot open"), std::string::npos) << r.out;
  ASSERT_EQ(run("voxelize cube --voxel 0.5 -o " + vox).rc, 0);
  std::string bytes;
  {
    std::ifstream in(vox, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    bytes = s.str();
  }
  test::write_file(vox, bytes.substr(0, 100));
  r = run("info " + vox);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find(vox + ": truncated at byte "), std::string::npos) << r.out;
  r = run("info " + open);
  EXPECT_NE(r.rc, 0);
  EXPECT_NE(r.out.find(open + ": not a voxcd object file (bad magic) (byte 0)"), std::string::npos) << r.out;
  std::remove(open.c_str());
  std::remove(vox.c_str());
}

// A triangle with a NaN corner is dropped and counted, also when what is left is a point cloud of the other corners.
TEST(Cli, NonFiniteCornerIsCountedInEveryReport) {
  const std::string obj = test::tmp_path("nan_corner.obj"), vox = test::tmp_path("nan_corner.vxo");
  test::write_file(obj, "v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n");
  MeshReport rep;
  const Mesh m = load_mesh(obj, &rep);
  EXPECT_EQ(rep.dropped_nonfinite, 1u);
  EXPECT_TRUE(rep.points_only);
  EXPECT_EQ(m.vertices.size(), 2u);
  CliRun r = run("voxelize " + obj + " --voxel 0.1 -o " + vox);
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("dropped 1 non-finite"), std::string::npos) << r.out;
  r = run("info " + vox + " --json");
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("\"nonfinite\": 1"), std::string::npos) << r.out;
  std::remove(obj.c_str());
  std::remove(vox.c_str());
}

// Two boxes sharing a face: the report says how many non-manifold edges and parts repair found and what it did,
// and the object file keeps it (version 4).
TEST(Cli, NonManifoldPartsAreReported) {
  const std::string raw = test::tmp_path("face_sharing.raw"), vox = test::tmp_path("face_sharing.vxo");
  std::ostringstream text;
  for (const Eigen::Vector3d& lo : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)}) {
    const Mesh b = make_box(lo, lo + Eigen::Vector3d::Ones());
    for (size_t t = 0; t < b.size(); ++t) {
      for (int k = 0; k < 3; ++k) text << b.corner(t, k).x() << " " << b.corner(t, k).y() << " " << b.corner(t, k).z() << " ";
      text << "\n";
    }
  }
  test::write_file(raw, text.str());
  CliRun r = run("voxelize " + raw + " --resolution 32 --distance-bits 8 -o " + vox);
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_NE(r.out.find("nonmanifold 4 edges of three triangles or more in 1 parts"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("dropped 2 internal triangles"), std::string::npos) << r.out;
  r = run("info " + vox + " --json");
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(json_number(r.out, "nonmanifold_parts"), 1);
  EXPECT_EQ(json_number(r.out, "internal"), 2);
  EXPECT_GT(json_number(r.out, "interior"), 0);
  const ObjectFile o = read_object(vox);
  EXPECT_EQ(o.mesh_report.dropped_internal, 2u);
  EXPECT_EQ(o.voxelize_report.conservative, json_number(r.out, "conservative_cells"));
  std::remove(raw.c_str());
  std::remove(vox.c_str());
}

// voxcd pair --json prints the voxel the objects were built at, also when they come from object files.
TEST(Cli, PairJsonGivesTheObjectFilesVoxel) {
  const std::string a = test::tmp_path("pair_a.vxo"), b = test::tmp_path("pair_b.vxo");
  ASSERT_EQ(run("voxelize torus --voxel 0.07 -o " + a).rc, 0);
  ASSERT_EQ(run("voxelize cube --voxel 0.07 -o " + b).rc, 0);
  CliRun r = run("pair " + a + " " + b + " --json");
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(json_number(r.out, "voxel"), read_object(a).voxmap.voxel()) << r.out;
  ASSERT_EQ(run("voxelize cube --voxel 0.09 -o " + b).rc, 0);
  r = run("pair " + a + " " + b + " --json");
  ASSERT_EQ(r.rc, 0) << r.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("\"voxel\": \\[([0-9.eE+-]+), ([0-9.eE+-]+)\\]"))) << r.out;
  EXPECT_EQ(std::stod(m[1]), read_object(a).voxmap.voxel());
  EXPECT_EQ(std::stod(m[2]), read_object(b).voxmap.voxel());
  std::remove(a.c_str());
  std::remove(b.c_str());
}

// voxcd pair --storage sparse: shapes stored sparse run on a sparse device (BL 3) and find the hits of their dense
// forms, on ref and cpu with the same cycles; sparse object files need no option; a bad storage is refused.
TEST(Cli, PairOfSparseObjects) {
  const std::string args = "pair torus polytope36 --voxel 0.08 --random 12 --both --json";
  const CliRun dense = run(args), sparse = run(args + " --storage sparse"), ref = run(args + " --storage sparse --backend ref");
  ASSERT_EQ(dense.rc, 0) << dense.out;
  ASSERT_EQ(sparse.rc, 0) << sparse.out;
  ASSERT_EQ(ref.rc, 0) << ref.out;
  EXPECT_EQ(json_number(dense.out, "bl"), 0);
  EXPECT_EQ(json_number(sparse.out, "bl"), 3);
  EXPECT_GT(json_number(dense.out, "hits"), 0);
  EXPECT_EQ(json_number(sparse.out, "hits"), json_number(dense.out, "hits"));
  EXPECT_EQ(json_number(sparse.out, "device_cycles"), json_number(ref.out, "device_cycles"));
  const std::string a = test::tmp_path("pair_sparse.vxo");
  ASSERT_EQ(run("voxelize torus --voxel 0.08 --storage sparse -o " + a).rc, 0);
  const CliRun file = run("pair " + a + " polytope36 --voxel 0.08 --random 12 --both --json");
  ASSERT_EQ(file.rc, 0) << file.out;
  EXPECT_EQ(json_number(file.out, "bl"), 3);
  const CliRun bad = run(args + " --storage sparce");
  EXPECT_NE(bad.rc, 0);
  EXPECT_NE(bad.out.find("--storage"), std::string::npos) << bad.out;
  std::remove(a.c_str());
}

// simulate --json prints its summary as it always did: keys in their order, on one line, every floating-point
// number with at most 6 significant digits as a C++ stream prints it, the state hash in hex.
TEST(Cli, SimulateJsonNumbersAsAStreamPrintsThem) {
  const CliRun r = run("simulate --frames 5 --json --distance-bits 8");
  ASSERT_EQ(r.rc, 0) << r.out;
  EXPECT_EQ(r.out.rfind("{\"device\": \"PW ", 0), 0u) << r.out;
  EXPECT_NE(r.out.find("\"voxel\": 1, \"shell_count\": 827, \"shell_points\": 827, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"distance_bits\": 8, \"band\": 4, \"margin\": 0, \"ccd\": false, \"frames\": 5, "),
            std::string::npos)
      << r.out;
  EXPECT_TRUE(std::regex_search(r.out, std::regex("\"state_hash\": \"[0-9a-f]+\"\\}\n$"))) << r.out;
  const std::regex number(": (-?[0-9]+(\\.[0-9]+)?(e[-+][0-9]+)?)[,}]");
  int checked = 0;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), number); it != std::sregex_iterator(); ++it) {
    const std::string n = (*it)[1];
    std::ostringstream again;
    again.precision(6);
    again << std::stod(n);
    if (n.find_first_of(".e") != std::string::npos) {
      EXPECT_EQ(n, again.str()) << "not as a stream prints it at 6 digits";
      ++checked;
    }
  }
  EXPECT_GT(checked, 5) << r.out;
}

}  // namespace
}  // namespace voxcd
