// Sparse voxmaps and shells against dense ones and against OpenVDB's bool grid (docs/voxelize.md, "Sparse voxmaps"):
// device bytes of the voxmap and the shell, sparse (table + bricks, shell words) and dense (2 bits a voxel of the box,
// three 24-bit coordinates a point), at several resolutions for the built-in shapes and the real models; and the
// bytes per surface voxel of the sparse voxmap and of an openvdb::BoolGrid holding the same three states. Every
// ratio comes from this one run. Writes markdown to stdout.
//
// bench_sparse_memory [--resolutions 128,256,512,1020] [--big 4096] [--big-models torus,env] MODEL...
// MODEL: a built-in shape's name, or NAME=PATH of a mesh file.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/sparse_shell.h"
#include "voxcd/host/object/voxelize_sparse.h"

namespace {

using namespace voxcd;

struct Model {
  std::string name;
  Mesh mesh;
};

struct Row {
  std::string model;
  uint32_t resolution = 0;
  std::array<uint32_t, 3> dims{};
  uint64_t surface = 0, points = 0;
  uint64_t dense_map = 0, dense_shell = 0, sparse_map = 0, sparse_shell = 0, vdb = 0;
  uint64_t bricks = 0, shell_words = 0, origin_words = 0;
  double seconds = 0;
  double ratio() const { return double(sparse_map + sparse_shell) / double(dense_map + dense_shell); }
  double map_per_surface() const { return double(sparse_map) / double(surface); }
  double vdb_per_surface() const { return double(vdb) / double(surface); }
};

// The same states in an openvdb::BoolGrid: a voxel is active unless empty, and its value is true for surface, false
// for interior. A uniform cell of voxcd (8^3, aligned as OpenVDB's leaves are) is a tile; a brick, a leaf. Pruned
// (identical siblings merged into larger tiles) before its memory is read.
uint64_t vdb_bytes(const SparseVoxmap& sm) {
  openvdb::BoolGrid::Ptr grid = openvdb::BoolGrid::create(false);
  auto& tree = grid->tree();
  const auto& c = sm.coarse();
  const uint32_t b = sm.edge();
  uint64_t t = 0;
  for (uint64_t cz = 0; cz < c[2]; ++cz)
    for (uint64_t cy = 0; cy < c[1]; ++cy)
      for (uint64_t cx = 0; cx < c[0]; ++cx, ++t) {
        const uint8_t code = sm.code(t);
        const openvdb::Coord at(int(cx * b), int(cy * b), int(cz * b));
        if (code == kSurface || code == kInterior) tree.addTile(1, at, code == kSurface, true);
        if (code != kCodeBrick) continue;
        auto* leaf = tree.touchLeaf(at);
        const uint64_t* w = sm.brick(sm.brick_index(t));
        for (uint32_t i = 0; i < b * b * b; ++i) {
          const uint32_t s = uint32_t((w[i >> 5] >> (2 * (i & 31))) & 3);
          if (s == kEmpty) continue;
          const openvdb::Coord v(at.x() + int(i % b), at.y() + int(i / b % b), at.z() + int(i / (b * b)));
          leaf->setValueOn(v, s == kSurface);
        }
      }
  openvdb::tools::prune(tree);
  return tree.memUsage();
}

Row measure(const Model& m, uint32_t resolution, bool with_vdb) {
  const auto t0 = std::chrono::steady_clock::now();
  VoxelizeOptions vo;
  vo.resolution = resolution;
  vo.max_dim = kMaxSparseDim;
  const SparseVoxmap sm = voxelize_sparse(m.mesh, vo);
  ShellOptions so;
  so.target_voxel = sm.grid().voxel;
  so.max_dim = kMaxSparseShellDim;
  const SparseShell sh = sparse_point_shell(m.mesh, so);
  Row r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.model = m.name;
  r.resolution = resolution;
  r.dims = sm.dims();
  r.surface = sm.counts()[kSurface];
  r.points = sh.size();
  const DeviceConfig cfg;
  r.dense_map = (sm.size() + 31) / 32 * 8;
  r.dense_shell = (r.points * 3 * uint64_t(cfg.PW) + 7) / 8;
  r.sparse_map = sm.bytes();
  r.sparse_shell = sh.bytes(cfg);
  r.bricks = sm.bricks();
  r.shell_words = sh.words();
  r.origin_words = sh.origin_words();
  if (with_vdb) r.vdb = vdb_bytes(sm);
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

std::string fmt(double v, const char* f = "%.3f") {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

void print_table(std::ostream& o, const std::vector<Row>& rows) {
  o << "| model | grid | surface voxels | shell points | dense voxmap + shell (bytes) | sparse voxmap + shell "
       "(bytes) | sparse / dense | bricks | shell words (origin) | voxmap bytes per surface voxel: sparse | "
       "OpenVDB bool grid | s |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows)
    o << "| " << r.model << " | " << r.dims[0] << "x" << r.dims[1] << "x" << r.dims[2] << " | " << r.surface << " | "
      << r.points << " | " << r.dense_map << " + " << r.dense_shell << " | " << r.sparse_map << " + "
      << r.sparse_shell << " | 1/" << fmt(1 / r.ratio(), "%.1f") << " | " << r.bricks << " | " << r.shell_words
      << " (" << r.origin_words << ") | " << fmt(r.map_per_surface(), "%.2f") << " | "
      << (r.vdb ? fmt(r.vdb_per_surface(), "%.2f") : std::string("-")) << " | " << fmt(r.seconds, "%.1f") << " |\n";
}

std::vector<Model> load_models(const std::vector<std::string>& args) {
  std::vector<Model> v;
  for (const std::string& a : args) {
    const size_t eq = a.find('=');
    Model m;
    m.name = eq == std::string::npos ? a : a.substr(0, eq);
    m.mesh = eq == std::string::npos ? make_shape(a) : load_mesh(a.substr(eq + 1));
    v.push_back(std::move(m));
  }
  return v;
}

std::vector<uint32_t> parse_list(const char* s) {
  std::vector<uint32_t> v;
  std::stringstream in(s);
  for (std::string x; std::getline(in, x, ',');) v.push_back(uint32_t(std::stoul(x)));
  return v;
}

// The contract's brick of 8^3 voxels (BL 3) against 4^3 and 16^3: the sparse voxmap's bytes (table + bricks) at each.
void brick_sizes(std::ostream& o, const std::vector<Model>& models, uint32_t res) {
  o << "\n### Brick size (" << res << " voxels across)\n\nSparse voxmap bytes, table + bricks, with bricks of 4^3, "
       "8^3 and 16^3 voxels (BL 2, 3, 4; the table has 16 cells a 64-bit word at each):\n\n"
       "| model | BL 2 | BL 3 | BL 4 |\n|---|---|---|---|\n";
  for (const Model& m : models) {
    VoxelizeOptions vo;
    vo.resolution = res;
    vo.max_dim = kMaxSparseDim;
    o << "| " << m.name;
    for (int bl : {2, 3, 4}) {
      const SparseVoxmap sm = voxelize_sparse(m.mesh, vo, nullptr, bl);
      o << " | " << sm.table_bytes() << " + " << sm.brick_bytes() << " = " << sm.bytes();
    }
    o << " |\n";
  }
}

// The goals of docs/voxelize.md's section, each stated met or not from this run's rows.
void goals(std::ostream& o, const std::vector<Row>& all, uint32_t at, uint32_t big) {
  std::vector<double> at_ratio;
  const Row* torus = nullptr;
  for (const Row& r : all)
    if (r.resolution == at) {
      at_ratio.push_back(r.ratio());
      if (r.model == "torus") torus = &r;
    }
  auto met = [](bool ok) { return ok ? "met" : "not met"; };
  o << "\nGoals:\n";
  if (torus && !at_ratio.empty())
    o << "- at " << at << " voxels across, voxmap + shell at most 1/10 of dense: the torus 1/"
      << fmt(1 / torus->ratio(), "%.1f") << " (" << met(torus->ratio() <= 0.1) << "), the median of the "
      << at_ratio.size() << " models 1/" << fmt(1 / median(at_ratio), "%.1f") << " (" << met(median(at_ratio) <= 0.1)
      << ");\n";
  for (const Row& r : all)
    if (r.resolution == big)
      o << "- at " << big << " voxels across, at most 1/30: " << r.model << " 1/" << fmt(1 / r.ratio(), "%.1f") << " ("
        << met(r.ratio() <= 1.0 / 30) << ");\n";
  size_t fewer = 0;
  double worst = 0;
  for (const Row& r : all) {
    fewer += r.map_per_surface() <= r.vdb_per_surface();
    worst = std::max(worst, r.map_per_surface() / r.vdb_per_surface());
  }
  o << "- no more voxmap bytes per surface voxel than OpenVDB's bool grid: " << fewer << " of " << all.size()
    << " rows (" << met(fewer == all.size()) << "; the largest ratio sparse / OpenVDB is " << fmt(worst, "%.2f")
    << ").\n";
}

}  // namespace

int main(int argc, char** argv) {
  openvdb::initialize();
  std::vector<uint32_t> resolutions = {128, 256, 512, 1020};
  uint32_t big = 4096;
  std::vector<std::string> args, big_models = {"torus"};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--resolutions") && i + 1 < argc) {
      resolutions = parse_list(argv[++i]);
    } else if (!std::strcmp(argv[i], "--big") && i + 1 < argc) {
      big = uint32_t(std::stoul(argv[++i]));
    } else if (!std::strcmp(argv[i], "--big-models") && i + 1 < argc) {
      std::stringstream in(argv[++i]);
      big_models.clear();
      for (std::string x; std::getline(in, x, ',');) big_models.push_back(x);
    } else {
      args.push_back(argv[i]);
    }
  }
  const std::vector<Model> models = load_models(args);
  std::ostringstream md;
  std::vector<Row> all;
  for (uint32_t res : resolutions) {
    std::vector<Row> rows;
    for (const Model& m : models) {
      rows.push_back(measure(m, res, true));
      std::fprintf(stderr, "%s at %u: %.1f s\n", m.name.c_str(), res, rows.back().seconds);
    }
    std::vector<double> ratio, ours, vdb;
    for (const Row& r : rows) {
      ratio.push_back(r.ratio());
      ours.push_back(r.map_per_surface());
      vdb.push_back(r.vdb_per_surface());
    }
    md << "\n### " << res << " voxels across\n\n";
    print_table(md, rows);
    md << "\nMedian over the " << rows.size() << " models: sparse / dense 1/" << fmt(1 / median(ratio), "%.1f")
       << "; voxmap bytes per surface voxel " << fmt(median(ours), "%.2f") << " sparse, " << fmt(median(vdb), "%.2f")
       << " OpenVDB.\n";
    all.insert(all.end(), rows.begin(), rows.end());
  }
  std::vector<Row> rows;
  for (const Model& m : models)
    if (std::find(big_models.begin(), big_models.end(), m.name) != big_models.end()) {
      rows.push_back(measure(m, big, true));
      std::fprintf(stderr, "%s at %u: %.1f s\n", m.name.c_str(), big, rows.back().seconds);
    }
  if (!rows.empty()) {
    md << "\n### " << big << " voxels across\n\n";
    print_table(md, rows);
  }
  all.insert(all.end(), rows.begin(), rows.end());
  std::vector<Model> brick_models;
  for (const Model& m : models)
    if (std::find(big_models.begin(), big_models.end(), m.name) != big_models.end()) brick_models.push_back(m);
  if (!resolutions.empty()) brick_sizes(md, brick_models, resolutions.back());
  brick_sizes(md, brick_models, big);
  goals(md, all, resolutions.empty() ? 0 : resolutions.back(), big);
  std::printf("%s", md.str().c_str());
  return 0;
}
