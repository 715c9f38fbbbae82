#include "voxcd/ref/fast/fast.h"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#include <immintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "voxcd/ref/banks.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/fast/detail/distance_kernel.h"
#include "voxcd/ref/fast/detail/emit.h"
#include "voxcd/ref/fast/detail/point_blocks.h"
#include "voxcd/ref/fast/detail/sparse_shell.h"
#include "voxcd/ref/fast/detail/sparse_copy.h"
#include "voxcd/ref/fast/detail/node_quads.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

namespace {

constexpr size_t kChunk = 2048;  // points per piece
constexpr size_t kBlock = 256;   // points per vector block inside a piece
// Points per task (runs of consecutive pieces, so that the many small jobs of a simulation frame make tasks of a
// few microseconds: about 1.5 ns a point).
constexpr size_t kTaskPoints = 2048;

// The whole lookup of a block on the double path, for maps of fewer than 2^31 voxels: transform, floor,
// bounds, linear address, word fetch, state select and hit test. Outputs per point state | hit << 2 and, for hits,
// the voxel (cx, cy, cz); returns the number of hits. Outside points read the map's first word and are masked.
// Compiled twice (AVX2 with FMA, baseline; a processor with AVX-512 takes block_avx512) and chosen once at run time.
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
      const double vx = inside ? ax : 0.0, vy = inside ? ay : 0.0, vz = inside ? az : 0.0;                      \
      const int32_t li = int32_t(vx + nx * (vy + ny * vz));                                                     \
      const uint32_t st = uint32_t(map[li >> slot_bits] >> (2 * (li & slot_mask))) & 3u;                        \
      const uint32_t hit = uint32_t(inside) & (mask >> st) & 1u;                                                \
      cx[k] = int32_t(vx);                                                                                      \
      cy[k] = int32_t(vy);                                                                                      \
      cz[k] = int32_t(vz);                                                                                      \
      state[k] = uint8_t(st | (hit << 2));                                                                      \
      count += hit;                                                                                             \
    }                                                                                                           \
    return count;                                                                                               \
  }
#define VOXCD_BLOCK_DOUBLE_FETCH_ARGS                                                                           \
  const Coord *__restrict x, const Coord *__restrict y, const Coord *__restrict z, size_t n,                    \
      const double *__restrict mp, const double *__restrict tp, const double *__restrict dp,                    \
      const uint64_t *__restrict map, int slot_bits, uint32_t mask, int32_t *__restrict cx,                     \
      int32_t *__restrict cy, int32_t *__restrict cz, uint8_t *__restrict state

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
bool have_avx512() { return detail::cpu_has_avx512(); }

