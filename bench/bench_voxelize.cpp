// Object preparation speed and size: mesh preparation (weld + validate), voxelisation and point-shell time
// against triangle count and resolution (medians of repeated runs, on every core and on one), voxmap and shell
// sizes against voxel size for the built-in shapes, and defective meshes (tests/defects.h): the winding-number
// voxeliser against the ray-casting one and OpenVDB, in time and in voxels that differ from the intended solid.
// Writes markdown to stdout (and to --out FILE).
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "bench/bench_common.h"
#include "voxcd/host/object/point_shell.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/ref/config.h"
#include "tests/defects.h"

using namespace voxcd;

namespace {

struct Timing {
  double prepare = 0, vox_all = 0, vox_one = 0, shell_all = 0;
  std::array<uint32_t, 3> dims{};
  uint64_t surface = 0, interior = 0, shell_points = 0;
};

// Voxel size that makes the longest axis of `m` span `res` voxels (with the two padding voxels).
double voxel_for(const Mesh& m, int res) {
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  return (hi - lo).maxCoeff() / (res - 3);
}

Timing measure(const Mesh& src, int res, int repeats, bool with_shell) {
  Timing t;
  Mesh m;
  t.prepare = bench::median_time(repeats, [&] {
    m = src;
    prepare(m);
  });
  VoxelizeOptions o;
  o.voxel = voxel_for(m, res);
  o.max_dim = 4096;
  Voxmap vm;
  t.vox_all = bench::median_time(repeats, [&] { vm = voxelize(m, o); });
  o.threads = 1;
  Voxmap v1;
  t.vox_one = bench::median_time(repeats, [&] { v1 = voxelize(m, o); });
  if (v1.words() != vm.words()) {
    std::fprintf(stderr, "one thread and all threads disagree\n");
    std::exit(1);
  }
  t.dims = vm.dims();
  const auto c = vm.counts();
  t.surface = c[kSurface];
  t.interior = c[kInterior];
  if (with_shell) {
    ShellOptions so;
    so.target_voxel = o.voxel;
    PointShell s;
    t.shell_all = bench::median_time(repeats, [&] { s = point_shell(m, so); });
    t.shell_points = s.size();
  }
  return t;
}

// ---------------------------------------------------------------------------------------------------------------
// Defective meshes.

// Inside/outside at every voxel centre of `g` from OpenVDB's narrow-band level set of the mesh (meshToLevelSet,
// half width 3 voxels; its sign flood fill classifies the rest): index (i, j, k) of the level set is our voxel
// (i, j, k)'s centre. Returns the conversion's median time; `inside` gets one byte per voxel.
double openvdb_inside(const Mesh& m, const GridPlacement& g, int repeats, std::vector<uint8_t>& inside) {
  std::vector<openvdb::Vec3s> points;
  points.reserve(m.vertices.size());
  for (const auto& v : m.vertices) points.emplace_back(float(v.x()), float(v.y()), float(v.z()));
  std::vector<openvdb::Vec3I> tris;
  tris.reserve(m.size());
  for (const auto& t : m.triangles) tris.emplace_back(t[0], t[1], t[2]);
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(g.voxel);
  const Eigen::Vector3d c0 = g.origin + Eigen::Vector3d::Constant(0.5 * g.voxel);
  xf->postTranslate(openvdb::Vec3d(c0.x(), c0.y(), c0.z()));
  openvdb::FloatGrid::Ptr grid;
  const double t = bench::median_time(repeats, [&] { grid = openvdb::tools::meshToLevelSet<openvdb::FloatGrid>(*xf, points, tris, 3.0f); });
  inside.assign(g.size(), 0);
  const openvdb::FloatGrid::ConstAccessor acc = grid->getConstAccessor();
  uint64_t i = 0;
  for (uint32_t z = 0; z < g.dims[2]; ++z)
    for (uint32_t y = 0; y < g.dims[1]; ++y)
      for (uint32_t x = 0; x < g.dims[0]; ++x, ++i) inside[i] = acc.getValue(openvdb::Coord(int(x), int(y), int(z))) < 0;
  return t;
}

// Voxels where a classification differs from the intended solid's, counting only voxels that are not surface in
// the intended map (nor, for our voxmaps, in ours): interior against empty.
uint64_t wrong_inside(const Voxmap& intended, const std::vector<uint8_t>& inside) {
  uint64_t n = 0;
  for (uint64_t i = 0; i < intended.size(); ++i) {
    const VoxelState s = intended.at(i);
    if (s != kSurface && (s == kInterior) != bool(inside[i])) ++n;
  }
  return n;
}
uint64_t wrong_voxmap(const Voxmap& intended, const Voxmap& vm) {
  uint64_t n = 0;
  for (uint64_t i = 0; i < intended.size(); ++i) {
    const VoxelState s = intended.at(i), v = vm.at(i);
    if (s != kSurface && v != kSurface && s != v) ++n;
  }
  return n;
}

struct DefectRow {
  std::string name;
  size_t triangles = 0;
  double repair = 0, ours = 0, vdb = 0;
  uint64_t ours_wrong = 0, vdb_wrong = 0, evaluated = 0, compared = 0;
  std::string ours_time;  // formatted, with the repeats when fewer
};

// One defect at `res` voxels along the longest side: our repair + voxelize and OpenVDB, each against the intended
// solid (the closed mesh's ray-cast voxmap on the same grid). Runs that take long are repeated less.
DefectRow measure_defect(const test::Defect& d, uint32_t res, int repeats) {
  DefectRow row;
  row.name = d.name;
  row.triangles = d.mesh.size();
  Mesh m;
  row.repair = bench::median_time(repeats, [&] {
    m = d.mesh;
    repair(m);
  });
  VoxelizeOptions o;
  o.resolution = res;
  VoxelizeReport rep;
  Voxmap vm;
  const double t0 = bench::now_seconds();
  vm = voxelize(m, o, &rep);
  const double first = bench::now_seconds() - t0;
  const int reps = first > 10 ? 1 : first > 2 ? std::min(repeats, 3) : repeats;
  row.ours = reps == 1 ? first : bench::median_time(reps, [&] { vm = voxelize(m, o, &rep); });
  row.ours_time = bench::fmt("%.3f", row.ours) + (reps < repeats ? " (" + std::to_string(reps) + (reps == 1 ? " run)" : " runs)") : "");
  row.evaluated = rep.evaluated;
  VoxelizeOptions oi;
  oi.voxel = vm.voxel();
  oi.shift = o.shift;
  const Voxmap intended = voxelize_raycast(d.solid[0], oi);
  if (intended.dims() != vm.dims() || intended.origin() != vm.origin()) {
    std::fprintf(stderr, "%s: the intended solid's grid differs\n", d.name.c_str());
    std::exit(1);
  }
  row.ours_wrong = wrong_voxmap(intended, vm);
  std::vector<uint8_t> inside;
  // OpenVDB gets the defective triangles as they are, with exactly equal vertices merged.
  Mesh welded = d.mesh;
  weld(welded);
  row.vdb = openvdb_inside(welded, vm.grid(), repeats, inside);
  row.vdb_wrong = wrong_inside(intended, inside);
  for (uint64_t i = 0; i < intended.size(); ++i) row.compared += intended.at(i) != kSurface;
  return row;
}

void defect_section(std::ostringstream& md, int repeats, int argc, char** argv) {
  openvdb::initialize();
  md << "\n## Defective meshes: winding number against ray casting and OpenVDB\n\n"
     << bench::provenance(argc, argv) << "\n\n"
     << "Meshes from tests/defects.h, each with a known intended solid (the closed mesh before the defect). *voxelize* "
        "is the winding-number voxeliser (the solid is where the generalized winding number of the repaired mesh is "
        "at least 1/2), *ray casting* the paper's parity voxeliser (voxelize_raycast, closed meshes only), OpenVDB "
        "10's `tools::meshToLevelSet` (half width 3 voxels, its sign flood fill classifying the rest; sampled at our "
        "voxel centres, inside where the distance is negative), on every hardware thread each. *Wrong voxels* "
        "count voxels that are not surface in the intended solid's voxmap (nor in ours) and whose inside/outside "
        "differs from it; the intended solid's voxmap is the closed mesh's voxelize_raycast on the same grid. "
        "*repair* (weld, drop, orient, mark sheets) is timed apart and not included in *voxelize*; OpenVDB gets the "
        "defective triangles with exactly equal vertices merged. Times are medians of " << repeats
     << " runs (fewer where one run takes over 2 s), in seconds. `build/bench_voxelize --defects-only --repeats 5` "
        "prints this section alone.\n\n";

  // 1. The 1.3M-triangle icosphere at 256 voxels across, closed and with 1% of its triangles removed.
  const Mesh big = test::icosphere(8);
  const test::Defect big_holes = test::punched(big, big.size() / 100, 20240601);
  VoxelizeOptions o;
  o.resolution = 256;
  Voxmap w, r;
  VoxelizeReport rep;
  const double t_w = bench::median_time(repeats, [&] { w = voxelize(big, o, &rep); });
  const double t_r = bench::median_time(repeats, [&] { r = voxelize_raycast(big, o); });
  if (w.words() != r.words()) {
    std::fprintf(stderr, "voxelize and voxelize_raycast disagree on the closed icosphere\n");
    std::exit(1);
  }
  const DefectRow holes = measure_defect(big_holes, 256, repeats);
  const test::Defect big_hole = test::punched(big, big.size() / 100, 20240601, true);
  const DefectRow hole = measure_defect(big_hole, 256, repeats);
  std::vector<uint8_t> inside;
  const double t_v = openvdb_inside(big, w.grid(), repeats, inside);
  const uint64_t vdb_closed_wrong = wrong_inside(r, inside);
  char line[1024];
  md << "### Icosphere level 8 (1,310,720 triangles), " << w.dims()[0] << "x" << w.dims()[1] << "x" << w.dims()[2]
     << " voxels\n\n"
     << "| mesh | method | time | wrong voxels | voxels evaluated one by one |\n|---|---|---|---|---|\n";
  auto row = [&](const char* mesh, const char* method, const std::string& t, uint64_t wrong, const std::string& ev) {
    std::snprintf(line, sizeof line, "| %s | %s | %s | %llu | %s |\n", mesh, method, t.c_str(),
                  (unsigned long long)wrong, ev.c_str());
    md << line;
    std::fprintf(stderr, "%s", line);
  };
  row("closed", "voxelize (winding number)", bench::fmt("%.3f", t_w), wrong_voxmap(r, w), std::to_string(rep.evaluated));
  row("closed", "voxelize_raycast", bench::fmt("%.3f", t_r), 0, "-");
  row("closed", "OpenVDB meshToLevelSet", bench::fmt("%.3f", t_v), vdb_closed_wrong, "-");
  const std::string removed = "1% removed (" + std::to_string(big.size() - big_holes.mesh.size()) + " triangles)";
  row(removed.c_str(), "voxelize (winding number)", holes.ours_time, holes.ours_wrong, std::to_string(holes.evaluated));
  row(removed.c_str(), "voxelize_raycast", "refused (open mesh)", 0, "-");
  row(removed.c_str(), "OpenVDB meshToLevelSet", bench::fmt("%.3f", holes.vdb), holes.vdb_wrong, "-");
  const std::string one = "1% removed in one hole (depth " +
                          bench::fmt("%.1f", test::hole_depth(big_hole.removed) / w.voxel()) + " voxels)";
  row(one.c_str(), "voxelize (winding number)", hole.ours_time, hole.ours_wrong, std::to_string(hole.evaluated));
  row(one.c_str(), "OpenVDB meshToLevelSet", bench::fmt("%.3f", hole.vdb), hole.vdb_wrong, "-");
  md << "\nRepair (not included above): " << bench::fmt("%.3f", holes.repair) << " s for the mesh with 1% removed, "
     << bench::fmt("%.3f", hole.repair) << " s with one hole. Voxels compared (not surface in the intended voxmap): "
     << holes.compared << ". The winding number fills a hole across its rim: what it gets wrong is the lens between that "
        "fill and the missing surface (test::hole_depth deep). OpenVDB's sign flood fill leaks through a hole wider "
        "than its band and loses the interior.\n\n";
  const bool g1 = t_w <= t_r, g2 = holes.ours <= 2 * t_w, g3 = t_w <= t_v && holes.ours <= holes.vdb,
             g4 = holes.ours_wrong < holes.vdb_wrong || (holes.ours_wrong == 0 && holes.vdb_wrong == 0);
  md << "Goals: the closed mesh no slower than ray casting (" << bench::fmt("%.3f", t_w) << " against "
     << bench::fmt("%.3f", t_r) << " s: " << (g1 ? "met" : "missed") << "); the punctured mesh within 2x of the closed one ("
     << bench::fmt("%.2f", holes.ours / t_w) << "x: " << (g2 ? "met" : "missed") << "); at least as fast as OpenVDB ("
     << bench::fmt("%.2f", t_v / t_w) << "x and " << bench::fmt("%.2f", holes.vdb / holes.ours) << "x its speed: "
     << (g3 ? "met" : "missed") << "); fewer wrong voxels than OpenVDB on the punctured mesh (" << holes.ours_wrong
     << " against " << holes.vdb_wrong << ": " << (g4 ? "met" : "missed") << ").\n\n";

  // 2. Every defect kind, smaller: icosphere level 6 at 128 voxels across.
  const Mesh s6 = test::icosphere(6);
  std::vector<test::Defect> ds;
  ds.push_back(test::clean(s6));
  ds.push_back(test::punched(s6, 10, 20240602));
  ds.push_back(test::punched(s6, s6.size() / 100, 20240603));
  ds.push_back(test::punched(s6, 40, 20240607, true));
  ds.push_back(test::punched(s6, 400, 20240604, true));
  ds.push_back(test::flipped(s6, 0.01, 20240605));
  ds.push_back(test::inside_out(s6));
  ds.push_back(test::duplicated(s6));
  ds.push_back(test::degenerate(s6, 25, 20240606));
  ds.push_back(test::cracked(s6, 1e-9));
  ds.push_back(test::cracked(s6, 1e-4));
  ds.push_back(test::cracked(s6, 1e-3));
  ds.push_back(test::hollow(6, 0));
  ds.push_back(test::hollow(6, 1));
  md << "### Every defect kind: icosphere level 6 (81,920 triangles), 128 voxels across\n\n"
     << "The hollow spheres are an icosphere level 6 with a cavity (level 5, radius 0.5) whose shell faces inward.\n\n"
     << "| defect | triangles | repair | voxelize | OpenVDB | wrong voxels: voxelize | wrong voxels: OpenVDB | "
        "evaluated one by one |\n|---|---|---|---|---|---|---|---|\n";
  uint64_t ours_total = 0, vdb_total = 0;
  for (const test::Defect& d : ds) {
    const DefectRow x = measure_defect(d, 128, repeats);
    ours_total += x.ours_wrong;
    vdb_total += x.vdb_wrong;
    const size_t comma = x.name.find("icosphere level 6, ") == 0 ? x.name.find(", ") + 2 : 0;
    const std::string name = x.name.substr(comma);
    std::snprintf(line, sizeof line, "| %s | %zu | %.3f | %s | %.3f | %llu | %llu | %llu |\n", name.c_str(),
                  x.triangles, x.repair, x.ours_time.c_str(), x.vdb, (unsigned long long)x.ours_wrong,
                  (unsigned long long)x.vdb_wrong, (unsigned long long)x.evaluated);
    md << line;
    std::fprintf(stderr, "%s", line);
  }
  md << "\nWrong voxels over the table: " << ours_total << " (voxelize) against " << vdb_total << " (OpenVDB).\n";
}


}  // namespace

