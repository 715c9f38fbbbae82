// The device as the RTL measures it: sustained points per cycle against shell size and lane count, idle cycles
// between back-to-back jobs, pipeline latency, and the speed of the Verilated simulation beside the host
// backends (ref, cpu) on the same stream. Every cycle count here is read from the RTL's own completion records
// or pins, not from the timing model. Writes Markdown to stdout (and to --out FILE); bench/hardware.sh puts it
// into docs/hardware.md. --distance measures the distance devices (SB > 2) instead: the same throughput table on a
// 64^3 distance map at SB 8, the SB 4 and SB 16 models, and their latency. --depth measures every pipeline depth
// the build has models of (docs/hardware.md, "Pipeline depth"): sustained points per cycle, latency, the cycles a
// FIRST job's early stop costs, and how fast each depth co-simulates beside depth 0 in the same run.
#include <verilated.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "Vvoxcd_lanes4.h"
#include "bench/bench_common.h"
#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"

using namespace voxcd;

namespace {

constexpr uint32_t kSide = 64;      // the map: 64^3 voxels
constexpr double kFill = 0.01;      // fraction of surface voxels: about 1% of lookups hit
constexpr uint32_t kShell = 65536;  // shell points: the whole shell memory (SAW = 16)

// A 64^3 map with ~1% surface voxels and a shell of random points inside it (identity pose).
DeviceMemory scene(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  DeviceMemory mem;
  const uint64_t voxels = uint64_t(kSide) * kSide * kSide;
  mem.map.assign(voxels / 32, 0);
  for (uint64_t i = 0; i < voxels; ++i)
    if (u(rng) < kFill) mem.map[i / 32] |= uint64_t(kSurface) << (2 * (i % 32));
  for (uint32_t k = 0; k < kShell; ++k) {
    auto c = [&] { return int64_t(u(rng) * kSide * 256); };  // PF = 8
    mem.shell.push_back({c(), c(), c()});
  }
  return mem;
}

// The same shell on a distance device: node values of a sphere's signed distance (radius 10 voxels, centred),
// 2^(SB-1)/8 per voxel and clamped to the band (the host's kind of map).
DeviceMemory distance_scene(const DeviceConfig& cfg, uint64_t seed) {
  DeviceMemory mem = scene(seed);
  Job m;
  m.nx = m.ny = m.nz = kSide;
  mem.map.assign(map_words(cfg, m), 0);
  const int64_t qmax = (int64_t{1} << (cfg.SB - 1)) - 1, qmin = -qmax - 1;
  const double step = double(int64_t{1} << (cfg.SB - 1)) / 8;
  for (uint64_t Z = 0; Z <= kSide; ++Z)
    for (uint64_t Y = 0; Y <= kSide; ++Y)
      for (uint64_t X = 0; X <= kSide; ++X) {
        const double c = kSide / 2.0;
        const double d = std::sqrt((X - c) * (X - c) + (Y - c) * (Y - c) + (Z - c) * (Z - c)) - 10;
        const int64_t q = std::clamp<int64_t>(std::llround(d * step), qmin, qmax);
        const NodeAddress a = node_address(cfg, m, X, Y, Z);
        const uint64_t mask = (uint64_t{1} << cfg.SB) - 1, shift = uint64_t(cfg.SB) * a.slot;
        mem.map[a.word] |= (uint64_t(q) & mask) << shift;
      }
  return mem;
}

// The threshold below which `fraction` of the shell's points lie (their interpolated distances, from ref/).
int64_t quantile_threshold(const DeviceConfig& cfg, const DeviceMemory& mem, double fraction) {
  Job m;
  m.nx = m.ny = m.nz = kSide;
  m.M[0][0] = m.M[1][1] = m.M[2][2] = int64_t{1} << cfg.MF;
  std::vector<int64_t> d;
  for (const ShellWord& p : mem.shell) {
    const Transformed t = transform(cfg, m, p);
    d.push_back(interpolate(cfg, fetch_nodes(cfg, mem.map, m, locate(cfg, m, t)), fractions(cfg, t)));
  }
  std::nth_element(d.begin(), d.begin() + ptrdiff_t(fraction * double(d.size())), d.end());
  return d[size_t(fraction * double(d.size()))];
}

int64_t g_threshold = 0;  // the threshold of the jobs job() makes (0 on a 2-bit device)

Job job(uint32_t tag, Mode mode, uint32_t base, uint32_t count) {
  Job j;
  j.threshold = g_threshold;
  j.tag = tag;
  j.mode = mode;
  j.shell_base = base;
  j.shell_count = count;
  j.nx = j.ny = j.nz = kSide;
  j.M[0][0] = j.M[1][1] = j.M[2][2] = int64_t{1} << 16;
  return j;
}

std::vector<Job> stream(Mode mode, uint32_t size, size_t n) {
  std::vector<Job> jobs;
  for (size_t i = 0; i < n; ++i) jobs.push_back(job(uint32_t(i), mode, uint32_t((i * 7919) % (kShell - size + 1)), size));
  return jobs;
}


// Points per cycle of the jobs after the first (whose count includes the pipeline fill), from the RTL's records.
struct Sustained {
  double points_per_cycle = 0;
  double hit_fraction = 0;
  uint64_t idle = 0;  // largest cycles - slots over COUNT jobs after the first: cycles lost between jobs
};

Sustained sustained(Device& dev, Mode mode, uint32_t size, int lanes) {
  const std::vector<Job> jobs = stream(mode, size, 8);
  const std::vector<Record> recs = dev.run(jobs);
  uint64_t cycles = 0, points = 0, hits = 0, idle = 0;
  size_t j = 0;
  for (const Record& r : recs) {
    if (r.kind != Record::Done) continue;
    if (j > 0) {
      cycles += *r.cycles;
      points += jobs[j].shell_count;
      hits += r.hits;
      const uint64_t slots = (jobs[j].shell_count + uint64_t(lanes) - 1) / uint64_t(lanes);
      if (mode == Mode::Count) idle = std::max<uint64_t>(idle, *r.cycles - slots);
    }
    ++j;
  }
  return {double(points) / double(cycles), double(hits) / double(points), idle};
}

// Cycles from a job's acceptance to its first hit record and to its completion record on the pins.
struct Latency {
  int to_hit = -1, to_done = -1;
};

Latency latency() {
  auto ctx = std::make_unique<VerilatedContext>();
  auto m = std::make_unique<Vvoxcd_lanes4>(ctx.get(), "voxcd");
  auto tick = [&] {
    m->clk_i = 1;
    m->eval();
    m->clk_i = 0;
    m->eval();
  };
  m->rst_ni = 0;
  m->hit_ready_i = m->done_ready_i = 1;
  tick();
  m->rst_ni = 1;
  // One point at (0.5, 0.5, 0.5) in a 1x1x1 surface map.
  m->shell_we_i = 1;
  m->shell_waddr_i = 0;
  const unsigned __int128 word = (unsigned __int128)128 | ((unsigned __int128)128 << 24) | ((unsigned __int128)128 << 48);
  for (int w = 0; w < 3; ++w) m->shell_wdata_i[w] = uint32_t(word >> (32 * w));  // {z, y, x}, PW = 24
  m->map_we_i = 1;
  m->map_waddr_i = 0;
  m->map_wdata_i = 1;  // voxel 0: surface
  tick();
  m->shell_we_i = m->map_we_i = 0;
  m->job_valid_i = 1;
  m->job_mode_i = 0;
  m->job_mask_i = 6;
  m->job_shell_count_i = 1;
  m->job_nx_i = m->job_ny_i = m->job_nz_i = 1;
  m->job_m00_i = m->job_m11_i = m->job_m22_i = 1u << 16;
  Latency l;
  for (int c = 0; c < 40 && l.to_done < 0; ++c) {
    m->eval();
    if (m->hit_valid_o && l.to_hit < 0) l.to_hit = c;
    if (m->done_valid_o) l.to_done = c;
    const bool accepted = m->job_valid_i && m->job_ready_o;
    tick();
    if (accepted) m->job_valid_i = 0;
  }
  m->final();
  Verilated::threadContextp(ctx.get());
  m.reset();
  return l;
}

// Cycles the RTL counts for a one-point job that hits (its completion record's cycles: from its acceptance to the
// record's emission into the output register), on the model of cfg.
// The point is the first of the shell that hits (ref/): on a distance device every point does (the threshold is
// IW's largest value), on the 2-bit device one in a surface voxel.
uint64_t one_point_cycles(const DeviceConfig& cfg, const DeviceMemory& mem, const std::string& backend = "rtl") {
  Job j = job(0, Mode::All, 0, 1);
  if (cfg.distance()) j.threshold = (cfg.IW() >= 64) ? INT64_MAX : (int64_t{1} << (cfg.IW() - 1)) - 1;
  while (j.shell_base < mem.shell.size() && run_stream(cfg, mem, {j}).front().kind != Record::Hit) ++j.shell_base;
  if (j.shell_base == mem.shell.size()) throw std::runtime_error("bench_hardware: no shell point hits");
  auto dev = make_device(backend, cfg);
  dev->load(mem);
  const std::vector<Record> r = dev->run({j});
  if (r.size() != 2 || r.front().kind != Record::Hit) throw std::runtime_error("bench_hardware: the job did not hit");
  return *r.back().cycles;
}

// The distance devices: sustained throughput of SB 8 at every lane count, the SB 4 and SB 16 models beside it,
// latency. Every model is one of rtl_distance_configs().
void distance_section(std::ostream& md) {
  const uint32_t sizes[] = {16, 64, 256, 1024, 4096, 16384, 65536};
  std::vector<DeviceConfig> sb8, other;
  for (const DeviceConfig& c : rtl_distance_configs()) (c.SB == 8 && c.WB == 8 ? sb8 : other).push_back(c);
  md << "### Distance devices: sustained throughput\n\n"
     << "The same measurement on the distance devices (SB > 2): a 64^3-cell map of a sphere's signed distance "
        "(radius 10 voxels, clamped to a band of 8 voxels), the same 65536 random points, and each job's threshold "
        "at the 1st percentile of the points' interpolated distances, so about 1% of lookups hit (ALL) as above. "
        "SB 8 WB 8 on every lane count the build has; goal: at least 0.95 x LANES from 256 points.\n\n"
     << "| shell points |";
  for (const DeviceConfig& c : sb8) md << " L=" << c.LANES << " ALL | L=" << c.LANES << " COUNT |";
  md << "\n|---|";
  for (size_t i = 0; i < sb8.size(); ++i) md << "---|---|";
  md << "\n";
  std::vector<std::unique_ptr<Device>> devs;
  std::vector<int64_t> thresholds;
  for (const DeviceConfig& c : sb8) {
    const DeviceMemory mem = distance_scene(c, 11);
    thresholds.push_back(quantile_threshold(c, mem, 0.01));
    devs.push_back(make_device("rtl", c));
    devs.back()->load(mem);
  }
  double worst_ratio = 1e9, hit_fraction = 0;
  uint64_t worst_idle = 0;
  for (uint32_t n : sizes) {
    md << "| " << n << " |";
    for (size_t i = 0; i < sb8.size(); ++i) {
      g_threshold = thresholds[i];
      const Sustained a = sustained(*devs[i], Mode::All, n, sb8[i].LANES);
      const Sustained c = sustained(*devs[i], Mode::Count, n, sb8[i].LANES);
      worst_idle = std::max(worst_idle, c.idle);
      if (n >= 256) worst_ratio = std::min(worst_ratio, a.points_per_cycle / sb8[i].LANES);
      if (n == 65536) hit_fraction = a.hit_fraction;
      md << " " << bench::fmt("%.2f", a.points_per_cycle) << " | " << bench::fmt("%.2f", c.points_per_cycle) << " |";
    }
    md << "\n";
    std::fprintf(stderr, "distance throughput: %u points done\n", n);
  }
  md << "\nFrom 256 points on, ALL sustains at least " << bench::fmt("%.3f", worst_ratio)
     << " x LANES (the goal is 0.95; hits at 65536 points: " << bench::fmt("%.2f", 100 * hit_fraction)
     << "%). Idle cycles between back-to-back COUNT jobs, largest over every row: " << worst_idle << ".\n\n";

  md << "The other value widths, 4096-point jobs:\n\n| model | ALL | COUNT | x LANES (ALL) |\n|---|--:|--:|--:|\n";
  for (const DeviceConfig& c : other) {
    const DeviceMemory mem = distance_scene(c, 11);
    g_threshold = quantile_threshold(c, mem, 0.01);
    auto dev = make_device("rtl", c);
    dev->load(mem);
    const Sustained a = sustained(*dev, Mode::All, 4096, c.LANES);
    const Sustained n = sustained(*dev, Mode::Count, 4096, c.LANES);
    md << "| SB " << c.SB << " WB " << c.WB << " LANES " << c.LANES << " | " << bench::fmt("%.2f", a.points_per_cycle)
       << " | " << bench::fmt("%.2f", n.points_per_cycle) << " | " << bench::fmt("%.3f", a.points_per_cycle / c.LANES)
       << " |\n";
  }
  g_threshold = 0;

  // ---- Latency ----
  DeviceConfig two;
  two.LANES = 4;
  const DeviceMemory two_mem = scene(11);
  const uint64_t two_cycles = one_point_cycles(two, two_mem);
  md << "\n### Distance devices: latency\n\n"
     << "A one-point job that hits, accepted with the consumer always ready: the cycles its completion record "
        "carries (from its acceptance to the record's emission into the output register) are "
     << two_cycles << " on the 2-bit device (LANES 4) and";
  const std::vector<DeviceConfig> dist = rtl_distance_configs();
  std::vector<uint64_t> more;  // cycles beyond the 2-bit device's
  for (size_t i = 0; i < dist.size(); ++i) {
    const DeviceConfig& c = dist[i];
    const uint64_t cycles = one_point_cycles(c, distance_scene(c, 11));
    more.push_back(cycles - two_cycles);
    md << (i == 0 ? " " : i + 1 == dist.size() ? " and " : ", ") << cycles << " (SB " << c.SB << ", LANES " << c.LANES
       << ")";
  }
  if (!more.empty() && std::count(more.begin(), more.end(), more.front()) == ptrdiff_t(more.size()))
    md << ": " << more.front() << " more on every distance device";
  md << " (ref/timing.h: kDistanceSlots = " << kDistanceSlots << " slot registers after the voxmap read, "
     << "pipeline_slots = " << kPipelineSlots + kDistanceSlots << " instead of " << kPipelineSlots << ").\n\n";
  md << "Machine: " << bench::machine_description() << ". Verilator " << Verilated::productVersion()
     << ", models built with -O3.\n";
}

// Cycles from one job's completion to the next's, the first a FIRST job of `groups` slots that hits in its first
// slot, the second a one-point COUNT job: the squashed slots, the empty slot, the second job's slot.
uint64_t first_stop_cycles(const DeviceConfig& cfg) {
  DeviceMemory mem;
  const uint32_t groups = 64;
  for (uint32_t k = 0; k < groups * uint32_t(cfg.LANES); ++k) mem.shell.push_back({128, 128, 128});  // voxel 0
  mem.map = {uint64_t{kSurface}};
  Job first;
  first.mode = Mode::First;
  first.shell_count = groups * uint32_t(cfg.LANES);
  Job count;
  count.tag = 1;
  count.mode = Mode::Count;
  count.shell_count = 1;
  auto dev = make_device("rtl", cfg);
  dev->load(mem);
  const std::vector<Record> r = dev->run({first, count});
  if (r.size() != 3 || r[0].kind != Record::Hit) throw std::runtime_error("bench_hardware: the FIRST job did not hit");
  return *r.back().cycles;
}

// The thread's CPU time in seconds: on a shared machine less disturbed by other jobs than wall time.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// Co-simulation speed of the rtl backend at LANES 4 at every depth: 64 COUNT jobs of 4096 points, the depths taken in
// turn within each of `repeats` rounds (so that a change of load falls on all of them), median thread CPU time.
std::vector<double> depth_cosim_rates(const DeviceMemory& mem, int repeats) {
  std::vector<std::unique_ptr<Device>> devs;
  for (int d = 0; d <= kMaxDepth; ++d) {
    DeviceConfig c;
    c.depth = d;
    devs.push_back(make_device("rtl", c));
    devs.back()->load(mem);
  }
  const std::vector<Job> jobs = stream(Mode::Count, 4096, 64);
  std::vector<std::vector<double>> secs(devs.size());
  std::vector<uint64_t> cycles(devs.size(), 0);
  for (int r = 0; r < repeats; ++r) {
    for (size_t d = 0; d < devs.size(); ++d) {
      const double t0 = thread_cpu_seconds();
      const std::vector<Record> recs = devs[d]->run(jobs);
      secs[d].push_back(thread_cpu_seconds() - t0);
      cycles[d] = 0;
      for (const Record& rec : recs)
        if (rec.kind == Record::Done) cycles[d] += *rec.cycles;
    }
  }
  std::vector<double> rates;
  for (size_t d = 0; d < devs.size(); ++d) rates.push_back(double(cycles[d]) / bench::median(secs[d]) / 1e6);
  return rates;
}

// The backend that runs cfg: rtl when the build has its model, else cpu, whose cycles are the timing model's (which
// the RTL matches at every depth, tests/rtl/test_rtl_depth.cpp); `mark` is "*" for cpu.
std::string backend_for(const DeviceConfig& cfg, std::string& mark) {
  try {
    make_device("rtl", cfg);
    mark = "";
    return "rtl";
  } catch (const DeviceError&) {
    mark = "*";
    return "cpu";
  }
}

// One row of the depth table: slot registers, latency, FIRST's stop, points per cycle at LANES 1 (its RTL model, or
// the cpu backend's cycles where the build has none: marked *) and 4; the worst ratio to LANES of the row.
double depth_row(std::ostream& md, const DeviceMemory& mem, int d) {
  DeviceConfig l1, l4;
  l1.LANES = 1;
  l4.LANES = 4;
  l1.depth = l4.depth = d;
  std::string m1;
  auto one = make_device(backend_for(l1, m1), l1);
  auto four = make_device("rtl", l4);
  one->load(mem);
  four->load(mem);
  md << "| " << d << " | " << pipeline_slots(l4) << " | " << one_point_cycles(l4, mem) << " | " << first_stop_cycles(l4)
     << " |";
  const Sustained a1 = sustained(*one, Mode::All, 4096, 1), n1 = sustained(*one, Mode::Count, 4096, 1);
  double worst = std::min(a1.points_per_cycle, n1.points_per_cycle);
  md << " " << bench::fmt("%.3f", a1.points_per_cycle) << m1 << " | " << bench::fmt("%.3f", n1.points_per_cycle) << m1
     << " |";
  for (uint32_t n : {256u, 4096u, 65536u}) {
    const Sustained a4 = sustained(*four, Mode::All, n, 4);
    worst = std::min(worst, a4.points_per_cycle / 4);
    md << " " << bench::fmt("%.2f", a4.points_per_cycle) << " |";
  }
  const Sustained n4 = sustained(*four, Mode::Count, 4096, 4);
  worst = std::min(worst, n4.points_per_cycle / 4);
  md << " " << bench::fmt("%.2f", n4.points_per_cycle) << " | " << bench::fmt("%.3f", worst) << " |";
  return worst;
}

// The deepest banked and distance models beside the same configuration at depth 0 (its RTL model, else the cpu
// backend, whose cycles are the timing model's).
void depth_deepest(std::ostream& md, const DeviceMemory& mem) {
  md << "The deepest pipeline with shared banks and on a distance device, 4096-point jobs (the distance device on "
        "the sphere map of its own section, thresholds at the 1st percentile), beside the same configuration at "
        "depth 0 (its RTL model, or where the build has none the cpu backend's cycles, which are the timing model's: "
        "marked *). The random points of these jobs read random words, so bank conflicts bound the throughput of a "
        "banked device, at every depth alike:\n\n| model | ALL | COUNT | latency (cycles) | at depth 0: ALL | COUNT | "
        "latency |\n|---|--:|--:|--:|--:|--:|--:|\n";
  for (const DeviceConfig& c : rtl_depth_configs()) {
    if (c.depth != kMaxDepth || !(c.banked() || c.distance())) continue;
    DeviceConfig base = c;
    base.depth = 0;
    const DeviceMemory m = c.distance() ? distance_scene(c, 11) : mem;
    g_threshold = c.distance() ? quantile_threshold(c, m, 0.01) : 0;
    md << "| " << (c.distance() ? "SB " + std::to_string(c.SB) + " WB " + std::to_string(c.WB) + " " : "")
       << "LANES " << c.LANES << " BANKS " << c.BANKS << " DEPTH " << c.depth << " |";
    for (const DeviceConfig& x : {c, base}) {
      std::string mark;
      const std::string backend = backend_for(x, mark);
      auto dev = make_device(backend, x);
      dev->load(m);
      const Sustained a = sustained(*dev, Mode::All, 4096, x.LANES), n = sustained(*dev, Mode::Count, 4096, x.LANES);
      const int64_t thr = g_threshold;
      const uint64_t lat = one_point_cycles(x, m, backend);
      g_threshold = thr;
      md << " " << bench::fmt("%.2f", a.points_per_cycle) << mark << " | " << bench::fmt("%.2f", n.points_per_cycle)
         << mark << " | " << lat << mark << " |";
    }
    md << "\n";
  }
  g_threshold = 0;
}

// Every depth of the 2-bit device at LANES 4 (and 1), and the deepest banked and distance models beside their depth-0
// counterparts (ref/timing.h: pipeline_slots = 6 + depth, 9 + depth on a distance device).
void depth_section(std::ostream& md, int repeats) {
  const DeviceMemory mem = scene(11);
  md << "### Pipeline depth: throughput, latency and co-simulation speed\n\n"
     << "Every depth the build has models of, on the scene of the throughput table above (a 64^3 voxmap with 1% "
        "surface voxels, 65536 random points, about 1% of lookups hit): points per cycle of 8 back-to-back jobs of "
        "one size (the first left out) in ALL and COUNT, read from the RTL's completion records; the latency of a "
        "one-point job that hits (its completion record's cycles, from its acceptance to the record's emission); "
        "the cycles from a FIRST job's completion to the next job's when the FIRST job hits in its first slot (its "
        "squashed slots, the empty slot it leaves, the next job's one slot); LANES 1 on its RTL model where the build "
        "has one, else the cpu backend's cycles, which are the timing model's (marked *); and the rtl backend's "
        "co-simulation "
        "speed at LANES 4 on 64 COUNT jobs of 4096 points (the median of "
     << repeats << " runs by thread CPU time, the depths in turn within each round, with the ratio to depth 0). "
                   "Goal: at least 0.95 x LANES from 256 points at every depth, and no depth more than 10% slower to "
                   "co-simulate than depth 0.\n\n"
     << "| depth | slot registers | latency (cycles) | FIRST stop (cycles) | L=1 ALL 4096 | L=1 COUNT 4096 | L=4 ALL "
        "256 | L=4 ALL 4096 | L=4 ALL 65536 | L=4 COUNT 4096 | worst x LANES | co-sim Mcycles/s (L=4) | ratio |\n"
        "|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  const std::vector<double> rates = depth_cosim_rates(mem, repeats);
  double worst = 1e9, slowest = 1e9;
  for (int d = 0; d <= kMaxDepth; ++d) {
    worst = std::min(worst, depth_row(md, mem, d));
    slowest = std::min(slowest, rates[size_t(d)] / rates[0]);
    md << " " << bench::fmt("%.2f", rates[size_t(d)]) << " | " << bench::fmt("%.2f", rates[size_t(d)] / rates[0])
       << " |\n";
    std::fprintf(stderr, "depth %d done\n", d);
  }
  md << "\nEvery depth sustains at least " << bench::fmt("%.3f", worst)
     << " x LANES (the goal is 0.95); the slowest depth co-simulates at " << bench::fmt("%.2f", slowest)
     << " of depth 0's rate in this run (the goal: at least 0.90).\n\n";
  depth_deepest(md, mem);
  md << "\nMachine: " << bench::machine_description() << ". Verilator " << Verilated::productVersion()
     << ", models built with -O3 (the rtl backend's: --assert, FST tracing compiled in).\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path;
  int repeats = 5;
  bool distance = false, depth = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--distance")) distance = true;
    else if (!std::strcmp(argv[i], "--depth")) depth = true;
    else {
      std::fprintf(stderr, "usage: bench_hardware [--out FILE] [--repeats N] [--distance | --depth]\n");
      return 2;
    }
  }
  if (distance || depth) {
    std::ostringstream md;
    if (distance) distance_section(md);
    else depth_section(md, repeats);
    std::cout << md.str();
    if (!out_path.empty()) std::ofstream(out_path) << md.str();
    return 0;
  }
  const DeviceMemory mem = scene(11);
  std::ostringstream md;
  const int lane_counts[] = {1, 2, 4, 8};
  const uint32_t sizes[] = {16, 64, 256, 1024, 4096, 16384, 65536};