// The block lookup on AVX-512, written by hand, eight points at a time: it tests the bounds on the exact accumulator
// (for an integer n, floor(a) is in [0, n) exactly when a is, and for such an a truncation is the floor, so it needs
// no floor instruction), computes y and z only where a point is inside along x, skips the fetch for eight points none
// of which is inside, and fetches the words of the others with one gather instruction (measured by CPU time, faster
// than eight scalar loads and than the compiler's vectorisation of the generic body, in and out of cache). Outputs
// as the generic body for the hits; a point that is no hit has state 0 and an unspecified voxel.
// GCC 12's intrinsics fill unused lanes from a self-initialised "undefined" vector, which -Wmaybe-uninitialized
// reports once inlined here.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
__attribute__((target("avx512f,avx512dq,avx512vl,avx512bw,fma"))) uint32_t block_avx512(
    const int32_t* __restrict x, const int32_t* __restrict y, const int32_t* __restrict z, size_t n,
    const double* __restrict mp, const double* __restrict tp, const double* __restrict dp,
    const uint64_t* __restrict map, int slot_bits, uint32_t mask, int32_t* __restrict cx, int32_t* __restrict cy,
    int32_t* __restrict cz, uint8_t* __restrict state) {
  const __m512d m0 = _mm512_set1_pd(mp[0]), m1 = _mm512_set1_pd(mp[1]), m2 = _mm512_set1_pd(mp[2]);
  const __m512d m3 = _mm512_set1_pd(mp[3]), m4 = _mm512_set1_pd(mp[4]), m5 = _mm512_set1_pd(mp[5]);
  const __m512d m6 = _mm512_set1_pd(mp[6]), m7 = _mm512_set1_pd(mp[7]), m8 = _mm512_set1_pd(mp[8]);
  const __m512d t0 = _mm512_set1_pd(tp[0]), t1 = _mm512_set1_pd(tp[1]), t2 = _mm512_set1_pd(tp[2]);
  const __m512d nx = _mm512_set1_pd(dp[0]), ny = _mm512_set1_pd(dp[1]), nz = _mm512_set1_pd(dp[2]);
  const __m512d zero = _mm512_setzero_pd();
  const __m256i inx = _mm256_set1_epi32(int32_t(dp[0])), iny = _mm256_set1_epi32(int32_t(dp[1]));
  const __m256i slot_mask = _mm256_set1_epi32((int32_t{1} << slot_bits) - 1);
  const __m128i word_shift = _mm_cvtsi32_si128(slot_bits);
  const __m512i hit_mask = _mm512_set1_epi64(int64_t(mask)), three = _mm512_set1_epi64(3);
  const __m512i one = _mm512_set1_epi64(1), four = _mm512_set1_epi64(4);
  uint32_t count = 0;
  for (size_t k = 0; k < n; k += 8) {
    const __mmask8 live = n - k >= 8 ? __mmask8(0xff) : __mmask8((1u << (n - k)) - 1);
    const __m512d px = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, x + k));
    const __m512d py = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, y + k));
    const __m512d pz = _mm512_cvtepi32_pd(_mm256_maskz_loadu_epi32(live, z + k));
    const __m512d ax = _mm512_fmadd_pd(m0, px, _mm512_fmadd_pd(m1, py, _mm512_fmadd_pd(m2, pz, t0)));
    __mmask8 in = _mm512_mask_cmp_pd_mask(live, ax, zero, _CMP_GE_OQ);
    in = _mm512_mask_cmp_pd_mask(in, ax, nx, _CMP_LT_OQ);
    __m512d ay = zero, az = zero;
    if (in != 0) {  // y and z only where a point is inside along x
      ay = _mm512_fmadd_pd(m3, px, _mm512_fmadd_pd(m4, py, _mm512_fmadd_pd(m5, pz, t1)));
      az = _mm512_fmadd_pd(m6, px, _mm512_fmadd_pd(m7, py, _mm512_fmadd_pd(m8, pz, t2)));
      in = _mm512_mask_cmp_pd_mask(in, ay, zero, _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, ay, ny, _CMP_LT_OQ);
      in = _mm512_mask_cmp_pd_mask(in, az, zero, _CMP_GE_OQ);
      in = _mm512_mask_cmp_pd_mask(in, az, nz, _CMP_LT_OQ);
    }
    if (in == 0) {
      _mm_mask_storeu_epi8(state + k, live, _mm_setzero_si128());
      continue;
    }
    // Inside lanes: below 2^31 voxels, so the index fits int32; outside lanes are masked from here on.
    const __m256i ix = _mm512_cvttpd_epi32(ax), iy = _mm512_cvttpd_epi32(ay), iz = _mm512_cvttpd_epi32(az);
    const __m256i li = _mm256_maskz_mov_epi32(
        in, _mm256_add_epi32(ix, _mm256_mullo_epi32(inx, _mm256_add_epi32(iy, _mm256_mullo_epi32(iny, iz)))));
    const __m512i word = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), in, _mm256_srl_epi32(li, word_shift),
                                                     reinterpret_cast<const long long*>(map), 8);
    const __m512i shift = _mm512_slli_epi64(_mm512_cvtepi32_epi64(_mm256_and_si256(li, slot_mask)), 1);
    const __m512i st = _mm512_and_si512(_mm512_srlv_epi64(word, shift), three);
    const __mmask8 hit = _mm512_mask_test_epi64_mask(in, _mm512_srlv_epi64(hit_mask, st), one);
    count += uint32_t(__builtin_popcount(hit));
    _mm_mask_storeu_epi8(state + k, live, _mm512_cvtepi64_epi8(_mm512_maskz_or_epi64(hit, st, four)));
    _mm256_mask_storeu_epi32(cx + k, hit, ix);
    _mm256_mask_storeu_epi32(cy + k, hit, iy);
    _mm256_mask_storeu_epi32(cz + k, hit, iz);
  }
  return count;
}
#pragma GCC diagnostic pop
#endif

template <class Coord>
struct BlockKernel {
  using Fn = uint32_t (*)(VOXCD_BLOCK_DOUBLE_FETCH_ARGS);
  static uint32_t base(VOXCD_BLOCK_DOUBLE_FETCH_ARGS) VOXCD_BLOCK_DOUBLE_FETCH_BODY
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
  __attribute__((target("arch=haswell"))) static uint32_t avx2(VOXCD_BLOCK_DOUBLE_FETCH_ARGS)
      VOXCD_BLOCK_DOUBLE_FETCH_BODY
#endif
  struct Choice {
    Fn fn;
    const char* name;
  };
  static Choice choose() {
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
    __builtin_cpu_init();
    const std::string want = detail::kernel_override();
    if (have_avx512() && (want.empty() || want == "avx512")) return {block_avx512, "avx512"};
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && want != "baseline") return {avx2, "avx2"};
#endif
    return {base, "baseline"};
  }
};

