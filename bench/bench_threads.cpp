// Every core in a process (docs/scale.md): the same work on 1 and on 2 threads (or any list) in the same run,
// interleaved repeat by repeat, with the medians and their ratio, and a check that every thread count gives the
// same results. The machine is shared: every run also measures how much of the machine's CPU time other processes
// took meanwhile (/proc/stat less this process's own), and the speed-up is given over all repeats and over the
// quiet ones (no run of the repeat shared the machine with more than --quiet of other load).
//  - simulate: `voxcd simulate --objects N` as a new user runs it (the built-in scene at its default voxel, grid
//    pruning, cpu backend, ALL contacts), F frames timed by the wall clock after W frames of warm-up; the state
//    hash after them compared across thread counts; and the stages' times (FrameStats) per frame.
//  - pair: one pair query at a time of two 10,000-triangle tori (bench_pair's meshes and poses) at voxel sizes
//    that give shells of about 50,000 and 100,000 points; every contact compared across thread counts.
// Writes Markdown to stdout (and to --out FILE); exits 1 when a thread count gave other results.
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "bench/bench_common.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/ref/util/thread_pool.h"

using namespace voxcd;

namespace {

std::vector<std::string> split(const std::string& list) {
  std::vector<std::string> items;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) items.push_back(item);
  if (items.empty()) throw std::invalid_argument("empty list '" + list + "'");
  return items;
}

// The order of the thread counts in repeat r: rotated by one each repeat, so that no count always runs first.
std::vector<size_t> order(size_t n, int r) {
  std::vector<size_t> o(n);
  for (size_t k = 0; k < n; ++k) o[k] = (k + size_t(r)) % n;
  return o;
}

bool same_contact(const Contact& a, const Contact& b) {
  return a.pair == b.pair && a.a_in_b == b.a_in_b && a.point == b.point && a.voxel == b.voxel &&
         a.state == b.state && std::memcmp(a.position.data(), b.position.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(a.normal.data(), b.normal.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(&a.depth, &b.depth, sizeof(double)) == 0;
}

bool same_results(const std::vector<PairResult>& a, const std::vector<PairResult>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].hits != b[i].hits || a[i].lookups != b[i].lookups || a[i].device_cycles != b[i].device_cycles ||
        a[i].contacts.size() != b[i].contacts.size())
      return false;
    for (size_t k = 0; k < a[i].contacts.size(); ++k)
      if (!same_contact(a[i].contacts[k], b[i].contacts[k])) return false;
  }
  return true;
}

std::string thread_name(unsigned t) { return t == 1 ? "1 thread" : std::to_string(t) + " threads"; }

// The machine's busy CPU time (/proc/stat, all CPUs), this process's CPU time and the wall clock, at one moment.
struct Clock {
  double busy = 0, own = 0, wall = 0;
  static Clock now() {
    Clock c;
    std::ifstream in("/proc/stat");
    std::string cpu;
    double v[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    in >> cpu >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5] >> v[6] >> v[7];
    // user nice system idle iowait irq softirq steal: busy is all but idle and iowait.
    c.busy = (v[0] + v[1] + v[2] + v[5] + v[6] + v[7]) / double(sysconf(_SC_CLK_TCK));
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    c.own = double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
    c.wall = bench::now_seconds();
    return c;
  }
};

// The share of the machine's CPU capacity that other processes used between a and b (about, /proc/stat counts in
// ticks of 10 ms).
double other_load(const Clock& a, const Clock& b) {
  const double cpus = double(std::max(1u, std::thread::hardware_concurrency()));
  const double other = std::max(0.0, (b.busy - a.busy) - (b.own - a.own));
  return std::min(1.0, other / (cpus * std::max(1e-9, b.wall - a.wall)));
}