  // ---- Throughput ----
  md << "### Sustained throughput\n\n"
     << "Points per cycle of back-to-back jobs of one shell size (8 jobs; the first, which includes the pipeline "
        "fill, is left out), read from the RTL's completion records. ALL: a 64^3 voxmap with 1% surface voxels, "
        "so about 1% of lookups hit and each hit record takes an output cycle; COUNT: no hit records. Goal: at "
        "least 0.95 x LANES from 256 points.\n\n"
     << "| shell points |";
  for (int L : lane_counts) md << " L=" << L << " ALL | L=" << L << " COUNT |";
  md << "\n|---|";
  for (size_t i = 0; i < std::size(lane_counts); ++i) md << "---|---|";
  md << "\n";
  std::vector<std::unique_ptr<Device>> devs;
  for (int L : lane_counts) {
    DeviceConfig cfg;
    cfg.LANES = L;
    devs.push_back(make_device("rtl", cfg));
    devs.back()->load(mem);
  }
  uint64_t worst_idle = 0;
  double worst_ratio = 1e9;
  for (uint32_t n : sizes) {
    md << "| " << n << " |";
    for (size_t li = 0; li < std::size(lane_counts); ++li) {
      const int L = lane_counts[li];
      const Sustained a = sustained(*devs[li], Mode::All, n, L);
      const Sustained c = sustained(*devs[li], Mode::Count, n, L);
      worst_idle = std::max(worst_idle, c.idle);
      if (n >= 256) worst_ratio = std::min(worst_ratio, a.points_per_cycle / L);
      md << " " << bench::fmt("%.2f", a.points_per_cycle) << " | " << bench::fmt("%.2f", c.points_per_cycle) << " |";
    }
    md << "\n";
    std::fprintf(stderr, "throughput: %u points done\n", n);
  }
  md << "\nFrom 256 points on, ALL sustains at least " << bench::fmt("%.3f", worst_ratio)
     << " x LANES (the goal is 0.95). Idle cycles between back-to-back COUNT jobs, largest over every row: "
     << worst_idle << " (the goal is at most 2).\n\n";