// Coordinates are int32 on the double path: DeviceConfig::validate keeps PW within 2..32.
const BlockKernel<int32_t>::Choice block_fetch = BlockKernel<int32_t>::choose();

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

// Quotients by a job's nx and ny without a hardware divide (tens of cycles per hit): a double reciprocal gives the
// quotient within one for dividends below 2^53 (every map that fits memory), and the correction makes it exact.
struct Divider {
  uint64_t d;
  double inv;
  explicit Divider(uint64_t den) : d(den), inv(1.0 / double(den)) {}
  uint64_t operator()(uint64_t v) const {
    uint64_t q = uint64_t(double(v) * inv);
    while (q * d > v) --q;
    while ((q + 1) * d <= v) ++q;
    return q;
  }
};

struct Dividers {
  Divider x, y;
  explicit Dividers(const Job& j) : x(j.nx), y(j.ny) {}
};

using detail::emit;
using detail::emit_cells;

// A record appended in place: a Record returned by value and then copied costs a store-forwarding stall per hit.
Record& push_record(std::vector<Record>& out, Record::Kind kind, uint32_t tag) {
  Record& r = out.emplace_back();
  r.kind = kind;
  r.tag = tag;
  return r;
}

// The voxels from their linear indices.
template <class Lin>
bool emit_hits(const Job& j, uint32_t b, size_t n, const Lin* lin, const uint8_t* state, uint32_t found,
               HitColumns& hits, uint32_t& count) {
  const Dividers div(j);
  return emit(j, b, n, state, found, hits, count, [&](size_t k, uint32_t* v) {
    const uint64_t li = uint64_t(lin[k]);
    const uint64_t yz = div.x(li), z = div.y(yz);
    v[0] = uint32_t(li - yz * j.nx);
    v[1] = uint32_t(yz - z * j.ny);
    v[2] = uint32_t(z);
  });
}

// Hits [from, end) of `c` appended to `out` as hit records of job `tag`.
void append_records(const HitColumns& c, size_t from, uint32_t tag, std::vector<Record>& out) {
  for (size_t k = from; k < c.size(); ++k) {
    Record& r = push_record(out, Record::Hit, tag);
    r.point = c.point[k], r.x = c.x[k], r.y = c.y[k], r.z = c.z[k], r.state = c.state[k], r.dist = c.dist[k];
  }
}

}  // namespace

FastRunner::FastRunner(const DeviceConfig& cfg, unsigned threads) : cfg_(cfg) {
  cfg_.validate();
  if (cfg_.acc_width() <= 53)
    path_ = Path::Double;
  else if (cfg_.acc_width() <= 63)
    path_ = Path::Int64;
  else
    path_ = Path::Wide;
  keep_int64_ = path_ == Path::Int64 || (path_ == Path::Double && 3 * cfg_.DW >= 31);
  while ((1 << slot_bits_) < cfg_.states_per_word()) ++slot_bits_;
  tf_scale_ = std::ldexp(1.0, -cfg_.TF());
  if (threads != 1) pool_ = std::make_shared<ThreadPool>(threads);
}

FastRunner::FastRunner(const DeviceConfig& cfg, std::shared_ptr<ThreadPool> pool) : FastRunner(cfg, 1) {
  pool_ = std::move(pool);
}

FastRunner::~FastRunner() = default;

const char* FastRunner::path_name(Path p) {
  switch (p) {
    case Path::Double: return "double";
    case Path::Int64: return "int64";
    case Path::Wide: return "wide";
  }
  return "?";
}

const char* FastRunner::double_kernel() { return block_fetch.name; }

const char* FastRunner::distance_kernel() { return detail::distance_block_name(); }

unsigned FastRunner::threads() const { return pool_ ? pool_->size() : 1; }

void FastRunner::set_shell_word(size_t k, const ShellWord& w) {
  shell_[k] = w;
  if (path_ == Path::Double) sx_[k] = int32_t(w.x), sy_[k] = int32_t(w.y), sz_[k] = int32_t(w.z);
  if (keep_int64_) ix_[k] = w.x, iy_[k] = w.y, iz_[k] = w.z;
}

