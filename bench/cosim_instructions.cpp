// cosim_instructions: the harness of bench/cosim_instructions.sh. Drives one Verilated voxcd_device (LANES 4) with
// the workload of bench/bench_cosim.cpp: a 64^3 voxmap with about 1% of its voxels set, a 4096-point shell, JOBS
// jobs of the whole shell (mode COUNT unless told), two evals a cycle. Prints the device cycles, the hits and the
// wall time of the job phase; the script counts instructions around it with callgrind.
//
// cosim_instructions JOBS [MODE: 0 ALL, 1 FIRST, 2 COUNT]
#include <verilated.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "Vvoxcd_device.h"

int main(int argc, char** argv) {
  constexpr int kPW = 24, kPF = 8, kMF = 16;  // the default widths (rtl/voxcd_arch_pkg.sv)
  const int jobs = argc > 1 ? std::atoi(argv[1]) : 64;
  const int mode = argc > 2 ? std::atoi(argv[2]) : 2;
  std::mt19937_64 rng(7);
  const uint32_t n = 64, per_word = 32;
  std::vector<uint64_t> map(n * n * n / per_word, 0);
  for (uint32_t i = 0; i < n * n * n; ++i)
    if (rng() % 100 == 0) map[i / per_word] |= uint64_t(1 + rng() % 2) << (2 * (i % per_word));
  std::uniform_int_distribution<int32_t> coord(0, int32_t(n) * 256 - 1);
  std::vector<std::array<int32_t, 3>> shell;
  for (int k = 0; k < 4096; ++k) shell.push_back({coord(rng), coord(rng), coord(rng)});

  VerilatedContext ctx;
  auto model = std::make_unique<Vvoxcd_device>(&ctx, "dut");
  Vvoxcd_device& m = *model;
  const auto edges = [&] {
    m.clk_i = 1;
    m.eval();
    m.clk_i = 0;
    m.eval();
  };
  m.clk_i = 0;
  m.rst_ni = 0;
  m.shell_we_i = m.map_we_i = m.job_valid_i = 0;
  m.hit_ready_i = m.done_ready_i = 1;
  m.eval();
  edges();
  edges();
  m.rst_ni = 1;
  m.eval();
  for (size_t k = 0; k < std::max(shell.size(), map.size()); ++k) {
    m.shell_we_i = k < shell.size();
    if (m.shell_we_i) {
      m.shell_waddr_i = uint32_t(k);
      for (int w = 0; w < (3 * kPW + 31) / 32; ++w) m.shell_wdata_i[w] = 0;
      for (int i = 0; i < 3; ++i)
        for (int b = 0; b < kPW; ++b)
          if ((uint64_t(shell[k][i]) >> b) & 1) m.shell_wdata_i[(i * kPW + b) / 32] |= 1u << ((i * kPW + b) % 32);
    }
    m.map_we_i = k < map.size();
    if (m.map_we_i) {
      m.map_waddr_i = uint32_t(k);
      m.map_wdata_i = map[k];
    }
    edges();
  }
  m.shell_we_i = m.map_we_i = 0;
  m.eval();

  size_t next = 0, dones = 0;
  uint64_t cycles = 0, hits = 0;
  const auto t0 = std::chrono::steady_clock::now();
  while (dones < size_t(jobs)) {
    m.job_valid_i = next < size_t(jobs);
    if (m.job_valid_i) {
      m.job_tag_i = uint32_t(next);
      m.job_mode_i = uint8_t(mode);
      m.job_mask_i = 6;  // surface | interior
      m.job_shell_base_i = 0;
      m.job_shell_count_i = 4096;
      m.job_map_base_i = 0;
      m.job_nx_i = m.job_ny_i = m.job_nz_i = uint16_t(n);
      m.job_m00_i = m.job_m11_i = m.job_m22_i = 1u << kMF;
      m.job_m01_i = m.job_m02_i = m.job_m10_i = m.job_m12_i = m.job_m20_i = m.job_m21_i = 0;
      m.job_t0_i = uint64_t(next % 4) << (kMF + kPF);  // a few voxels along x: different hits per job
      m.job_t1_i = m.job_t2_i = 0;
      m.job_threshold_i = 0;
    }
    const bool fire = m.job_valid_i && m.job_ready_o;
    if (m.done_valid_o) {
      hits += m.done_hits_o;
      ++dones;
    }
    edges();
    ++cycles;
    if (fire) ++next;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("cycles %llu hits %llu seconds %.6f\n", (unsigned long long)cycles, (unsigned long long)hits, s);
  m.final();
  return 0;
}