  // ---- Latency ----
  const Latency lat = latency();
  md << "### Latency\n\n"
     << "A one-point job that hits, on the 4-lane model, accepted in cycle 0 with the consumer always ready: its "
        "hit record is valid on the pins in cycle "
     << lat.to_hit << " and its completion record in cycle " << lat.to_done
     << ". The timing model's latency to the hit-test stage is " << kFirstSlotLatency
     << " cycles (the queue register and " << kPipelineSlots
     << " slot registers); the output register adds one.\n\n";

  // ---- Simulation speed ----
  md << "### Simulation speed\n\n"
     << "One stream of 64 COUNT jobs of 4096 points (262144 lookups) and the same in ALL mode (~1% hits), run "
        "on each backend; median wall time of "
     << repeats << " runs. rtl cycles are the RTL's own (the sum of its completion records' cycles).\n\n"
     << "| backend | lanes | mode | sim Mcycles/s | Mpoints/s | ratio to ref (points/s) |\n|---|---|---|---|---|---|\n";
  for (Mode mode : {Mode::Count, Mode::All}) {
    const std::vector<Job> jobs = stream(mode, 4096, 64);
    double ref_pps = 0;
    {
      auto dev = make_device("ref", DeviceConfig{});
      dev->load(mem);
      const double t = bench::median_time(repeats, [&] { bench::keep(dev->run(jobs)); });
      ref_pps = 64.0 * 4096 / t;
      md << "| ref | - | " << mode_name(mode) << " | - | " << bench::fmt("%.1f", ref_pps / 1e6) << " | 1.0 |\n";
    }
    {
      auto dev = make_device("cpu", DeviceConfig{});
      dev->load(mem);
      const double t = bench::median_time(repeats, [&] { bench::keep(dev->run(jobs)); });
      md << "| cpu | - | " << mode_name(mode) << " | - | " << bench::fmt("%.1f", 64.0 * 4096 / t / 1e6) << " | "
         << bench::fmt("%.1f", 64.0 * 4096 / t / ref_pps) << " |\n";
    }
    for (size_t li = 0; li < std::size(lane_counts); ++li) {
      std::vector<Record> recs;
      const double t = bench::median_time(repeats, [&] { recs = devs[li]->run(jobs); });
      uint64_t cycles = 0;
      for (const Record& r : recs)
        if (r.kind == Record::Done) cycles += *r.cycles;
      md << "| rtl | " << lane_counts[li] << " | " << mode_name(mode) << " | " << bench::fmt("%.2f", cycles / t / 1e6)
         << " | " << bench::fmt("%.2f", 64.0 * 4096 / t / 1e6) << " | " << bench::fmt("%.2f", 64.0 * 4096 / t / ref_pps)
         << " |\n";
    }
  }
  md << "\nMachine: " << bench::machine_description() << ". Verilator " << Verilated::productVersion()
     << ", models built with -O3.\n";
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  return 0;
}
