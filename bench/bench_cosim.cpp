// bench_cosim: how fast the Verilated device co-simulates (docs/hardware.md, "Co-simulation speed"). One LANES 4
// device, Verilated four times with one more option each (bench/cosim.cmake), driven by two harness loops: the rtl
// backend's (inputs, then eval, rising edge, falling edge: three evals a cycle) and one that reads the outputs the
// falling edge left (they are registers) and evaluates only the two edges. Workload: 64 jobs of 4096 points on a
// 64^3 voxmap with about 1% of its voxels set, in COUNT and in ALL mode (about 1% hits); every run's hits are
// checked against ref/. Prints a markdown table: median Mcycles/s over the repeats by wall time and by the thread's
// CPU time (the machine is shared), each with the ratio to the rtl backend's setup (first row) in the same run.
//
// build/bench_cosim [--repeats N]
#include <verilated.h>

#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "Vcosim_base.h"
#include "Vcosim_noassert.h"
#include "Vcosim_notrace.h"
#include "Vcosim_sized.h"
#include "bench/bench_common.h"
#include "voxcd/ref/pipeline.h"

using namespace voxcd;
using voxcd::bench::machine_description;
using voxcd::bench::median_time;

namespace {

struct Workload {
  DeviceConfig cfg;
  DeviceMemory mem;
  std::vector<Job> jobs;
  uint64_t hits = 0;  // ref/'s
};

Workload make_workload(Mode mode) {
  Workload w;
  w.cfg.LANES = 4;
  std::mt19937_64 rng(7);
  const uint32_t n = 64, per_word = uint32_t(w.cfg.MEMW / 2);
  w.mem.map.assign(n * n * n / per_word, 0);
  for (uint32_t i = 0; i < n * n * n; ++i)
    if (rng() % 100 == 0) w.mem.map[i / per_word] |= uint64_t(1 + rng() % 2) << (2 * (i % per_word));
  std::uniform_int_distribution<int32_t> coord(0, int32_t(n) * 256 - 1);  // PF = 8
  for (int k = 0; k < 4096; ++k) w.mem.shell.push_back({coord(rng), coord(rng), coord(rng)});
  for (uint32_t j = 0; j < 64; ++j) {
    Job job;
    job.tag = j;
    job.mode = mode;
    job.shell_count = 4096;
    job.nx = job.ny = job.nz = n;
    for (int i = 0; i < 3; ++i) job.M[i][i] = int64_t{1} << w.cfg.MF;
    job.t[0] = int64_t(j % 4) << (w.cfg.MF + w.cfg.PF);  // a few voxels along x: different hits per job
    w.jobs.push_back(job);
  }
  for (const Record& r : run_stream(w.cfg, w.mem, w.jobs))
    if (r.kind == Record::Done) w.hits += r.hits;
  return w;
}

template <class M>
class Sim {
 public:
  explicit Sim(const Workload& w) : w_(w), m_(std::make_unique<M>(&ctx_, "dut")) {
    M& m = *m_;
    m.clk_i = 0;
    m.rst_ni = 0;
    m.shell_we_i = m.map_we_i = m.job_valid_i = 0;
    m.hit_ready_i = m.done_ready_i = 1;
    m.eval();
    edges();
    edges();
    m.rst_ni = 1;
    m.eval();
    const size_t words = std::max(w.mem.shell.size(), w.mem.map.size());
    for (size_t k = 0; k < words; ++k) {
      m.shell_we_i = k < w.mem.shell.size();
      if (m.shell_we_i) {
        const ShellWord& p = w.mem.shell[k];
        m.shell_waddr_i = uint32_t(k);
        for (int i = 0; i < 3; ++i)
          for (int b = 0; b < w.cfg.PW; ++b) {
            const int bit = i * w.cfg.PW + b;
            const uint32_t mask = uint32_t{1} << (bit % 32);
            m.shell_wdata_i[bit / 32] = ((uint64_t(p[i]) >> b) & 1) ? (m.shell_wdata_i[bit / 32] | mask)
                                                                     : (m.shell_wdata_i[bit / 32] & ~mask);
          }
      }
      m.map_we_i = k < w.mem.map.size();
      if (m.map_we_i) {
        m.map_waddr_i = uint32_t(k);
        m.map_wdata_i = w.mem.map[k];
      }
      edges();
    }
    m.shell_we_i = m.map_we_i = 0;
    m.eval();
  }
  ~Sim() { m_->final(); }

  // Runs the jobs; returns the cycles and adds up the hits. three_evals: the rtl backend's loop.
  uint64_t run(bool three_evals, uint64_t& hits) {
    M& m = *m_;
    size_t next = 0, dones = 0;
    uint64_t cycles = 0;
    hits = 0;
    while (dones < w_.jobs.size()) {
      m.job_valid_i = next < w_.jobs.size();
      if (m.job_valid_i) drive(w_.jobs[next]);
      if (three_evals) m.eval();
      const bool fire = m.job_valid_i && m.job_ready_o;
      if (m.done_valid_o) {
        hits += m.done_hits_o;
        ++dones;
      }
      edges();
      ++cycles;
      if (fire) ++next;
    }
    if (ctx_.gotError()) throw std::runtime_error("an RTL assertion failed");
    return cycles;
  }

