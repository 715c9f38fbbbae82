// The cpu backend. Three arithmetic paths give the same bits as ref/:
//  - double: when the accumulator fits 53 bits (the default widths: 49), every product M*p and every partial
//    sum is an integer below 2^53, so double arithmetic is exact (fused multiply-adds included), and
//    floor(acc * 2^-TF) is exact too. This path vectorises (AVX-512 or AVX2 and FMA where the processor has
//    them, chosen at run time).
//  - int64: when the accumulator fits 63 bits.
//  - ref: otherwise, the reference's own stage functions on 128-bit integers.
// Jobs are split into chunks of points spread over a thread pool; chunk results are merged in order, so the
// stream is the same for any thread count.
#include "host/device_cpu.h"

#include <algorithm>
#include <cmath>

#include "host/thread_pool.h"
#include "ref/pipeline.h"
#include "ref/timing.h"

namespace voxcd {

namespace {

constexpr size_t kChunk = 4096;  // points per task
constexpr size_t kBlock = 256;   // points per vector block inside a task

struct ChunkResult {
  std::vector<Record> hits;  // ALL: every hit; FIRST: at most the first
  uint32_t count = 0;
};

// The whole lookup of a block on the double path, for maps of fewer than 2^31 voxels: transform, floor,
// bounds, linear address, word fetch, state select and hit test. Outputs the linear index and, per point,
// state | hit << 2; returns the number of hits. Outside points read the map's first word and are masked.
// Compiled three times (AVX-512 with 512-bit vectors, AVX2 with FMA, baseline) and chosen once at run time.
#define VOXCD_BLOCK_DOUBLE_FETCH_BODY                                                                           \
  {                                                                                                             \
    const double m0 = mp[0], m1 = mp[1], m2 = mp[2], m3 = mp[3], m4 = mp[4], m5 = mp[5], m6 = mp[6],            \
                 m7 = mp[7], m8 = mp[8];                                                                        \
    const double t0 = tp[0], t1 = tp[1], t2 = tp[2];                                                            \
    const double nx = dp[0], ny = dp[1], nz = dp[2];                                                            \
    const int32_t slot_mask = (int32_t{1} << slot_bits) - 1;                                                    \
    uint32_t count = 0;                                                                                         \
    for (size_t k = 0; k < n; ++k) {                                                                            \
      const double px = double(x[k]), py = double(y[k]), pz = double(z[k]);                                      \
      const double ax = std::floor(m0 * px + m1 * py + m2 * pz + t0);                                           \
      const double ay = std::floor(m3 * px + m4 * py + m5 * pz + t1);                                           \
      const double az = std::floor(m6 * px + m7 * py + m8 * pz + t2);                                           \
      const bool inside = (ax >= 0) & (ax < nx) & (ay >= 0) & (ay < ny) & (az >= 0) & (az < nz);                \
      const int32_t li = int32_t(inside ? ax + nx * (ay + ny * az) : 0.0);                                      \
      const uint32_t st = uint32_t(map[li >> slot_bits] >> (2 * (li & slot_mask))) & 3u;                        \
      const uint32_t hit = uint32_t(inside) & (mask >> st) & 1u;                                                \
      lin[k] = li;                                                                                              \
      state[k] = uint8_t(st | (hit << 2));                                                                      \
      count += hit;                                                                                             \
    }                                                                                                           \
    return count;                                                                                               \
  }
#define VOXCD_BLOCK_DOUBLE_FETCH_ARGS                                                                           \
  const Coord *__restrict x, const Coord *__restrict y, const Coord *__restrict z, size_t n,                    \
      const double *__restrict mp, const double *__restrict tp, const double *__restrict dp,                    \
      const uint64_t *__restrict map, int slot_bits, uint32_t mask, int32_t *__restrict lin,                    \
      uint8_t *__restrict state

template <class Coord>
struct BlockKernel {
  using Fn = uint32_t (*)(VOXCD_BLOCK_DOUBLE_FETCH_ARGS);
  static uint32_t base(VOXCD_BLOCK_DOUBLE_FETCH_ARGS) VOXCD_BLOCK_DOUBLE_FETCH_BODY
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __attribute__((target("arch=haswell"))) static uint32_t avx2(VOXCD_BLOCK_DOUBLE_FETCH_ARGS)
      VOXCD_BLOCK_DOUBLE_FETCH_BODY
  __attribute__((target("arch=skylake-avx512,prefer-vector-width=512"))) static uint32_t
      avx512(VOXCD_BLOCK_DOUBLE_FETCH_ARGS) VOXCD_BLOCK_DOUBLE_FETCH_BODY
#endif
  static Fn choose() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    __builtin_cpu_init();
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw"))
      return avx512;
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return avx2;
#endif
    return base;
  }
};

const BlockKernel<double>::Fn block_fetch = BlockKernel<double>::choose();

void block_int64(const int64_t* x, const int64_t* y, const int64_t* z, size_t n, const Job& j, int tf,
                 int64_t* lin) {
  const int64_t nx = j.nx, ny = j.ny, nz = j.nz;
  for (size_t k = 0; k < n; ++k) {
    const int64_t ix = (j.M[0][0] * x[k] + j.M[0][1] * y[k] + j.M[0][2] * z[k] + j.t[0]) >> tf;
    const int64_t iy = (j.M[1][0] * x[k] + j.M[1][1] * y[k] + j.M[1][2] * z[k] + j.t[1]) >> tf;
    const int64_t iz = (j.M[2][0] * x[k] + j.M[2][1] * y[k] + j.M[2][2] * z[k] + j.t[2]) >> tf;
    const bool inside = uint64_t(ix) < uint64_t(nx) && uint64_t(iy) < uint64_t(ny) && uint64_t(iz) < uint64_t(nz);
    lin[k] = inside ? ix + nx * (iy + ny * iz) : -1;
  }
}

class CpuDevice final : public Device {
 public:
  CpuDevice(const DeviceConfig& cfg, const DeviceOptions& opt) : cfg_(cfg), pool_(opt.threads) {
    cfg_.validate();
    if (cfg_.acc_width() <= 53)
      path_ = Path::Double;
    else if (cfg_.acc_width() <= 63)
      path_ = Path::Int64;
    else
      path_ = Path::Ref;
    slot_bits_ = 0;
    while ((1 << slot_bits_) < cfg_.states_per_word()) ++slot_bits_;
  }
  std::string name() const override { return "cpu"; }
  const DeviceConfig& config() const override { return cfg_; }
  bool models_cycles() const override { return true; }