// One workload's runs: per thread count, per repeat, the value (higher is better when `rate`) and the other load.
struct Series {
  bool rate = true;
  std::vector<std::vector<double>> value, load;
  explicit Series(size_t nt, bool rate_) : rate(rate_), value(nt), load(nt) {}
  void add(size_t k, double v, double l) { value[k].push_back(v), load[k].push_back(l); }
  // Repeats whose every run had at most `quiet` of other load.
  std::vector<size_t> quiet_repeats(double quiet) const {
    std::vector<size_t> q;
    for (size_t r = 0; r < value[0].size(); ++r) {
      bool ok = true;
      for (const auto& l : load) ok &= l[r] <= quiet;
      if (ok) q.push_back(r);
    }
    return q;
  }
  double median(size_t k, const std::vector<size_t>* only = nullptr) const {
    std::vector<double> v;
    for (size_t r = 0; r < value[k].size(); ++r)
      if (!only || std::find(only->begin(), only->end(), r) != only->end()) v.push_back(value[k][r]);
    return bench::median(v);
  }
  double median_load() const {
    std::vector<double> v;
    for (const auto& l : load) v.insert(v.end(), l.begin(), l.end());
    return bench::median(v);
  }
  // The speed-up of thread count k over the first.
  double speedup(size_t k, const std::vector<size_t>* only = nullptr) const {
    const double a = median(0, only), b = median(k, only);
    return rate ? b / a : a / b;
  }
};

}  // namespace

// What a loop of the pool costs by itself: an empty loop of `threads` tasks, its workers polling for it (as between
// the loops of a frame), in microseconds; the median of 7 runs of 20,000 loops.
double empty_loop_us(unsigned threads) {
  ThreadPool pool(threads);
  std::vector<double> us;
  for (int r = 0; r < 7; ++r) {
    constexpr int kLoops = 20000;
    const Clock c0 = Clock::now();
    for (int i = 0; i < kLoops; ++i) pool.parallel_for(threads, [](size_t) {});
    us.push_back((Clock::now().wall - c0.wall) * 1e6 / kLoops);
  }
  std::nth_element(us.begin(), us.begin() + 3, us.end());
  return us[3];
}

