// Sparse distance fields at scale (host/object/sparse_field.h): built shapes at voxel resolutions up to 4,096 voxels
// across, brick by brick. Per shape and resolution: the grid, the build's wall time and peak memory, uniform cells,
// bricks per level, conservative sub-cells, the field's host bytes and the sparse device's bytes (table and bricks,
// BL 3, SB 8) beside a dense distance map's (docs/contract.md). The grid is placed without voxelising (a dense
// voxmap of 4,096^3 voxels would take 16 GiB). Writes Markdown to stdout (and to --out FILE).
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "bench/bench_common.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/sparse_field.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

using namespace voxcd;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

double peak_mib() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_maxrss) / 1024;
}

// The sparse device's words for a field (its table and its bricks), and a dense distance map's for the same grid.
uint64_t sparse_words(const DeviceConfig& cfg, const SparseDistanceField& f) {
  return (f.codes().size() + table_cells_per_word(cfg) - 1) / table_cells_per_word(cfg) +
         table_units(cfg, f.codes()) * unit_words(cfg);
}
uint64_t dense_words(const DeviceConfig& cfg, const std::array<uint32_t, 3>& dims) {
  Job j;
  j.nx = dims[0];
  j.ny = dims[1];
  j.nz = dims[2];
  DeviceConfig dense = cfg;
  dense.BL = 0;
  return map_words(dense, j);
}

std::string row(const std::string& shape, uint32_t resolution, unsigned threads) {
  Mesh m = make_shape(shape);
  repair(m);
  VoxelizeOptions vo;
  vo.voxel = voxel_for_resolution(m, resolution);
  vo.max_dim = 1u << 16;
  const GridPlacement g = place_grid(m, vo);
  SparseFieldOptions so;
  so.distance.bits = 8;
  so.distance.threads = threads;
  const auto t0 = std::chrono::steady_clock::now();
  const SparseDistanceField f = sparse_distance_field(m, g, so);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const SparseFieldCounts c = f.counts();
  DeviceConfig cfg;
  cfg.SB = 8;
  cfg.BL = 3;
  const double sparse_mib = double(8 * sparse_words(cfg, f)) / (1 << 20);
  const double dense_mib = double(8 * dense_words(cfg, g.dims)) / (1 << 20);
  std::fprintf(stderr, "%s %u: %.1f s\n", shape.c_str(), resolution, secs);
  return "| " + shape + " | " + std::to_string(resolution) + " | " + std::to_string(g.dims[0]) + "x" +
         std::to_string(g.dims[1]) + "x" + std::to_string(g.dims[2]) + " | " + bench::fmt("%.1f", secs) + " | " +
         bench::fmt("%.0f", peak_mib()) + " | " + std::to_string(c.far + c.deep) + " | " + std::to_string(c.bricks[0]) +
         " / " + std::to_string(c.bricks[1]) + " / " + std::to_string(c.bricks[2]) + " / " +
         std::to_string(c.bricks[3]) + " | " + std::to_string(c.conservative) + " | " +
         bench::fmt("%.1f", double(f.bytes()) / (1 << 20)) + " | " + bench::fmt("%.1f", sparse_mib) + " | " +
         bench::fmt("%.1f", dense_mib) + " | " + bench::fmt("%.1f", dense_mib / sparse_mib) + " |\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path;
  std::vector<std::string> shapes = {"torus", "cube"};
  std::vector<std::string> resolutions = {"64", "256", "1020"};
  unsigned threads = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--shapes") && i + 1 < argc) shapes = split(argv[++i]);
    else if (!std::strcmp(argv[i], "--resolutions") && i + 1 < argc) resolutions = split(argv[++i]);
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = unsigned(std::atoi(argv[++i]));
    else {
      std::fprintf(stderr,
                   "usage: bench_sparse_field [--shapes a,b] [--resolutions 64,256,1020,4096] [--threads N] "
                   "[--out FILE]\n");
      return 2;
    }
  }
  std::ostringstream md;
  md << bench::provenance(argc, argv) << "\n\n"
     << "Sparse distance fields (SB 8, band 4 voxels, bricks refined up to level 3), built brick by brick on "
     << (threads ? std::to_string(threads) + (threads == 1 ? " thread" : " threads")
                 : std::string("every hardware thread"))
     << "; peak memory is the process's peak so far (the rows run in order). Device bytes: the sparse device's table "
        "and bricks (BL 3, MEMW 64) and a dense distance map of the same grid.\n\n"
     << "| shape | voxels across | grid | seconds | peak MiB | uniform cells | bricks at level 0 / 1 / 2 / 3 | "
        "conservative sub-cells | host MiB | sparse device MiB | dense device MiB | dense / sparse |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const std::string& s : shapes)
    for (const std::string& r : resolutions) md << row(s, uint32_t(std::stoul(r)), threads);
  md << "\nMachine: " << bench::machine_description() << ".\n";
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  return 0;
}
