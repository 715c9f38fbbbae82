// Sparse against dense on the cpu backend (ref/fast: FastRunner), one object in both forms (bench/sparse_lookup_scene.h: a
// ball, 2-bit states and a distance field of SB 8): nanoseconds per lookup of COUNT jobs on one thread (its CPU time,
// the median of the repeats), the map in cache (64^3 voxels) and out of it (1020^3, far beyond the last-level cache),
// points near the ball's surface (every lookup of a sparse map reads a brick) and anywhere in the map's box (most read
// a uniform cell); then a sparse shell against the dense words of its points. Every row's hits agree between the
// forms, and with ref/'s run_stream on one job of each kind.
//   bench_sparse_lookup [--repeats N] [--out FILE] [--ir FILE] [--only in|out]
//       the tables (markdown) on stdout and in FILE; --ir FILE: "case instructions-per-point" lines (bench/sparse_lookup.sh
//       makes them with callgrind) printed beside the times; --only: the in-cache or the out-of-cache maps alone
//   bench_sparse_lookup --count CASE JOBS      runs JOBS jobs of in-cache CASE once (for callgrind: bench/sparse_lookup.sh)
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>

#include "bench/bench_common.h"
#include "bench/sparse_lookup_scene.h"
#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/timing.h"

using namespace voxcd;