int main(int argc, char** argv) {
  const std::string provenance = bench::provenance(argc, argv);
  std::string out_path;
  int repeats = 21;
  std::vector<unsigned> threads = {1, 2};
  std::vector<size_t> counts = {256, 4096};
  std::vector<double> voxels = {0.028, 0.02};
  uint64_t frames_small = 2000, frames_large = 200, warm = 20;
  size_t poses = 40, passes = 5;
  double quiet = 0.1;
  bool run_sim = true, run_pair = true;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
        return argv[++i];
      };
      if (a == "--out") out_path = next();
      else if (a == "--repeats") repeats = std::stoi(next());
      else if (a == "--threads") {
        threads.clear();
        for (const auto& t : split(next())) threads.push_back(unsigned(std::stoul(t)));
      } else if (a == "--counts") {
        counts.clear();
        for (const auto& c : split(next())) counts.push_back(size_t(std::stoull(c)));
      } else if (a == "--voxels") {
        voxels.clear();
        for (const auto& v : split(next())) voxels.push_back(std::stod(v));
      } else if (a == "--frames") {
        // F for N <= 1024, F for larger N
        const auto f = split(next());
        frames_small = std::stoull(f.at(0));
        frames_large = f.size() > 1 ? std::stoull(f[1]) : frames_small;
      } else if (a == "--warm") warm = std::stoull(next());
      else if (a == "--poses") poses = size_t(std::stoull(next()));
      else if (a == "--passes") passes = size_t(std::stoull(next()));
      else if (a == "--quiet") quiet = std::stod(next());
      else if (a == "--only") {
        const std::string w = next();
        run_sim = w == "simulate";
        run_pair = w == "pair";
        if (!run_sim && !run_pair) throw std::invalid_argument("--only: simulate or pair");
      } else {
        throw std::invalid_argument("unknown option " + a);
      }
    }
    if (repeats < 1 || threads.empty() || passes < 1) throw std::invalid_argument("--repeats, --threads and --passes must be positive");
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "bench_threads: %s\nusage: bench_threads [--out FILE] [--repeats N] [--threads 1,2] [--counts "
                 "256,4096] [--frames F[,F_LARGE]] [--warm W] [--voxels 0.028,0.02] [--poses N] [--passes P] "
                 "[--quiet SHARE] [--only simulate|pair]\n",
                 e.what());
    return 2;
  }
  const size_t nt = threads.size();
  std::ostringstream md;
  md << provenance << "\n\n";
  std::ostringstream stages;
  bool all_same = true;

  md << "Medians of " << repeats << " repeats; in each repeat every thread count runs once, in an order rotated "
     << "from repeat to repeat. Each run also measures the share of the machine's CPU time that other processes "
     << "took meanwhile (from /proc/stat, in ticks of 10 ms): the speed-up is given over all repeats and over the "
     << "quiet ones, those whose every run saw at most " << bench::fmt("%.0f%%", 100 * quiet)
     << " of other load (their number in brackets). Machine: " << bench::machine_description()
     << ".\n\n| workload | size |";
  for (unsigned t : threads) md << " " << thread_name(t) << " |";
  for (size_t k = 1; k < nt; ++k) md << " speed-up " << threads[k] << "/" << threads[0] << " | the same, quiet repeats |";
  md << " other load (median) | results |\n|---|---|";
  for (size_t k = 0; k < nt + 2 * (nt - 1) + 2; ++k) md << "---|";
  md << "\n";
  auto row = [&](const std::string& workload, const std::string& size, const Series& s, const char* unit,
                 const std::string& results) {
    const std::vector<size_t> q = s.quiet_repeats(quiet);
    md << "| " << workload << " | " << size << " |";
    for (size_t k = 0; k < nt; ++k) md << " " << bench::fmt(unit, s.median(k)) << " |";
    for (size_t k = 1; k < nt; ++k) {
      md << " " << bench::fmt("%.2fx", s.speedup(k)) << " |";
      md << " " << (q.empty() ? std::string("-") : bench::fmt("%.2fx", s.speedup(k, &q))) << " ("
         << q.size() << ") |";
    }
    md << " " << bench::fmt("%.0f%%", 100 * s.median_load()) << " | " << results << " |\n";
    std::fprintf(stderr, "%s, %s:", workload.c_str(), size.c_str());
    for (size_t k = 1; k < nt; ++k)
      std::fprintf(stderr, " %.2fx (quiet repeats: %s of %zu)", s.speedup(k),
                   q.empty() ? "-" : bench::fmt("%.2fx", s.speedup(k, &q)).c_str(), q.size());
    std::fprintf(stderr, "\n");
  };

  if (run_sim) {
    stages << "\nThe frame's stages (FrameStats, microseconds per frame, medians over the repeats; the mid-phase "
              "is part of the pair tests), and with more than one thread the calling thread's time in the pool's "
              "loops, the rest of the frame (what runs on one thread) and the loops per frame:\n\n| objects | "
              "threads | integrate | bounds | broadphase | pair tests | response | frame | in loops | outside "
              "loops | loops |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (size_t n : counts) {
      RunConfig spec;
      spec.types[0].count = n;
      const Scene scene = make_scene(spec);
      const uint64_t frames = n <= 1024 ? frames_small : frames_large;
      Series hz(nt, true);
      std::vector<std::vector<std::array<double, 8>>> st(nt);
      std::vector<uint64_t> hashes;
      for (int r = 0; r < repeats; ++r)
        for (size_t k : order(nt, r)) {
          RunConfig opt;
          opt.threads = threads[k];
          Simulation sim(scene, opt);
          for (uint64_t f = 0; f < warm; ++f) sim.step();
          std::array<double, 8> sum{};
          if (sim.pool()) sim.pool()->enable_stats(true);
          const Clock c0 = Clock::now();
          for (uint64_t f = 0; f < frames; ++f) {
            const FrameStats s = sim.step();
            sum[0] += s.t_integrate, sum[1] += s.t_bounds, sum[2] += s.t_broadphase, sum[3] += s.t_narrow;
            sum[4] += s.t_response, sum[5] += s.seconds();
          }
          const Clock c1 = Clock::now();
          if (sim.pool()) sum[6] = sim.pool()->stats().seconds, sum[7] = double(sim.pool()->stats().loops) / 1e6;
          hz.add(k, double(frames) / (c1.wall - c0.wall), other_load(c0, c1));
          for (double& v : sum) v = v / double(frames) * 1e6;
          st[k].push_back(sum);
          hashes.push_back(sim.state_hash());
        }
      const bool same = std::all_of(hashes.begin(), hashes.end(), [&](uint64_t h) { return h == hashes[0]; });
      all_same &= same;
      char hash[32];
      std::snprintf(hash, sizeof hash, "%016llx", (unsigned long long)hashes[0]);
      row("`simulate --objects " + std::to_string(n) + "`, frames per second (" + std::to_string(frames) +
              " frames after " + std::to_string(warm) + ")",
          std::to_string(n) + " objects", hz, "%.0f Hz",
          same ? "state hash " + std::string(hash) + " on every run" : "STATE HASHES DIFFER");
      for (size_t k = 0; k < nt; ++k) {
        stages << "| " << n << " | " << threads[k] << " |";
        auto med_of = [&](auto f) {
          std::vector<double> v;
          for (const auto& s : st[k]) v.push_back(f(s));
          return bench::median(v);
        };
        for (size_t c = 0; c < 6; ++c)
          stages << " " << bench::fmt("%.1f", med_of([&](const auto& s) { return s[c]; })) << " |";
        if (threads[k] == 1) {
          stages << " - | - | - |\n";
        } else {
          stages << " " << bench::fmt("%.1f", med_of([](const auto& s) { return s[6]; })) << " | "
                 << bench::fmt("%.1f", med_of([](const auto& s) { return s[5] - s[6]; })) << " | "
                 << bench::fmt("%.1f", med_of([](const auto& s) { return s[7]; })) << " |\n";
        }
      }
    }
  }

  if (run_pair) {
    // bench_pair's meshes and poses.
    Mesh ma = make_torus(1.0, 0.35, 100, 50), mb = make_torus(0.8, 0.3, 100, 50);
    std::mt19937_64 rng(5);
    std::normal_distribution<double> nd(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<PairRequest> reqs;
    for (size_t k = 0; k < poses; ++k) {
      PairRequest r;
      r.a = 0;
      r.b = 1;
      r.pose_a.rotation = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
      r.pose_b.rotation = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
      r.pose_b.translation = Eigen::Vector3d(nd(rng), nd(rng), nd(rng)).normalized() * 1.2 * std::cbrt(u(rng));
      reqs.push_back(r);
    }
    for (double voxel : voxels) {
      ObjectOptions o;
      o.voxel = voxel;
      auto ta = std::make_shared<ObjectType>(make_object_type(make_object(ma, "torus A", 0, o), "torus A"));
      auto tb = std::make_shared<ObjectType>(make_object_type(make_object(mb, "torus B", 0, o), "torus B"));
      const DeviceConfig cfg = fit_memory(DeviceConfig{}, {ta.get(), tb.get()});
      for (bool both : {false, true}) {
        std::vector<std::unique_ptr<PairCollider>> cols;
        for (unsigned t : threads) {
          DeviceOptions dopt;
          dopt.threads = t;
          cols.push_back(std::make_unique<PairCollider>(make_device("cpu", cfg, dopt),
                                                        std::vector<std::shared_ptr<const ObjectType>>{ta, tb}));
        }
        PairOptions opt;
        opt.both_directions = both;
        // Every pose's results on every thread count, compared (untimed).
        std::vector<std::vector<PairResult>> res(nt);
        for (size_t k = 0; k < nt; ++k) res[k] = cols[k]->collide(reqs, opt);
        bool same = true;
        for (size_t k = 1; k < nt; ++k) same &= same_results(res[0], res[k]);
        all_same &= same;
        size_t lookups = 0, contacts = 0;
        for (const auto& r : res[0]) lookups += r.lookups, contacts += r.contacts.size();
        // One query at a time, as an application asks them, reusing the collider's and the result's buffers.
        Series us(nt, false);
        std::vector<PairResult> one;
        std::vector<PairRequest> req(1);
        for (int r = 0; r < repeats; ++r)
          for (size_t k : order(nt, r)) {
            const Clock c0 = Clock::now();
            for (size_t pass = 0; pass < passes; ++pass)
              for (size_t q = 0; q < reqs.size(); ++q) {
                req[0] = reqs[q];
                cols[k]->collide(req, opt, one);
              }
            const Clock c1 = Clock::now();
            us.add(k, (c1.wall - c0.wall) * 1e6 / double(passes * reqs.size()), other_load(c0, c1));
          }
        const size_t points = ta->shell().size() + (both ? tb->shell().size() : 0);
        row(std::string("pair query, ") + (both ? "both directions" : "A in B") + ", us per query (" +
                std::to_string(poses) + " poses, voxel " + bench::fmt("%g", voxel) + ")",
            std::to_string(points) + " shell points, " + std::to_string(lookups / poses) + " lookups and " +
                std::to_string(contacts / poses) + " contacts a query",
            us, "%.0f us", same ? "contacts identical" : "CONTACTS DIFFER");
      }
    }
  }
  md << stages.str();
  const unsigned most = *std::max_element(threads.begin(), threads.end());
  if (most > 1)
    md << "\nAn empty loop of the pool (" << most << " tasks, its workers polling for it): "
       << bench::fmt("%.2f", empty_loop_us(most)) << " us (median of 7 runs of 20,000 loops).\n";
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  return all_same ? 0 : 1;
}