namespace {

// docs/voxelize.md's last section, "Sparse voxmaps", is bench/sparse_memory.sh's: a rewrite of the file keeps it as it is.
std::string kept_tail(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string t = text.str();
  const size_t at = t.find("\n## Sparse voxmaps\n");
  return at == std::string::npos ? std::string() : t.substr(at);
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path;
  int repeats = 5;
  bool defects_only = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) {
      out_path = argv[++i];
    } else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) {
      repeats = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--defects-only")) {
      defects_only = true;  // the last section alone, to stdout (not with --out: it would replace the whole file)
    } else {
      std::fprintf(stderr, "usage: bench_voxelize [--out FILE] [--repeats N] | bench_voxelize --defects-only [--repeats N]\n");
      return 2;
    }
  }
  if (defects_only && !out_path.empty()) {
    std::fprintf(stderr, "bench_voxelize: --defects-only prints one section; it does not take --out\n");
    return 2;
  }
  if (defects_only) {
    std::ostringstream md;
    defect_section(md, repeats, argc, argv);
    std::cout << md.str();
    return 0;
  }
  std::ostringstream md;
  md << "# Object preparation: speed and size\n\n"
     << "Regenerate with `build/bench_voxelize --out docs/voxelize.md --repeats " << repeats << "` (a Release build)."
     << "\nMachine: " << bench::machine_description() << ". Times are medians of " << repeats
     << " runs, in seconds. *prepare* welds and validates the mesh (closed, manifold, oriented); *voxelize* is "
        "the voxmap (winding-number fill and surface voxels) on every hardware thread and on one (the two maps are "
        "checked to be identical); *shell* is the point shell for target voxels of the voxmap's size (spacing "
        "voxel / sqrt(2), so its grid is sqrt(2) times finer), on every thread.\n\n";

  // 1. Triangles: icospheres of 5k to 1.3M triangles and a 1M-triangle torus, longest axis 256 voxels.
  md << "## Time against triangle count (longest axis 256 voxels)\n\n"
     << "| mesh | triangles | voxmap | prepare | voxelize (all threads) | voxelize (1 thread) | shell (all threads) "
        "| shell points |\n|---|---|---|---|---|---|---|---|\n";
  struct Case {
    std::string name;
    Mesh mesh;
  };
  std::vector<Case> cases;
  for (int level : {4, 5, 6, 7, 8})
    cases.push_back({"icosphere level " + std::to_string(level), make_icosphere(Eigen::Vector3d::Zero(), 1, level)});
  cases.push_back({"torus 1000 x 500", make_torus(1, 0.35, 1000, 500)});
  double goal_time = 0;
  for (const Case& c : cases) {
    const Timing t = measure(c.mesh, 256, repeats, true);
    char line[512];
    std::snprintf(line, sizeof line, "| %s | %zu | %ux%ux%u | %.3f | %.3f | %.3f | %.3f | %llu |\n", c.name.c_str(),
                  c.mesh.size(), t.dims[0], t.dims[1], t.dims[2], t.prepare, t.vox_all, t.vox_one, t.shell_all,
                  (unsigned long long)t.shell_points);
    md << line;
    std::fprintf(stderr, "%s", line);
    if (c.name == "icosphere level 8") goal_time = t.prepare + t.vox_all;
  }
  md << "\nGoal: a 1M-triangle mesh at 256^3 in under 2 s. The 1,310,720-triangle icosphere at 256^3 takes "
     << bench::fmt("%.2f", goal_time) << " s for prepare + voxelize on every thread (" << (goal_time < 2 ? "met" : "missed")
     << "); loading a file adds the parser's time.\n\n";

  // 2. Resolution, for the 1.3M-triangle icosphere.
  md << "## Time against resolution (icosphere level 8, 1,310,720 triangles)\n\n"
     << "| longest axis | voxmap | voxelize (all threads) | voxelize (1 thread) | shell (all threads) | shell points "
        "| surface | interior |\n|---|---|---|---|---|---|---|---|\n";
  const Mesh big = make_icosphere(Eigen::Vector3d::Zero(), 1, 8);
  for (int res : {64, 128, 256, 512, 1024}) {
    const bool shell = res <= 512;  // the shell grid of a 1024^3 voxmap is 1448^3
    const Timing t = measure(big, res, res >= 512 ? std::min(repeats, 3) : repeats, shell);
    char line[512];
    std::snprintf(line, sizeof line, "| %d | %ux%ux%u | %.3f | %.3f | %s | %s | %llu | %llu |\n", res, t.dims[0],
                  t.dims[1], t.dims[2], t.vox_all, t.vox_one, shell ? bench::fmt("%.3f", t.shell_all).c_str() : "-",
                  shell ? std::to_string(t.shell_points).c_str() : "-", (unsigned long long)t.surface,
                  (unsigned long long)t.interior);
    md << line;
    std::fprintf(stderr, "%s", line);
  }

  // 3. Sizes against voxel size for the built-in shapes.
  const DeviceConfig cfg;
  md << "\n## Voxmap and shell size against voxel size (built-in shapes, about 2 units across)\n\n"
     << "Device memory with the default widths (" << cfg.to_string()
     << "): voxmap `ceil(voxels / 32) * 8` bytes, shell `3 * 24 / 8 = 9` bytes per point. The shell is built "
        "for target voxels of the voxmap's size.\n\n"
     << "| shape | voxel | voxmap | surface | interior | voxmap bytes | shell points | shell bytes |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const auto& name : shape_names()) {
    const Mesh m = make_shape(name);
    for (double s : {0.2, 0.1, 0.05, 0.02, 0.01}) {
      VoxelizeOptions o;
      o.voxel = s;
      const Voxmap vm = voxelize(m, o);
      ShellOptions so;
      so.target_voxel = s;
      const PointShell sh = point_shell(m, so);
      const auto c = vm.counts();
      const uint64_t vbytes = (vm.size() + 31) / 32 * 8, sbytes = (sh.size() * 3 * uint64_t(cfg.PW) + 7) / 8;
      char line[512];
      std::snprintf(line, sizeof line, "| %s | %g | %ux%ux%u | %llu | %llu | %llu | %zu | %llu |\n", name.c_str(), s,
                    vm.dims()[0], vm.dims()[1], vm.dims()[2], (unsigned long long)c[kSurface],
                    (unsigned long long)c[kInterior], (unsigned long long)vbytes, sh.size(),
                    (unsigned long long)sbytes);
      md << line;
    }
  }
  md << "\nShell points grow as 1 / voxel^2: about 2 (faces aligned with the grid, the cube) to 3 "
        "(curved, the sphere) times area / voxel^2 for the sqrt(2) rule; voxmap memory grows as 1 / voxel^3.\n";

  // 4. Defective meshes.
  defect_section(md, repeats, argc, argv);
  {
    // Other work on the machine slows every row alike; say how busy it was.
    std::ifstream la("/proc/loadavg");
    std::string l1, l5, l15;
    la >> l1 >> l5 >> l15;
    md << "\nLoad average when the run ended (1, 5, 15 min): " << l1 << ", " << l5 << ", " << l15 << ".\n";
  }
  std::cout << md.str();
  if (!out_path.empty()) {
    const std::string tail = kept_tail(out_path);
    std::ofstream(out_path) << md.str() << tail;
  }
  return 0;
}