namespace {

struct Size {
  const char* name;
  uint32_t n;
  size_t points, jobs;  // a lookup batch: jobs of points
};
const Size kSizes[] = {{"in cache", 64, 4096, 128}, {"out of cache", 1020, 65536, 16}};

// One scene: a map in both forms, the lookup points and the shells, and a job for every case.
struct Scene {
  DeviceConfig cfg;
  DeviceMemory mem;
  uint64_t dense_bytes = 0, sparse_bytes = 0, shell_words = 0, shell_points = 0;
  std::map<std::string, Job> jobs;  // "lookup-surface-dense", ..., "shell-sparse-sparse"
};

DeviceConfig config_of(int sb, uint32_t n) {
  DeviceConfig c;
  c.BL = 3;
  c.SB = sb;
  c.SAW = 22;
  c.MAW = n > 100 ? (sb > 2 ? 28 : 26) : 20;
  return c;
}

Job with_shell(Job j, const DeviceConfig& cfg, const bench::Ball& b, uint32_t base, uint32_t count, bool sparse) {
  bench::ball_pose(cfg, b, j);
  j.mode = Mode::Count;
  j.shell_base = base, j.shell_count = count;
  if (sparse) j.sparse |= kSparseShell;
  return j;
}

Scene make_scene(int sb, const Size& s) {
  Scene sc;
  sc.cfg = config_of(sb, s.n);
  const DeviceConfig& cfg = sc.cfg;
  const bench::Ball b{s.n / 2.0 + 0.17, s.n * 0.4};
  Job dense;
  dense.nx = dense.ny = dense.nz = s.n;
  dense.map_base = cfg.distance() ? bench::append_dense_field(b, s.n, sc.mem.map)
                                  : bench::append_dense_states(b, s.n, sc.mem.map);
  sc.dense_bytes = 8 * sc.mem.map.size();
  const Job sparse = bench::append_sparse(cfg, b, s.n, sc.mem.map);
  sc.sparse_bytes = 8 * (sc.mem.map.size() - sc.dense_bytes / 8);
  auto add = [&](const std::vector<ShellWord>& w) {
    const uint32_t base = uint32_t(sc.mem.shell.size());
    sc.mem.shell.insert(sc.mem.shell.end(), w.begin(), w.end());
    return base;
  };
  for (bool surface : {true, false}) {
    const uint32_t base = add(bench::ball_points(cfg, b, s.n, s.points, surface, surface ? 11 : 12));
    const std::string pts = surface ? "surface" : "box";
    sc.jobs["lookup-" + pts + "-dense"] = with_shell(dense, cfg, b, base, uint32_t(s.points), false);
    sc.jobs["lookup-" + pts + "-sparse"] = with_shell(sparse, cfg, b, base, uint32_t(s.points), false);
  }
  const std::vector<ShellWord> words = bench::sphere_shell(cfg, b, b.r);
  Job walk;
  walk.sparse = kSparseShell;
  walk.shell_count = uint32_t(words.size());
  const std::vector<ShellWord> points = job_points(cfg, words, walk);
  sc.shell_words = words.size(), sc.shell_points = points.size();
  const uint32_t wb = add(words), pb = add(points);
  for (const Job* m : {static_cast<const Job*>(&dense), &sparse}) {
    const std::string map = m == &dense ? "dense" : "sparse";
    sc.jobs["shell-dense-" + map] = with_shell(*m, cfg, b, pb, uint32_t(points.size()), false);
    sc.jobs["shell-sparse-" + map] = with_shell(*m, cfg, b, wb, uint32_t(words.size()), true);
  }
  return sc;
}

// ns per lookup of `batch` on `runner` (one thread: its CPU time, median of `repeats`), and the batch's hits.
struct Timed {
  double ns = 0, first_ns = 0;
  uint64_t hits = 0;
};
Timed time_batch(FastRunner& runner, const std::vector<Job>& batch, uint64_t points, int repeats) {
  Timed r;
  std::vector<Record> out;
  const double w0 = bench::thread_cpu_seconds();
  runner.run_into(batch, out, false);  // the first batch: a distance map's copy is built here
  r.first_ns = (bench::thread_cpu_seconds() - w0) * 1e9 / double(points);
  std::vector<double> t;
  for (int k = 0; k < repeats; ++k) {
    const double t0 = bench::thread_cpu_seconds();
    runner.run_into(batch, out, false);
    t.push_back(bench::thread_cpu_seconds() - t0);
  }
  r.ns = bench::median(t) * 1e9 / double(points);
  for (const Record& rec : out) r.hits += rec.kind == Record::Done ? rec.hits : 0;
  return r;
}

// The job's hits on ref/ (run_stream) against the runner's: false, with a message, if they differ.
bool agrees_with_ref(const Scene& sc, FastRunner& runner, const std::string& name) {
  const Job& j = sc.jobs.at(name);
  const uint32_t want = run_stream(sc.cfg, sc.mem, {j}).back().hits;
  std::vector<Record> got;
  runner.run_into({j}, got, false);
  if (got.back().hits == want) return true;
  std::fprintf(stderr, "bench_sparse_lookup: %s: %u hits, ref %u\n", name.c_str(), got.back().hits, want);
  return false;
}

struct Row {
  std::string scene, name;
  Timed t;
  uint64_t points = 0;
  uint64_t map_bytes = 0, shell_bytes = 0;  // the map's (or the shell's) memory in this form
};

// The pairs of cases that must count the same hits: the same points on both forms of the map, and a sparse shell and
// the dense words of its points.
bool forms_agree(const std::vector<Row>& rows, size_t first) {
  std::map<std::string, uint64_t> hits;
  for (size_t i = first; i < rows.size(); ++i) hits[rows[i].name] = rows[i].t.hits;
  const char* pairs[][2] = {{"lookup-surface-dense", "lookup-surface-sparse"}, {"lookup-box-dense", "lookup-box-sparse"},
                            {"shell-dense-dense", "shell-sparse-dense"}, {"shell-dense-sparse", "shell-sparse-sparse"},
                            {"shell-dense-dense", "shell-dense-sparse"}};
  for (const char* copy : {"lookup-surface-dense", "lookup-box-dense"})  // the rows on the copy, where made
    if (hits.count(copy + std::string("-copy")) && hits.at(copy + std::string("-copy")) != hits.at(copy)) return false;
  for (const auto& p : pairs)
    if (hits.at(p[0]) != hits.at(p[1])) {
      std::fprintf(stderr, "bench_sparse_lookup: %s: %llu hits, %s: %llu\n", p[0], (unsigned long long)hits.at(p[0]), p[1],
                   (unsigned long long)hits.at(p[1]));
      return false;
    }
  return true;
}

// A dense distance map too large for the runner's default copy limit (FastRunner::kNodeCopyLimit): its lookups
// again with the limit raised so that it is read from its node-quad copy, as rows "...-dense-copy".
void time_dense_copy(const Scene& sc, const Size& s, int repeats, const std::string& scene, std::vector<Row>& rows) {
  FastRunner runner(sc.cfg, 1);
  runner.set_node_copy_limit(uint64_t{16} << 30);
  runner.load(sc.mem);
  for (const char* name : {"lookup-box-dense", "lookup-surface-dense"}) {
    const Job& job = sc.jobs.at(name);
    Row r{scene, std::string(name) + "-copy", {}, runner.job_points(job) * s.jobs};
    r.t = time_batch(runner, std::vector<Job>(s.jobs, job), r.points, repeats);
    r.map_bytes = runner.node_copy_bytes();
    std::fprintf(stderr, "%s %s %.3f ns (first batch %.1f) %llu hits\n", scene.c_str(), r.name.c_str(), r.t.ns,
                 r.t.first_ns, (unsigned long long)r.t.hits);
    rows.push_back(r);
  }
}

// Every case of one scene; false when the forms or ref disagree.
bool run_scene(int sb, const Size& s, int repeats, std::vector<Row>& rows) {
  const Scene sc = make_scene(sb, s);
  FastRunner runner(sc.cfg, 1);
  runner.load(sc.mem);
  const std::string scene = std::string(sb > 2 ? "distance" : "2-bit") + ", " + s.name;
  const size_t first = rows.size();
  for (const auto& [name, job] : sc.jobs) {  // in name order: "lookup-box-dense" first on each map
    const bool lookup = name.rfind("lookup", 0) == 0;
    const size_t jobs = lookup ? s.jobs : 1;
    Row r{scene, name, {}, runner.job_points(job) * jobs};
    const bool sparse_map = name.size() > 6 && name.compare(name.size() - 6, 6, "sparse") == 0;
    r.map_bytes = sparse_map ? sc.sparse_bytes : sc.dense_bytes;
    r.shell_bytes = name.rfind("shell-sparse", 0) == 0 ? 9 * sc.shell_words : 9 * sc.shell_points;
    r.t = time_batch(runner, std::vector<Job>(jobs, job), r.points, repeats);
    std::fprintf(stderr, "%s %s %.3f ns (first batch %.1f) %llu hits\n", scene.c_str(), name.c_str(), r.t.ns,
                 r.t.first_ns, (unsigned long long)r.t.hits);
    rows.push_back(r);
    if (!agrees_with_ref(sc, runner, name)) return false;
  }
  if (sb > 2 && s.n > 100) time_dense_copy(sc, s, repeats, scene, rows);
  return forms_agree(rows, first);
}

// `--count CASE JOBS`: CASE is "2bit-NAME" or "distance-NAME" of the in-cache scene; runs JOBS jobs once.
int count_only(const std::string& c, size_t jobs) {
  const size_t dash = c.find('-');
  const std::string kind = c.substr(0, dash), name = dash == std::string::npos ? "" : c.substr(dash + 1);
  const Scene sc = make_scene(kind == "distance" ? 8 : 2, kSizes[0]);
  if ((kind != "2bit" && kind != "distance") || !sc.jobs.count(name)) {
    std::fprintf(stderr, "bench_sparse_lookup: no case '%s'\n", c.c_str());
    return 2;
  }
  FastRunner runner(sc.cfg, 1);
  runner.load(sc.mem);
  std::vector<Record> out;
  const Job& job = sc.jobs.at(name);
  runner.run_into(std::vector<Job>(jobs, job), out, false);
  std::printf("%s %zu jobs %llu points %u hits\n", c.c_str(), jobs,
              (unsigned long long)(runner.job_points(job) * jobs), out.back().hits);
  return 0;
}

// "case instructions-per-point" lines.
std::map<std::string, double> read_ir(const std::string& path) {
  std::map<std::string, double> ir;
  if (path.empty()) return ir;
  std::ifstream in(path);
  std::string c;
  double v = 0;
  while (in >> c >> v) ir[c] = v;
  return ir;
}

std::string mib(uint64_t bytes) { return bench::fmt(bytes < (uint64_t{1} << 20) ? "%.3g" : "%.0f", bytes / 1048576.0); }

// The callgrind count of a case of the in-cache scene ("-" where there is none).
std::string ir_cell(const std::map<std::string, double>& ir, const Row& r) {
  if (r.scene.find("in cache") == std::string::npos) return "-";
  const std::string key = std::string(r.scene.rfind("distance", 0) == 0 ? "distance-" : "2bit-") + r.name;
  const auto it = ir.find(key);
  return it == ir.end() ? "-" : bench::fmt("%.1f", it->second);
}

const Row& row_of(const std::vector<Row>& rows, const std::string& scene, const std::string& name) {
  for (const Row& r : rows)
    if (r.scene == scene && r.name == name) return r;
  throw std::runtime_error("bench_sparse_lookup: no row " + scene + " " + name);
}

bool has_row(const std::vector<Row>& rows, const std::string& scene, const std::string& name) {
  for (const Row& r : rows)
    if (r.scene == scene && r.name == name) return true;
  return false;
}

// One line of a table: the dense case against the sparse one.
std::string compare_line(const std::vector<Row>& rows, const std::map<std::string, double>& ir, const std::string& scene,
                         const std::string& label, const std::string& dense, const std::string& sparse, bool shell) {
  const Row &d = row_of(rows, scene, dense), &s = row_of(rows, scene, sparse);
  const uint64_t db = shell ? d.shell_bytes : d.map_bytes, sb = shell ? s.shell_bytes : s.map_bytes;
  return "| " + scene + " | " + label + " | " + bench::fmt("%.2f", d.t.ns) + " | " + bench::fmt("%.2f", s.t.ns) +
         " | " + bench::fmt("%.2fx", s.t.ns / d.t.ns) + " | " + ir_cell(ir, d) + " | " + ir_cell(ir, s) + " | " +
         mib(db) + " | " + mib(sb) + " |\n";
}

// The first batch's cost per point on each distance map (the first case that runs on it): its copy is built there.
std::string first_batches(const std::vector<Row>& rows) {
  std::string s;
  for (const Row& r : rows) {
    if (r.scene.rfind("distance", 0) != 0 || r.name.rfind("lookup-box", 0) != 0) continue;
    const std::string what = r.name == "lookup-box-sparse" ? "sparse map"
                             : r.name == "lookup-box-dense"  ? "dense map"
                                                             : "dense map, its node-quad copy (limit raised)";
    s += (s.empty() ? "" : "; ") + r.scene + ", " + what + " " + bench::fmt("%.1f", r.t.first_ns) + " ns a point of " +
         std::to_string(r.points);
  }
  return s;
}

std::string tables(int argc, char** argv, int repeats, const std::vector<Row>& rows,
                   const std::map<std::string, double>& ir) {
  std::ostringstream md;
  md << bench::provenance(argc, argv) << "\n\n";
  md << "| voxmap | points | dense map: ns per lookup | sparse map: ns per lookup | sparse / dense | instructions per "
        "lookup, dense (callgrind, AVX2) | sparse | dense map MiB | sparse map MiB |\n|---|---|--:|--:|--:|--:|--:|--:|--:|\n";
  std::vector<std::string> scenes;
  for (const Row& r : rows)
    if (std::find(scenes.begin(), scenes.end(), r.scene) == scenes.end()) scenes.push_back(r.scene);
  for (const std::string& sc : scenes)
    for (const char* pts : {"surface", "box"}) {
      const std::string label = std::string(pts) == "surface" ? "near the surface" : "anywhere in the box";
      const std::string dense = std::string("lookup-") + pts + "-dense", sparse = std::string("lookup-") + pts + "-sparse";
      md << compare_line(rows, ir, sc, label, dense, sparse, false);
      if (has_row(rows, sc, dense + "-copy"))
        md << compare_line(rows, ir, sc, label + ", the dense map's node-quad copy made (limit raised)", dense + "-copy",
                           sparse, false);
    }
  md << "\n| voxmap | map | dense shell: ns per point | sparse shell: ns per point | sparse / dense | instructions "
        "per point, dense (callgrind, AVX2) | sparse | dense shell MiB | sparse shell MiB |\n"
        "|---|---|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const std::string& sc : scenes)
    for (const char* map : {"dense", "sparse"})
      md << compare_line(rows, ir, sc, std::string(map) + " map", std::string("shell-dense-") + map,
                         std::string("shell-sparse-") + map, true);
  md << "\nOne thread, its CPU time, median of " << repeats << " batches after a first one (which builds a distance "
        "map's copy: " << first_batches(rows) << "). " << bench::machine_description() << ".\n";
  return md.str();
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 7;
  std::string out_path, ir_path, only, count_case;
  size_t count_jobs = 0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--ir") && i + 1 < argc) ir_path = argv[++i];
    else if (!std::strcmp(argv[i], "--only") && i + 1 < argc) only = argv[++i];
    else if (!std::strcmp(argv[i], "--count") && i + 2 < argc) count_case = argv[++i], count_jobs = size_t(std::atol(argv[++i]));
    else {
      std::fprintf(stderr, "usage: bench_sparse_lookup [--repeats N] [--out FILE] [--ir FILE] [--only in|out] | "
                           "bench_sparse_lookup --count CASE JOBS\n");
      return 2;
    }
  }
  if (!count_case.empty()) return count_only(count_case, count_jobs);
  std::vector<Row> rows;
  for (int sb : {2, 8})
    for (const Size& s : kSizes) {
      if ((only == "in" && s.n > 100) || (only == "out" && s.n < 100)) continue;
      if (!run_scene(sb, s, repeats, rows)) return 1;
    }
  const std::string md = tables(argc, argv, repeats, rows, read_ir(ir_path));
  std::cout << md;
  if (!out_path.empty()) std::ofstream(out_path) << md;
  return 0;
}