  void load(const DeviceMemory& mem) override {
    validate_memory(cfg_, mem);
    mem_ = mem;
    const size_t n = mem.shell.size();
    if (path_ == Path::Double) {
      dx_.resize(n), dy_.resize(n), dz_.resize(n);
      for (size_t k = 0; k < n; ++k) {
        dx_[k] = double(mem.shell[k].x);
        dy_[k] = double(mem.shell[k].y);
        dz_[k] = double(mem.shell[k].z);
      }
    }
    // The int64 arrays serve the int64 path, and the double path's maps of 2^31 voxels or more.
    if (path_ == Path::Int64 || (path_ == Path::Double && 3 * cfg_.DW >= 31)) {
      ix_.resize(n), iy_.resize(n), iz_.resize(n);
      for (size_t k = 0; k < n; ++k) {
        ix_[k] = mem.shell[k].x;
        iy_[k] = mem.shell[k].y;
        iz_[k] = mem.shell[k].z;
      }
    }
  }

  std::vector<Record> run(const std::vector<Job>& jobs) override {
    std::vector<Record> out;
    run_into(jobs, out);
    return out;
  }

  void run_into(const std::vector<Job>& jobs, std::vector<Record>& out) override {
    for (const Job& j : jobs) validate_job(cfg_, j, mem_.shell.size(), mem_.map.size());
    // Tasks: (job, first point, end point). The buffers live on between calls, so a caller that runs batch
    // after batch allocates nothing once they have grown.
    tasks_.clear();
    first_task_.assign(jobs.size() + 1, 0);
    for (size_t j = 0; j < jobs.size(); ++j) {
      first_task_[j] = tasks_.size();
      const uint32_t n = jobs[j].shell_count;
      for (uint32_t b = 0; b < n; b += uint32_t(kChunk)) tasks_.push_back({j, b, uint32_t(std::min<size_t>(n, b + kChunk))});
    }
    first_task_[jobs.size()] = tasks_.size();
    if (results_.size() < tasks_.size()) results_.resize(tasks_.size());
    for (size_t i = 0; i < tasks_.size(); ++i) {
      results_[i].hits.clear();
      results_[i].count = 0;
    }
    auto work = [&](size_t i) { run_chunk(jobs[tasks_[i].job], tasks_[i].begin, tasks_[i].end, results_[i]); };
    if (tasks_.size() > 1 && pool_.size() > 1)
      pool_.parallel_for(tasks_.size(), work);
    else
      for (size_t i = 0; i < tasks_.size(); ++i) work(i);
    // Merge in order.
    size_t total = jobs.size();
    for (size_t i = 0; i < tasks_.size(); ++i) total += results_[i].hits.size();
    out.clear();
    out.reserve(total);
    for (size_t j = 0; j < jobs.size(); ++j) {
      uint32_t hits = 0;
      for (size_t i = first_task_[j]; i < first_task_[j + 1]; ++i) {
        ChunkResult& r = results_[i];
        if (jobs[j].mode == Mode::First) {
          if (hits == 0 && r.count) {
            out.push_back(r.hits.front());
            hits = 1;
          }
        } else {
          hits += r.count;
          out.insert(out.end(), r.hits.begin(), r.hits.end());
        }
      }
      out.push_back(Record::done(jobs[j].tag, hits));
    }
    annotate_cycles(cfg_, jobs, out);  // the device's cycles, from ref/'s exact timing model
  }