void FastRunner::load(const DeviceMemory& mem) {
  validate_memory(cfg_, mem);
  shell_.clear();
  map_.clear();
  drop_node_quads(0, UINT64_MAX);
  write_shell(0, mem.shell.data(), mem.shell.size());
  write_map(0, mem.map.data(), mem.map.size());
}

void FastRunner::write_shell(uint64_t first, const ShellWord* words, size_t n) {
  if (first + n > cfg_.shell_depth())
    throw JobError("shell words [" + std::to_string(first) + ", " + std::to_string(first + n) +
                   ") do not fit the shell memory of 2^SAW = " + std::to_string(cfg_.shell_depth()) + " words");
  for (size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      if (!fits_signed(words[i][c], cfg_.PW))
        throw JobError("shell word " + std::to_string(first + i) + " coordinate " + std::to_string(c) + " = " +
                       std::to_string(words[i][c]) + " does not fit PW = " + std::to_string(cfg_.PW) + " bits");
  const size_t end = size_t(first + n);
  if (shell_.size() < end) {
    shell_.resize(end);
    if (path_ == Path::Double) sx_.resize(end), sy_.resize(end), sz_.resize(end);
    if (keep_int64_) ix_.resize(end), iy_.resize(end), iz_.resize(end);
  }
  for (size_t i = 0; i < n; ++i) set_shell_word(size_t(first) + i, words[i]);
}

void FastRunner::write_map(uint64_t first, const uint64_t* words, size_t n) {
  if (first + n > cfg_.map_depth())
    throw JobError("voxmap words [" + std::to_string(first) + ", " + std::to_string(first + n) +
                   ") do not fit the voxmap memory of 2^MAW = " + std::to_string(cfg_.map_depth()) + " words");
  for (size_t i = 0; i < n; ++i)
    if (!fits_unsigned(words[i], cfg_.MEMW))
      throw JobError("voxmap word " + std::to_string(first + i) + " has bits above MEMW = " +
                     std::to_string(cfg_.MEMW));
  const size_t end = size_t(first + n);
  drop_node_quads(first, end);
  if (map_.size() < end) map_.resize(end);
  std::copy(words, words + n, map_.begin() + std::ptrdiff_t(first));
}

BankCycles FastRunner::bank_cycles(const Job& job, const JobHits& hits, uint32_t done_hits) const {
  return job_bank_cycles(cfg_, shell_, map_, job, hits, done_hits);
}

std::vector<Record> FastRunner::run(const std::vector<Job>& jobs, bool cycles) {
  std::vector<Record> out;
  run_into(jobs, out, cycles);
  return out;
}

void FastRunner::run_into(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles) {
  run_jobs(jobs, out, cycles, true);
}

void FastRunner::run_validated_into(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles) {
  run_jobs(jobs, out, cycles, false);
}

uint64_t FastRunner::walk_sparse_shell(const Job& j, std::vector<detail::ShellCursor>* cursors, JobSlots* slots) const {
  const detail::ShellBricks bricks(cfg_, shell_.data() + j.shell_base, j.shell_count);
  detail::ShellWalk walk;
  detail::walk_shell(cfg_, bricks, kChunk, walk, slots);
  if (cursors) cursors->swap(walk.cursors);
  return walk.points;
}

const detail::ShellCursor* FastRunner::cursor_of(const Piece& p) const {
  return p.at == SIZE_MAX ? nullptr : piece_at_.data() + p.at;
}

uint64_t FastRunner::job_points(const Job& job) const {
  return job.sparse_shell() ? walk_sparse_shell(job, nullptr, nullptr) : job.shell_count;
}

JobSlots FastRunner::job_slots(const Job& job) const {
  if (!job.sparse_shell()) return voxcd::job_slots(cfg_, job);
  JobSlots s;
  walk_sparse_shell(job, nullptr, &s);
  return s;
}

void FastRunner::run_hits(const Job* jobs, size_t n, HitColumns& hits, std::vector<JobOutcome>& out,
                          bool cycles) const {
  for (size_t j = 0; j < n; ++j) validate_job(cfg_, jobs[j], shell_.size(), map_.size());
  hits.clear();
  out.resize(n);
  JobSpan prev;
  JobSlots slots;
  for (size_t j = 0; j < n; ++j) {
    const Job& job = jobs[j];
    JobOutcome& o = out[j];
    o = JobOutcome();
    o.first = hits.size();
    if (job.sparse_shell()) walk_sparse_shell(job, nullptr, &slots);
    else slots = voxcd::job_slots(cfg_, job);
    run_chunk(job, 0, uint32_t(slots.points), hits, o.hits);  // FIRST stops at its hit
    o.records = hits.size() - o.first;
    if (!cycles) continue;
    // The timing model's cycles from the hits' summary, as annotate_cycles gives them for this run as a stream.
    const JobHits sum = job_hits(slots, hits.point.data() + o.first, o.records);
    o.span = job_span(cfg_, job, slots, j, sum, o.hits,
                      cfg_.banked() ? job_bank_cycles(cfg_, shell_, map_, job, sum, o.hits) : BankCycles{});
    o.cycles = span_cycles(cfg_, j ? &prev : nullptr, o.span);
    prev = o.span;
  }
}

void FastRunner::run_piece(const Job& job, uint32_t begin, uint32_t end, bool validate, HitColumns& hits,
                           uint32_t& count) const {
  if (validate) validate_job(cfg_, job, shell_.size(), map_.size());
  run_chunk(job, begin, end, hits, count);
}

size_t FastRunner::make_pieces(const std::vector<Job>& jobs) {
  // Pieces: (job, first point, end point), at most kChunk points each.
  // A sparse shell's words are walked once: its points, where each piece's begin and its slots. The jobs are not
  // validated yet: a job whose shell is not loaded is left with no points (validation refuses it before it runs).
  pieces_.clear();
  piece_at_.clear();
  first_piece_.assign(jobs.size() + 1, 0);
  batch_slots_.resize(jobs.size());
  std::vector<detail::ShellCursor> cursors;
  size_t points = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    first_piece_[j] = pieces_.size();
    const Job& job = jobs[j];
    JobSlots& slots = batch_slots_[j];
    if (!job.sparse_shell()) {  // job_slots(cfg, job), in place: a batch may hold many small jobs
      slots.lanes = uint64_t(cfg_.dense_slot_points()), slots.points = job.shell_count;
      slots.groups = job.shell_count == 0 ? 1 : (slots.points + slots.lanes - 1) / slots.lanes;
      slots.starts.clear();
    } else if (uint64_t(job.shell_base) + job.shell_count <= shell_.size()) {
      cursors.clear();
      walk_sparse_shell(job, &cursors, &slots);
    } else {
      slots = JobSlots{};
    }
    const uint32_t n = uint32_t(slots.points);
    points += n;
    for (uint32_t b = 0; b < n; b += uint32_t(kChunk)) {
      Piece& p = pieces_.emplace_back();
      p.job = j;
      p.begin = b;
      p.end = uint32_t(std::min<size_t>(n, b + kChunk));
      if (job.sparse_shell()) p.at = piece_at_.size(), piece_at_.push_back(cursors[b / kChunk]);
    }
  }
  first_piece_[jobs.size()] = pieces_.size();
  return points;
}