 private:
  void edges() {
    m_->clk_i = 1;
    m_->eval();
    m_->clk_i = 0;
    m_->eval();
    ctx_.timeInc(2);
  }
  void drive(const Job& j) {
    M& m = *m_;
    m.job_tag_i = j.tag;
    m.job_mode_i = uint8_t(j.mode);
    m.job_mask_i = j.hit_mask;
    m.job_shell_base_i = j.shell_base;
    m.job_shell_count_i = j.shell_count;
    m.job_map_base_i = j.map_base;
    m.job_nx_i = uint16_t(j.nx);
    m.job_ny_i = uint16_t(j.ny);
    m.job_nz_i = uint16_t(j.nz);
    const uint32_t mm = (uint32_t{1} << w_.cfg.MW) - 1;
    m.job_m00_i = uint32_t(j.M[0][0]) & mm;
    m.job_m01_i = uint32_t(j.M[0][1]) & mm;
    m.job_m02_i = uint32_t(j.M[0][2]) & mm;
    m.job_m10_i = uint32_t(j.M[1][0]) & mm;
    m.job_m11_i = uint32_t(j.M[1][1]) & mm;
    m.job_m12_i = uint32_t(j.M[1][2]) & mm;
    m.job_m20_i = uint32_t(j.M[2][0]) & mm;
    m.job_m21_i = uint32_t(j.M[2][1]) & mm;
    m.job_m22_i = uint32_t(j.M[2][2]) & mm;
    const uint64_t tm = (uint64_t{1} << w_.cfg.TW) - 1;
    m.job_t0_i = uint64_t(j.t[0]) & tm;
    m.job_t1_i = uint64_t(j.t[1]) & tm;
    m.job_t2_i = uint64_t(j.t[2]) & tm;
    m.job_threshold_i = 0;
  }

  const Workload& w_;
  VerilatedContext ctx_;
  std::unique_ptr<M> m_;
};

struct Row {
  std::string model, options, depths;
  bool three_evals;
  double mcps[2];      // COUNT, ALL: by wall time
  double cpu_mcps[2];  // by the thread's CPU time (what the machine's other load does not take away)
};

double thread_cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

template <class M>
Row measure(const char* model, const char* options, const char* depths, bool three_evals, const Workload* w,
            int repeats) {
  Row row{model, options, depths, three_evals, {0, 0}, {0, 0}};
  for (int k = 0; k < 2; ++k) {
    Sim<M> sim(w[k]);
    uint64_t cycles = 0, hits = 0;
    std::vector<double> cpu;
    const double t = median_time(repeats, [&] {
      const double c0 = thread_cpu_seconds();
      cycles = sim.run(three_evals, hits);
      cpu.push_back(thread_cpu_seconds() - c0);
    });
    row.cpu_mcps[k] = double(cycles) / voxcd::bench::median(cpu) / 1e6;
    if (hits != w[k].hits) {
      std::fprintf(stderr, "%s: %llu hits, ref %llu\n", model, (unsigned long long)hits, (unsigned long long)w[k].hits);
      std::exit(1);
    }
    row.mcps[k] = double(cycles) / t / 1e6;
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  int repeats = 5;
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--repeats") == 0) repeats = std::atoi(argv[i + 1]);
  const Workload w[2] = {make_workload(Mode::Count), make_workload(Mode::All)};
  const char* dflt = "SAW 16, MAW 18 (defaults)";
  const char* sized = "SAW 12, MAW 13 (what is loaded)";
  std::vector<Row> rows;
  rows.push_back(measure<Vcosim_base>("base", "--assert, FST tracing compiled in", dflt, true, w, repeats));
  rows.push_back(measure<Vcosim_base>("base", "--assert, FST tracing compiled in", dflt, false, w, repeats));
  rows.push_back(measure<Vcosim_notrace>("notrace", "--assert", dflt, false, w, repeats));
  rows.push_back(measure<Vcosim_sized>("sized", "--assert", sized, false, w, repeats));
  rows.push_back(measure<Vcosim_noassert>("noassert", "--noassert", sized, false, w, repeats));
  std::printf("| model | Verilator options (all: -O3 --x-assign fast --x-initial fast) | memory depths | evals per "
              "cycle | COUNT Mcycles/s (wall) | ratio | COUNT Mcycles/s (CPU) | ratio | ALL Mcycles/s (wall) | ratio | "
              "ALL Mcycles/s (CPU) | ratio |\n|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n");
  for (const Row& r : rows)
    std::printf("| %s | %s | %s | %d | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", r.model.c_str(),
                r.options.c_str(), r.depths.c_str(), r.three_evals ? 3 : 2, r.mcps[0], r.mcps[0] / rows[0].mcps[0],
                r.cpu_mcps[0], r.cpu_mcps[0] / rows[0].cpu_mcps[0], r.mcps[1], r.mcps[1] / rows[0].mcps[1],
                r.cpu_mcps[1], r.cpu_mcps[1] / rows[0].cpu_mcps[1]);
  std::printf("\nLANES 4, 64 jobs of 4096 points on a 64^3 voxmap, COUNT (no hit records) and ALL (%.2f%% hits); "
              "median of %d runs; hits equal ref's in every run. %s\n",
              100.0 * double(w[1].hits) / (64.0 * 4096.0), repeats, machine_description().c_str());
  return 0;
}
