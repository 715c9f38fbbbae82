// Sparse devices as the RTL measures them (docs/hardware.md, "Sparse maps and shells"): sustained points per cycle of
// back-to-back sparse-map jobs with dense shells on every sparse model the build has (and, at the depths without a
// model, the timing model's cycles, which equal the RTL's: ref/timing.h), the same for sparse-shell jobs with the
// shell's brick fill beside it, and the latency the sparse registers add. Every RTL figure is read from the device's
// own completion records. Writes Markdown to stdout (bench/sparse_rtl.sh puts it into docs/hardware.md).
//   bench_sparse_rtl [--jobs N]   N back-to-back jobs a stream (default 8; the first, with the pipeline fill, left out)
#include <verilated.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "bench/bench_common.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "voxcd/ref/timing.h"

using namespace voxcd;

namespace {

constexpr uint32_t kSide = 64;       // the map: 64^3 voxels, a sphere of radius kRadius in its middle
constexpr double kRadius = 20;
constexpr uint32_t kPoints = 4096;   // points of a dense-shell job
constexpr int kShift = 16;           // voxels the sparse shell is moved by along x
constexpr uint32_t kCloud = 32768;   // the dense shell: random points in the map's box (the sparse shell after it)

double sphere(double x, double y, double z) {
  const double c = kSide / 2.0;
  return std::sqrt((x - c) * (x - c) + (y - c) * (y - c) + (z - c) * (z - c)) - kRadius;
}

// The sphere's 2-bit states at the voxel centres: surface within 0.87 voxel of it, interior inside, else empty.
uint8_t state_at(uint64_t x, uint64_t y, uint64_t z) {
  const double d = sphere(double(x) + 0.5, double(y) + 0.5, double(z) + 0.5);
  return std::fabs(d) < 0.87 ? kSurface : d < 0 ? kInterior : kEmpty;
}

// Appends the sphere as a sparse 2-bit map (a cell of one state uniform, else a brick); returns its job's fields.
Job sparse_states(const DeviceConfig& cfg, DeviceMemory& mem) {
  Job j;
  j.sparse = kSparseMap, j.nx = j.ny = j.nz = kSide, j.map_base = uint32_t(mem.map.size());
  const uint64_t B = brick_edge(cfg), C = kSide / B, spw = uint64_t(cfg.states_per_word());
  std::vector<uint8_t> codes(C * C * C);
  std::vector<std::vector<uint8_t>> bricks;
  for (uint64_t t = 0; t < codes.size(); ++t) {
    std::vector<uint8_t> s(B * B * B);
    for (uint64_t i = 0; i < s.size(); ++i)
      s[i] = state_at(t % C * B + i % B, t / C % C * B + i / B % B, t / (C * C) * B + i / (B * B));
    const bool uniform = std::all_of(s.begin(), s.end(), [&](uint8_t v) { return v == s[0]; });
    codes[t] = uniform ? s[0] : kCodeBrick;
    if (!uniform) bricks.push_back(s);
  }
  for (uint64_t w : table_image(cfg, codes)) mem.map.push_back(w);
  j.brick_base = uint32_t(mem.map.size()), j.brick_units = uint32_t(bricks.size());
  for (const std::vector<uint8_t>& s : bricks)
    for (uint64_t w = 0; w < unit_words(cfg); ++w) {
      uint64_t word = 0;
      for (uint64_t k = 0; k < spw; ++k) word |= uint64_t(s[w * spw + k]) << (2 * k);
      mem.map.push_back(word);
    }
  return j;
}

// Appends the sphere's signed distance (2^(SB-1)/8 a voxel, clamped) as a sparse distance map: a cell whose nodes all
// clamp is uniform, any other a brick of level 0.
Job sparse_field(const DeviceConfig& cfg, DeviceMemory& mem) {
  Job j;
  j.sparse = kSparseMap, j.nx = j.ny = j.nz = kSide;
  const int64_t qmax = (int64_t{1} << (cfg.SB - 1)) - 1;
  auto q = [&](double x, double y, double z) {
    return std::clamp<int64_t>(std::llround(sphere(x, y, z) * double(qmax + 1) / 8), -qmax - 1, qmax);
  };
  const uint64_t B = brick_edge(cfg), C = kSide / B;
  std::vector<uint8_t> codes(C * C * C);
  for (uint64_t t = 0; t < codes.size(); ++t) {
    bool far = true, deep = true;
    for (uint64_t i = 0; i < (B + 1) * (B + 1) * (B + 1); ++i) {
      const int64_t v = q(double(t % C * B + i % (B + 1)), double(t / C % C * B + i / (B + 1) % (B + 1)),
                          double(t / (C * C) * B + i / ((B + 1) * (B + 1))));
      far = far && v == qmax, deep = deep && v == -qmax - 1;
    }
    codes[t] = far ? kCodeFar : deep ? kCodeDeep : kCodeLevel0;
  }
  mem.map.resize((mem.map.size() + 7) / 8 * 8, 0);
  j.map_base = uint32_t(mem.map.size());
  for (uint64_t w : table_image(cfg, codes)) mem.map.push_back(w);
  mem.map.resize((mem.map.size() + 7) / 8 * 8, 0);
  j.brick_base = uint32_t(mem.map.size()), j.brick_units = uint32_t(table_units(cfg, codes));
  mem.map.resize(mem.map.size() + uint64_t(j.brick_units) * unit_words(cfg), 0);
  uint64_t unit = 0;
  for (uint64_t t = 0; t < codes.size(); ++t) {
    if (codes[t] != kCodeLevel0) continue;
    const Cell cell{kCodeLevel0, 0, j.brick_base + unit++ * unit_words(cfg)};
    for (uint64_t i = 0; i < (B + 1) * (B + 1) * (B + 1); ++i) {
      const uint64_t X = i % (B + 1), Y = i / (B + 1) % (B + 1), Z = i / ((B + 1) * (B + 1));
      const NodeAddress a = brick_node_address(cfg, cell, X, Y, Z);
      const int64_t v = q(double(t % C * B + X), double(t / C % C * B + Y), double(t / (C * C) * B + Z));
      mem.map[a.word] |= (uint64_t(v) & ((uint64_t{1} << cfg.SB) - 1)) << (uint64_t(cfg.SB) * a.slot);
    }
  }
  return j;
}

// The sphere's surface voxels as a sparse shell of the same grid: its 4^3 shell bricks that hold a surface voxel, in
// raster order, each a brick word chained by a step from the one before where it can be (each axis -2..1 bricks),
// else after an origin word. Appended to mem.shell; returns the number of words.
uint32_t sparse_shell(const DeviceConfig& cfg, DeviceMemory& mem) {
  const int64_t n = kSide / kShellBrick, v = int64_t{1} << cfg.PF;
  int64_t prev[3] = {0, 0, 0};
  uint32_t words = 0;
  for (int64_t t = 0; t < n * n * n; ++t) {
    const int64_t b[3] = {t % n, t / n % n, t / (n * n)};
    uint64_t mask = 0;
    for (int i = 0; i < 64; ++i)
      if (state_at(uint64_t(b[0] * 4 + (i & 3)), uint64_t(b[1] * 4 + (i >> 2 & 3)), uint64_t(b[2] * 4 + (i >> 4))) ==
          kSurface)
        mask |= uint64_t{1} << i;
    if (!mask) continue;
    int step[3];
    bool chained = words > 0;
    for (int i = 0; i < 3; ++i) {
      step[i] = int(b[i] - prev[i]);
      chained = chained && step[i] >= -2 && step[i] <= 1;
    }
    if (!chained) {
      mem.shell.push_back(origin_word(cfg, b[0] * 4 * v, b[1] * 4 * v, b[2] * 4 * v));
      std::fill(step, step + 3, 0);
      ++words;
    }
    mem.shell.push_back(brick_word(cfg, mask, step));
    ++words;
    std::copy(b, b + 3, prev);
  }
  return words;
}

}  // namespace