void FastRunner::run_serial(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles, bool validate) {
  // Every job validated first, then the pieces in order, hits straight into `out`; FIRST skips the pieces after its
  // hit.
  if (validate)
    for (const Job& j : jobs) validate_job(cfg_, j, shell_.size(), map_.size());
  out.clear();
  out.reserve(2 * jobs.size());
  for (size_t j = 0; j < jobs.size(); ++j) {
    uint32_t hits = 0;
    for (size_t i = first_piece_[j]; i < first_piece_[j + 1]; ++i) {
      serial_hits_.clear();
      run_chunk(jobs[j], pieces_[i].begin, pieces_[i].end, serial_hits_, hits, cursor_of(pieces_[i]));
      append_records(serial_hits_, 0, jobs[j].tag, out);
      if (jobs[j].mode == Mode::First && hits) break;
    }
    push_record(out, Record::Done, jobs[j].tag).hits = hits;
  }
  if (cycles) annotate(jobs, out);
}

void FastRunner::annotate(const std::vector<Job>& jobs, std::vector<Record>& out) const {
  // annotate_cycles with the batch's slots (a sparse shell's from make_pieces' walk of its words) and, on a banked
  // device, each job's bank cycles.
  JobSpan prev;
  size_t r = 0;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const size_t first = r;
    while (out[r].kind == Record::Hit) ++r;
    const JobHits h = job_hits(batch_slots_[j], jobs[j], j, out.data() + first, r - first, first);
    Record& done = out[r++];
    const BankCycles bank =
        cfg_.banked() ? job_bank_cycles(cfg_, shell_, map_, jobs[j], h, done.hits) : BankCycles{};
    const JobSpan span = job_span(cfg_, jobs[j], batch_slots_[j], j, h, done.hits, bank);
    done.cycles = span_cycles(cfg_, j ? &prev : nullptr, span);
    done.points = span.points;
    done.stalls = 0;
    prev = span;
  }
}

