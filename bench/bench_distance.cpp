// Distance fields and shells on the surface: the time to build the signed distance field of a mesh (SB 8, band
// +-4 voxels) on every hardware thread and on one (the two fields are checked to be identical), against triangle
// count and resolution, beside the voxmap and both kinds of shell. Writes a markdown table to stdout (docs/objects.md,
// "Distance fields").
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "voxcd/host/object/distance_field.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"

using namespace voxcd;

namespace {

struct Case {
  std::string name;
  Mesh mesh;
  uint32_t resolution;
};

std::string fixed(double v, int digits = 3) {
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 3;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: bench_distance [--repeats N]\n");
      return 2;
    }
  }
  std::vector<Case> cases;
  Mesh torus = make_torus(1.0, 0.35, 320, 160);
  prepare(torus);
  Mesh ico6 = make_icosphere(Eigen::Vector3d::Zero(), 1.0, 6), ico7 = make_icosphere(Eigen::Vector3d::Zero(), 1.0, 7);
  prepare(ico6);
  prepare(ico7);
  for (uint32_t r : {64u, 128u, 256u}) cases.push_back({"torus 320 x 160", torus, r});
  cases.push_back({"icosphere level 6", ico6, 128});
  cases.push_back({"icosphere level 7", ico7, 128});

  std::ostringstream md;
  md << bench::provenance(argc, argv) << " Medians of " << repeats
     << " runs, in seconds. *field* is `distance_field` (SB 8, band +-4 voxels) on every hardware thread and on one "
        "(checked identical); *surface shell* is the shell on the surface (`surface_shell`), *centre shell* the "
        "2-bit objects' shell of voxel centres, both for target voxels of the voxmap's size.\n\n"
     << "| mesh | triangles | voxmap | nodes | voxelize | field (all threads) | field (1 thread) | surface shell "
        "| centre shell | surface points | centre points |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Case& c : cases) {
    VoxelizeOptions vo;
    vo.resolution = c.resolution;
    Voxmap vm;
    const double t_vox = bench::median_time(repeats, [&] { vm = voxelize(c.mesh, vo); });
    DistanceOptions d;
    d.bits = 8;
    d.band = 4;
    DistanceField all, one;
    const double t_all = bench::median_time(repeats, [&] { all = distance_field(c.mesh, vm, d); });
    d.threads = 1;
    const double t_one = bench::median_time(repeats, [&] { one = distance_field(c.mesh, vm, d); });
    if (all.q != one.q) {
      std::fprintf(stderr, "bench_distance: %s: one thread and all threads disagree\n", c.name.c_str());
      return 1;
    }
    ShellOptions so;
    so.target_voxel = vm.voxel();
    PointShell centre, surface;
    const double t_centre = bench::median_time(repeats, [&] { centre = point_shell(c.mesh, so); });
    so.on_surface = true;
    const double t_surface = bench::median_time(repeats, [&] { surface = point_shell(c.mesh, so); });
    const auto& dm = vm.dims();
    md << "| " << c.name << " | " << c.mesh.size() << " | " << dm[0] << "x" << dm[1] << "x" << dm[2] << " | "
       << all.q.size() << " | " << fixed(t_vox) << " | " << fixed(t_all) << " | " << fixed(t_one) << " | "
       << fixed(t_surface) << " | " << fixed(t_centre) << " | " << surface.size() << " | " << centre.size()
       << " |\n";
    std::cerr << c.name << " at " << c.resolution << " done\n";
  }
  std::cout << md.str();
  return 0;
}