namespace {

// The scene of one configuration: the dense shell (random points in the map's box), then the sparse shell; the sparse
// map; the threshold that about 1% of the dense shell's points lie under (a distance device).
struct Scene {
  DeviceMemory mem;
  Job map;               // the sparse map's fields
  uint32_t shell_words = 0;  // the sparse shell, at kCloud
  uint64_t shell_points = 0;
};

Scene make_scene(const DeviceConfig& cfg) {
  Scene s;
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> u(0, kSide);
  for (uint32_t k = 0; k < kCloud; ++k)
    s.mem.shell.push_back({int64_t(std::ldexp(u(rng), cfg.PF)), int64_t(std::ldexp(u(rng), cfg.PF)),
                           int64_t(std::ldexp(u(rng), cfg.PF))});
  s.shell_words = sparse_shell(cfg, s.mem);
  s.map = cfg.distance() ? sparse_field(cfg, s.mem) : sparse_states(cfg, s.mem);
  s.map.M[0][0] = s.map.M[1][1] = s.map.M[2][2] = int64_t{1} << cfg.MF;
  s.map.hit_mask = uint8_t(1u << kSurface);
  if (cfg.distance()) {
    std::vector<int64_t> d;
    for (uint32_t k = 0; k < kPoints; ++k) d.push_back(look_up(cfg, s.mem.map, s.map, s.mem.shell[k]).dist);
    std::nth_element(d.begin(), d.begin() + kPoints / 100, d.end());
    s.map.threshold = d[kPoints / 100];
  }
  Job all = s.map;
  all.sparse |= kSparseShell, all.shell_base = kCloud, all.shell_count = s.shell_words;
  s.shell_points = job_points(cfg, s.mem.shell, all).size();
  return s;
}

// n back-to-back jobs: dense-shell jobs of kPoints points at spread bases, or the sparse shell moved by kShift voxels
// in x (its surface then crosses the map's at a steep angle, so few of its points hit).
std::vector<Job> stream(const DeviceConfig& cfg, const Scene& s, bool sparse_shell, Mode mode, size_t n) {
  std::vector<Job> jobs;
  for (size_t i = 0; i < n; ++i) {
    Job j = s.map;
    j.tag = uint32_t(i), j.mode = mode;
    if (sparse_shell) {
      j.sparse |= kSparseShell, j.shell_base = kCloud, j.shell_count = s.shell_words;
      j.t[0] = int64_t{kShift} << cfg.TF();
    } else {
      j.shell_base = uint32_t((i * 7919) % (kCloud - kPoints + 1)), j.shell_count = kPoints;
    }
    jobs.push_back(j);
  }
  return jobs;
}

// Points per cycle of a stream's jobs after the first (whose cycles include the pipeline fill), and the fraction
// that hit: on the rtl model of cfg, or where the build has none from the timing model (exact: ref/timing.h).
struct Rate {
  double points_per_cycle = 0, hits = 0;
};
Rate rate(const DeviceConfig& cfg, const Scene& s, bool sparse_shell, Mode mode, bool rtl, size_t n) {
  const std::vector<Job> jobs = stream(cfg, s, sparse_shell, mode, n);
  std::vector<Record> recs;
  if (rtl) {
    auto dev = make_device("rtl", cfg);
    dev->load(s.mem);
    recs = dev->run(jobs);
  } else {
    recs = run_stream(cfg, s.mem, jobs);
    annotate_cycles(cfg, s.mem, jobs, recs);
  }
  uint64_t cycles = 0, points = 0, hits = 0;
  size_t j = 0;
  for (const Record& r : recs) {
    if (r.kind != Record::Done) continue;
    if (j++ == 0) continue;
    cycles += *r.cycles, points += *r.points, hits += r.hits;
  }
  return {double(points) / double(cycles), double(hits) / double(points)};
}

bool has_model(const DeviceConfig& cfg) {
  for (const DeviceConfig& c : rtl_sparse_configs())
    if (c == cfg) return true;
  return false;
}

// The configurations measured: every sparse model of the build, and the depths 1..4 of its 2-bit LANES 4 and
// distance LANES 2 devices, which have no model (their figures are the timing model's).
std::vector<DeviceConfig> configs() {
  std::vector<DeviceConfig> out = rtl_sparse_configs();
  for (int sb : {2, 8}) {
    DeviceConfig c;
    c.BL = 3, c.SB = sb, c.LANES = sb == 2 ? 4 : 2;
    for (int d = 1; d <= 4; ++d) {
      c.depth = d;
      if (!has_model(c)) out.push_back(c);
    }
  }
  std::stable_sort(out.begin(), out.end(), [](const DeviceConfig& a, const DeviceConfig& b) {
    return std::make_tuple(a.SB, a.BANKS, a.LANES, a.depth) < std::make_tuple(b.SB, b.BANKS, b.LANES, b.depth);
  });
  return out;
}

std::string name(const DeviceConfig& c) {
  std::string s = c.distance() ? "SB " + std::to_string(c.SB) + " " : "";
  s += "LANES " + std::to_string(c.LANES);
  if (c.banked()) s += " BANKS " + std::to_string(c.BANKS);
  if (c.depth) s += " DEPTH " + std::to_string(c.depth);
  return s;
}

}  // namespace