void FastRunner::run_tasks(const std::vector<Job>& jobs, bool cycles, bool validate) {
  // Tasks: runs of consecutive pieces of at least kTaskPoints points.
  task_first_.clear();
  for (size_t i = 0, acc = kTaskPoints; i < pieces_.size(); ++i) {
    if (acc >= kTaskPoints) task_first_.push_back(i), acc = 0;
    acc += pieces_[i].end - pieces_[i].begin;
  }
  task_first_.push_back(pieces_.size());
  const size_t tasks = task_first_.size() - 1;
  if (results_.size() < tasks) results_.resize(tasks);
  // Each task validates a job before its first piece of it (the task holding a job's first piece validates it
  // before any piece of a later job), and the jobs of no points before it (the first task also those before its
  // first job, the last those after its last), so the lowest task that throws, whose exception the pool rethrows,
  // names the first invalid job, as run_serial would. The lookups only read the memories, and `out` is not touched
  // before every task has finished.
  pool_->parallel_for(tasks, [&](size_t t) {
    std::vector<Record>& hits = results_[t].hits;
    HitColumns& cols = results_[t].columns;
    hits.clear();
    size_t validated = SIZE_MAX, next = t == 0 ? 0 : pieces_[task_first_[t] - 1].job + 1;
    auto check = [&](size_t j) { validate_job(cfg_, jobs[j], shell_.size(), map_.size()); };
    for (size_t i = task_first_[t]; i < task_first_[t + 1]; ++i) {
      Piece& p = pieces_[i];
      const Job& j = jobs[p.job];
      if (validate) {
        for (; next < p.job; ++next) check(next);
        if (validated != p.job) check(p.job), validated = p.job;
        next = std::max(next, p.job + 1);
      }
      p.task = t;
      p.first = hits.size();
      p.count = 0;
      cols.clear();
      run_chunk(j, p.begin, p.end, cols, p.count, cursor_of(p));
      append_records(cols, 0, j.tag, hits);
      p.records = hits.size() - p.first;
      if (cycles) p.sum = job_hits(batch_slots_[p.job], j, p.job, hits.data() + p.first, p.records);
    }
    if (validate && t + 1 == tasks)
      for (; next < jobs.size(); ++next) check(next);
  });
}

size_t FastRunner::place_records(const std::vector<Job>& jobs) {
  // Where each piece's records go: ALL every one, FIRST only those of the job's first piece with a hit; then the
  // completion record.
  size_t total = 0;
  done_at_.resize(jobs.size());
  for (size_t j = 0; j < jobs.size(); ++j) {
    bool found = false;
    for (size_t i = first_piece_[j]; i < first_piece_[j + 1]; ++i) {
      Piece& p = pieces_[i];
      if (jobs[j].mode == Mode::First) {
        if (found || p.count == 0) p.records = 0;
        else found = true;
      }
      p.out = total;
      total += p.records;
    }
    done_at_[j] = total++;
  }
  return total;
}

void FastRunner::job_result(const std::vector<Job>& jobs, size_t j, bool cycles, uint32_t& hits, JobHits& sum) const {
  hits = 0;
  sum = JobHits();  // none yet: the group sentinels of job_hits
  sum.first_group = sum.last_group = batch_slots_[j].groups;
  for (size_t i = first_piece_[j]; i < first_piece_[j + 1]; ++i) {
    const Piece& p = pieces_[i];
    if (jobs[j].mode == Mode::First) {
      if (p.records) hits = 1, sum = p.sum;
    } else {
      hits += p.count;
      if (cycles) sum = join_job_hits(sum, p.sum);
    }
  }
}