 private:
  enum class Path { Double, Int64, Ref };

  void run_chunk(const Job& j, uint32_t begin, uint32_t end, ChunkResult& r) const {
    int64_t lin[kBlock];
    int32_t lin32[kBlock];
    uint8_t state[kBlock];  // bits 1:0 the state, bit 2 the hit
    double m[9], t[3];
    const double dims[3] = {double(j.nx), double(j.ny), double(j.nz)};
    for (int i = 0; i < 9; ++i) m[i] = double(j.M[i / 3][i % 3]);
    for (int i = 0; i < 3; ++i) t[i] = double(j.t[i]);
    const double scale = std::ldexp(1.0, -cfg_.TF());
    // The fused kernel takes M and t already scaled by 2^-TF: scaling by a power of two is exact, and so is
    // every product and sum after it (multiples of 2^-TF below 2^(53-TF)).
    double ms[9], ts[3];
    for (int i = 0; i < 9; ++i) ms[i] = m[i] * scale;
    for (int i = 0; i < 3; ++i) ts[i] = t[i] * scale;
    const uint64_t slot_mask = (uint64_t{1} << slot_bits_) - 1;
    const bool fused = path_ == Path::Double && j.voxels() < (uint64_t{1} << 31);
    for (uint32_t b = begin; b < end; b += uint32_t(kBlock)) {
      const size_t n = std::min<size_t>(kBlock, end - b);
      const size_t base = size_t(j.shell_base) + b;
      if (fused) {
        const uint64_t* map = mem_.map.data() + j.map_base;
        const uint32_t count = block_fetch(&dx_[base], &dy_[base], &dz_[base], n, ms, ts, dims, map, slot_bits_,
                                           j.hit_mask, lin32, state);
        if (count == 0) continue;
        if (j.mode == Mode::Count) {
          r.count += count;
          continue;
        }
        for (size_t k = 0; k < n; ++k) lin[k] = lin32[k];
        if (emit_hits(j, b, n, lin, state, r)) return;
        continue;
      }
      switch (path_) {
        case Path::Double:  // a map of 2^31 voxels or more: the accumulator fits 53 bits, so int64 is exact
        case Path::Int64: block_int64(&ix_[base], &iy_[base], &iz_[base], n, j, cfg_.TF(), lin); break;
        case Path::Ref:
          for (size_t k = 0; k < n; ++k) {
            const Located l = locate(cfg_, j, transform(cfg_, j, mem_.shell[base + k]));
            lin[k] = l.inside ? int64_t(l.linear) : -1;
          }
          break;
      }
      // Fetch, select and test without branches (outside points read the map's first word and are masked);
      // then walk only the hits.
      const uint64_t* map = mem_.map.data() + j.map_base;
      const uint32_t mask = j.hit_mask;
      uint32_t count = 0;
      for (size_t k = 0; k < n; ++k) {
        const bool inside = lin[k] >= 0;
        const uint64_t li = inside ? uint64_t(lin[k]) : 0;
        const uint32_t st = uint32_t(map[li >> slot_bits_] >> (2 * (li & slot_mask))) & 3u;
        const uint32_t hit = uint32_t(inside) & (mask >> st) & 1u;
        state[k] = uint8_t(st | (hit << 2));
        count += hit;
      }
      if (count == 0) continue;
      if (j.mode == Mode::Count) {
        r.count += count;
        continue;
      }
      if (emit_hits(j, b, n, lin, state, r)) return;
    }
  }

  // Appends the block's hit records; true when FIRST has its answer.
  static bool emit_hits(const Job& j, uint32_t b, size_t n, const int64_t* lin, const uint8_t* state,
                        ChunkResult& r) {
    for (size_t k = 0; k < n; ++k) {
      if (!(state[k] & 4u)) continue;
      ++r.count;
      const uint64_t li = uint64_t(lin[k]);
      const uint64_t x = li % j.nx, yz = li / j.nx;
      r.hits.push_back(Record::hit(j.tag, b + uint32_t(k), uint32_t(x), uint32_t(yz % j.ny), uint32_t(yz / j.ny),
                                   uint8_t(state[k] & 3u)));
      if (j.mode == Mode::First) return true;
    }
    return false;
  }

  struct Task {
    size_t job;
    uint32_t begin, end;
  };

  DeviceConfig cfg_;
  mutable ThreadPool pool_;
  std::vector<Task> tasks_;
  std::vector<size_t> first_task_;
  std::vector<ChunkResult> results_;
  Path path_;
  int slot_bits_;
  DeviceMemory mem_;
  std::vector<double> dx_, dy_, dz_;
  std::vector<int64_t> ix_, iy_, iz_;
};

}  // namespace

std::unique_ptr<Device> make_cpu_device(const DeviceConfig& cfg, const DeviceOptions& opt) {
  return std::make_unique<CpuDevice>(cfg, opt);
}

}  // namespace voxcd