namespace {

// Cycles of a one-point job that hits, alone (its completion record's: from its acceptance to the record's emission),
// on the rtl model of cfg; 0 when the build has none.
uint64_t one_point_cycles(const DeviceConfig& cfg) {
  DeviceMemory mem;
  mem.shell = {{int64_t{1} << cfg.PF, int64_t{1} << cfg.PF, int64_t{1} << cfg.PF}};
  Job j;
  j.nx = j.ny = j.nz = 2;
  for (int i = 0; i < 3; ++i) j.M[i][i] = int64_t{1} << cfg.MF;
  j.shell_count = 1;
  mem.map.assign(map_words(cfg, j), cfg.distance() ? 0 : 0x5555555555555555ull >> (64 - cfg.MEMW));
  j.threshold = cfg.distance() ? 1 : 0;
  try {
    auto dev = make_device("rtl", cfg);
    dev->load(mem);
    const std::vector<Record> r = dev->run({j});
    if (r.size() != 2 || r.front().kind != Record::Hit) throw std::runtime_error("bench_sparse_rtl: the job did not hit");
    return *r.back().cycles;
  } catch (const DeviceError&) {
    return 0;
  }
}

void throughput_table(std::ostream& md, size_t n, double& worst) {
  md << "| device | source | ALL | COUNT | ALL / LANES | hits | sparse shell: points a word | slots a word | ALL | "
        "COUNT | COUNT / LANES | hits |\n|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  char buf[512];
  for (const DeviceConfig& cfg : configs()) {
    const bool rtl = has_model(cfg);
    const Scene s = make_scene(cfg);
    const Rate all = rate(cfg, s, false, Mode::All, rtl, n), count = rate(cfg, s, false, Mode::Count, rtl, n);
    const Rate shell_all = rate(cfg, s, true, Mode::All, rtl, n), shell_count = rate(cfg, s, true, Mode::Count, rtl, n);
    Job j = s.map;
    j.sparse |= kSparseShell, j.shell_base = kCloud, j.shell_count = s.shell_words;
    const double slots = double(job_slots(cfg, s.mem.shell, j).groups), L = cfg.LANES;
    if (!cfg.banked()) worst = std::min(worst, std::min(all.points_per_cycle, count.points_per_cycle) / L);
    std::snprintf(buf, sizeof buf,
                  "| %s | %s | %.2f | %.2f | %.3f | %.1f%% | %.1f | %.2f | %.2f | %.2f | %.3f | %.1f%% |\n",
                  name(cfg).c_str(), rtl ? "RTL" : "timing model*", all.points_per_cycle, count.points_per_cycle,
                  all.points_per_cycle / L, 100 * all.hits, double(s.shell_points) / s.shell_words,
                  slots / s.shell_words, shell_all.points_per_cycle, shell_count.points_per_cycle,
                  shell_count.points_per_cycle / L, 100 * shell_all.hits);
    md << buf;
  }
}

void latency_table(std::ostream& md) {
  md << "\n| device | one-point job, sparse (cycles) | the same on the dense device | added |\n|---|--:|--:|--:|\n";
  for (const DeviceConfig& cfg : rtl_sparse_configs()) {
    DeviceConfig dense = cfg;
    dense.BL = 0;
    const uint64_t a = one_point_cycles(cfg), b = one_point_cycles(dense);
    if (!a || !b) continue;
    md << "| " << name(cfg) << " | " << a << " | " << b << " | " << int64_t(a) - int64_t(b) << " |\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  size_t n = 8;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--jobs") == 0 && i + 1 < argc)
      n = std::max<size_t>(2, std::strtoul(argv[++i], nullptr, 0));
    else return std::fprintf(stderr, "usage: bench_sparse_rtl [--jobs N]\n"), 2;
  }
  if (!rtl_unavailable().empty() || rtl_sparse_configs().empty()) {
    std::fprintf(stderr, "bench_sparse_rtl: no sparse RTL models: %s\n", rtl_unavailable().c_str());
    return 1;
  }
  std::ostringstream md;
  md << "### Sparse maps and shells: throughput and latency\n\n"
     << "A 64^3 map of a sphere (radius " << kRadius << " voxels) stored sparse at BL 3 (2-bit: uniform empty and "
     << "interior cells, bricks across the surface; distance: the signed distance, uniform where it clamps, level-0 "
     << "bricks elsewhere). Points per cycle of " << n << " back-to-back jobs of one kind, the first (with the "
     << "pipeline fill) left out, read from the RTL's completion records (or, marked *, at the depths the build has no "
     << "model of, the timing model's cycles, which equal the RTL's). Sparse-map jobs with dense shells: " << kPoints
     << " random points each in the map's box, hit mask surface (distance: the threshold under which 1% of the points "
     << "lie). Sparse-shell jobs: the sphere's surface voxels as 4^3 shell bricks (a brick word each, chained by "
     << "steps), "
     << "moved " << kShift << " voxels along x, on the same sparse map; a word of p points takes "
     << "max(1, ceil(p / LANES)) slots, so "
     << "their rate is set by the brick fill. Goal: at least 0.95 x LANES for sparse-map jobs at every depth (shared "
     << "banks: random points conflict, as on a dense device).\n\n";
  double worst = 1e9;
  throughput_table(md, n, worst);
  char buf[256];
  std::snprintf(buf, sizeof buf, "\nSparse-map jobs with dense shells sustain at least %.3f x LANES on every device "
                "with a copy per lane (the goal is 0.95).\n", worst);
  md << buf;
  latency_table(md);
  md << "\nMachine: " << bench::machine_description() << ". Verilator " << Verilated::productVersion() << ".\n";
  std::cout << md.str();
  return 0;
}