// Task t copies its pieces' kept records to their places and writes the completion records of the jobs from its
// first piece's to the next task's (the first task also those before, the last those after: jobs of no points have no
// pieces), with their cycles. A job's cycles need only its own span and the previous job's (ref/timing.h), so every
// task times its jobs apart; a banked device's conflict cycles of a job come from its slots' addresses (ref/banks.h).
void FastRunner::finish_task(size_t t, const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles) const {
  const size_t tasks = task_first_.size() - 1;
  const std::vector<Record>& hits = results_[t].hits;
  for (size_t i = task_first_[t]; i < task_first_[t + 1]; ++i) {
    const Piece& p = pieces_[i];
    std::copy(hits.begin() + std::ptrdiff_t(p.first), hits.begin() + std::ptrdiff_t(p.first + p.records),
              out.begin() + std::ptrdiff_t(p.out));
  }
  auto conflicts = [&](const Job& job, const JobHits& sum, uint32_t n) -> BankCycles {
    return cfg_.banked() ? job_bank_cycles(cfg_, shell_, map_, job, sum, n) : BankCycles{};
  };
  const size_t j0 = t == 0 ? 0 : pieces_[task_first_[t]].job;
  const size_t j1 = t + 1 == tasks ? jobs.size() : pieces_[task_first_[t + 1]].job;
  JobSpan prev;
  for (size_t j = j0; j < j1; ++j) {
    uint32_t n = 0;
    JobHits sum;
    job_result(jobs, j, cycles, n, sum);
    Record& done = out[done_at_[j]];
    done = Record();
    done.kind = Record::Done;
    done.tag = jobs[j].tag;
    done.hits = n;
    if (!cycles) continue;
    if (j == j0 && j > 0) {
      uint32_t pn = 0;
      JobHits psum;
      job_result(jobs, j - 1, cycles, pn, psum);
      prev = job_span(cfg_, jobs[j - 1], batch_slots_[j - 1], j - 1, psum, pn, conflicts(jobs[j - 1], psum, pn));
    }
    const JobSpan span = job_span(cfg_, jobs[j], batch_slots_[j], j, sum, n, conflicts(jobs[j], sum, n));
    done.cycles = span_cycles(cfg_, j > 0 ? &prev : nullptr, span);
    done.points = span.points;
    done.stalls = 0;
    prev = span;
  }
}

void FastRunner::run_jobs(const std::vector<Job>& jobs, std::vector<Record>& out, bool cycles, bool validate) {
  const size_t points = make_pieces(jobs);
  if (pieces_.size() <= 1 || !pool_ || pool_->size() <= 1 || points < kParallelMinPoints)
    return run_serial(jobs, out, cycles, validate);
  run_tasks(jobs, cycles, validate);
  const size_t total = place_records(jobs);
  // Records are trivially destructible: shrinking `out` to the total costs nothing, and growing it constructs only
  // the new ones. Every record is written by finish_task.
  out.resize(total);
  // On the pool when there is enough to share (a copy of 4,096 records takes about 5 us, a job's completion about
  // 0.1 us).
  const size_t tasks = task_first_.size() - 1;
  if (total - jobs.size() >= kParallelMinPoints || jobs.size() >= 64) {
    pool_->parallel_for(tasks, [&](size_t t) { finish_task(t, jobs, out, cycles); });
  } else {
    for (size_t t = 0; t < tasks; ++t) finish_task(t, jobs, out, cycles);
  }
}

namespace {
// The voxels of n points' linear indices (-1: outside the map) fetched, selected and tested without branches
// (outside points read the map's first word and are masked): state[k] bits 1:0 the state, bit 2 the hit; the hits.
inline uint32_t fetch_states(const uint64_t* map, int slot_bits, uint32_t hit_mask, const int64_t* lin, size_t n,
                             uint8_t* state) {
  const uint64_t slot_mask = (uint64_t{1} << slot_bits) - 1;
  uint32_t count = 0;
  for (size_t k = 0; k < n; ++k) {
    const bool inside = lin[k] >= 0;
    const uint64_t li = inside ? uint64_t(lin[k]) : 0;
    const uint32_t st = uint32_t(map[li >> slot_bits] >> (2 * (li & slot_mask))) & 3u;
    const uint32_t hit = uint32_t(inside) & (hit_mask >> st) & 1u;
    state[k] = uint8_t(st | (hit << 2));
    count += hit;
  }
  return count;
}
}  // namespace

detail::ShellArrays FastRunner::shell_arrays() const {
  detail::ShellArrays a{shell_.data(), nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};
  if (path_ == Path::Double) a.sx = sx_.data(), a.sy = sy_.data(), a.sz = sz_.data();
  if (keep_int64_) a.ix = ix_.data(), a.iy = iy_.data(), a.iz = iz_.data();
  return a;
}

namespace {

// The 2-bit lookups of a block of a job's points on a dense map, on every path: the fused kernel (transform to state in
// one loop) where the doubles are exact and the map below 2^31 voxels, else the linear indices (int64 or ref/'s
// 128-bit stages) and then the fetch. Returns true when FIRST has its hit.
struct TwoBitBlocks {
  const DeviceConfig& cfg;
  const Job& j;
  FastRunner::Path path;
  bool fused;
  int slot_bits;
  const uint64_t* map;
  HitColumns& hits;
  uint32_t& hit_count;
  double ms[9], ts[3], dims[3];
  int64_t lin[kBlock];
  int32_t cx[kBlock], cy[kBlock], cz[kBlock];
  uint8_t state[kBlock];  // bits 1:0 the state, bit 2 the hit

  TwoBitBlocks(const DeviceConfig& c, const Job& job, FastRunner::Path p, double tf_scale, int bits,
               const uint64_t* memory, HitColumns& h, uint32_t& count)
      : cfg(c), j(job), path(p), fused(p == FastRunner::Path::Double && job.voxels() < (uint64_t{1} << 31)),
        slot_bits(bits), map(memory + job.map_base), hits(h), hit_count(count),
        dims{double(job.nx), double(job.ny), double(job.nz)} {
    // The fused kernel takes M and t already scaled by 2^-TF: scaling by a power of two is exact, and so is every
    // product and sum after it (multiples of 2^-TF below 2^(53-TF)).
    if (!fused) return;
    for (int i = 0; i < 9; ++i) ms[i] = double(job.M[i / 3][i % 3]) * tf_scale;
    for (int i = 0; i < 3; ++i) ts[i] = double(job.t[i]) * tf_scale;
  }
  // The forms of the points the path reads (detail::PointBlocks::Need).
  unsigned need() const {
    return fused ? detail::PointBlocks::kInt32
                 : path == FastRunner::Path::Wide ? detail::PointBlocks::kWords : detail::PointBlocks::kInt64;
  }

  bool operator()(uint32_t b, size_t n, const detail::BlockCoords& c) {
    if (fused) {
      const uint32_t count = block_fetch.fn(c.x, c.y, c.z, n, ms, ts, dims, map, slot_bits, j.hit_mask, cx, cy, cz,
                                            state);
      if (count == 0) return false;
      if (j.mode == Mode::Count) return hit_count += count, false;
      return emit_cells(j, b, n, cx, cy, cz, state, count, hits, hit_count);
    }
    if (path == FastRunner::Path::Wide) {
      for (size_t k = 0; k < n; ++k) {
        const Located l = locate(cfg, j, transform(cfg, j, c.w[k]));
        lin[k] = l.inside ? int64_t(l.linear) : -1;
      }
    } else {  // int64, or the double path's maps of 2^31 voxels or more (the accumulator fits 53 bits)
      block_int64(c.ix, c.iy, c.iz, n, j, cfg.TF(), lin);
    }
    // Then walk only the hits.
    const uint32_t count = fetch_states(map, slot_bits, j.hit_mask, lin, n, state);
    if (count == 0) return false;
    if (j.mode == Mode::Count) return hit_count += count, false;
    return emit_hits(j, b, n, lin, state, count, hits, hit_count);
  }
};

}  // namespace

void FastRunner::run_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits, uint32_t& hit_count,
                           const detail::ShellCursor* at) const {
  if (j.sparse_map()) return run_sparse_chunk(j, begin, end, hits, hit_count, at);
  if (cfg_.distance()) return run_distance_chunk(j, begin, end, hits, hit_count, at);
  if (j.sparse_shell()) return run_sparse_shell_chunk(j, begin, end, hits, hit_count, at);
  TwoBitBlocks block(cfg_, j, path_, tf_scale_, slot_bits_, map_.data(), hits, hit_count);
  // A dense shell's words where the path keeps them (a batch may hold many small jobs: nothing more per block).
  detail::BlockCoords c;
  size_t n = 0;
  for (uint32_t b = begin; b < end; b += uint32_t(n)) {
    n = std::min<size_t>(kBlock, end - b);
    const size_t base = size_t(j.shell_base) + b;
    if (block.fused) c.x = &sx_[base], c.y = &sy_[base], c.z = &sz_[base];
    else if (path_ == Path::Wide) c.w = &shell_[base];
    else c.ix = &ix_[base], c.iy = &iy_[base], c.iz = &iz_[base];
    if (block(b, n, c)) return;
  }
}

void FastRunner::run_sparse_shell_chunk(const Job& j, uint32_t begin, uint32_t end, HitColumns& hits,
                                        uint32_t& hit_count, const detail::ShellCursor* at) const {
  TwoBitBlocks block(cfg_, j, path_, tf_scale_, slot_bits_, map_.data(), hits, hit_count);
  detail::sparse_shell_blocks(cfg_, shell_arrays(), j, begin, end, at, block.need(), kBlock, block);
}

}  // namespace voxcd
