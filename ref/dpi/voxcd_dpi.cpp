// The DPI-C reference device (voxcd_dpi.h): ref/'s pipeline and cycle model behind C functions with standard DPI
// types. Every function catches what ref/ throws and keeps the message for voxcd_dpi_error.
#include "voxcd_dpi.h"

#include <cstdint>
#include <deque>
#include <exception>
#include <initializer_list>
#include <iterator>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/error.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"

namespace {

using namespace voxcd;

// An argument or a call that the reference refuses; the message is the whole text voxcd_dpi_error returns.
struct DpiError : Error {
  using Error::Error;
};

// Addresses written so far, as disjoint half-open intervals [first, second), merged when they touch.
class Written {
 public:
  void add(uint64_t a) {
    auto next = runs_.upper_bound(a);
    if (next != runs_.begin()) {
      auto prev = std::prev(next);
      if (prev->second > a) return;  // already written
      if (prev->second == a) {
        prev->second = a + 1;
        if (next != runs_.end() && next->first == a + 1) {
          prev->second = next->second;
          runs_.erase(next);
        }
        return;
      }
    }
    uint64_t end = a + 1;
    if (next != runs_.end() && next->first == a + 1) {
      end = next->second;
      runs_.erase(next);
    }
    runs_.emplace(a, end);
  }
  // The first address of [lo, hi) never written, or nothing when all were.
  std::optional<uint64_t> first_gap(uint64_t lo, uint64_t hi) const {
    if (lo >= hi) return std::nullopt;
    auto next = runs_.upper_bound(lo);
    if (next == runs_.begin()) return lo;
    const uint64_t end = std::prev(next)->second;
    if (end <= lo) return lo;
    if (end >= hi) return std::nullopt;
    return end;
  }

 private:
  std::map<uint64_t, uint64_t> runs_;
};

constexpr uint64_t kMagic = 0x766f7863645f6470;  // "voxcd_dp" marks a live device (a freed one has 0)

struct Device {
  uint64_t magic = kMagic;
  DeviceConfig cfg;
  std::string cfg_text;
  std::string error;

  DeviceMemory mem;  // sized to one past the highest address written
  Written shell_written, map_written;

  std::deque<Record> expected;
  uint64_t jobs = 0;
  // The previous job and its records: the cycle model gives a job's cycles from it and the job alone
  // (job_timing of the pair; see next_timing).
  std::optional<Job> prev_job;
  std::vector<Record> prev_records;

  std::optional<GeneratedVectors> gen;
};

std::string g_error;  // of voxcd_dpi_new and of calls given no device

Device* device(void* h, const char* fn) {
  auto* d = static_cast<Device*>(h);
  if (!d) throw DpiError(std::string(fn) + ": the handle is null (voxcd_dpi_new failed or was not called)");
  if (d->magic != kMagic) throw DpiError(std::string(fn) + ": the handle is not a voxcd_dpi device");
  return d;
}

// Keeps a failed call's message on its device, or globally when it has none.
void keep_error(void* h, const char* msg) noexcept {
  try {
    auto* d = static_cast<Device*>(h);
    (d && d->magic == kMagic ? d->error : g_error) = msg;
  } catch (...) {  // no memory for the message: the call still fails
  }
}

// Runs `body`, turning any exception into `fail` and keeping its message.
template <class T, class Body>
T guarded(void* h, T fail, Body&& body) noexcept {
  try {
    return body();
  } catch (const std::exception& e) {
    keep_error(h, e.what());
  } catch (...) {
    keep_error(h, "voxcd_dpi: an unknown exception");
  }
  return fail;
}

uint64_t address(const char* fn, const char* what, int addr, uint64_t depth, const char* depth_name) {
  if (addr < 0 || uint64_t(addr) >= depth)
    throw DpiError(std::string(fn) + ": " + what + " address " + std::to_string(addr) + " is outside 0.." +
                   std::to_string(depth - 1) + " (" + depth_name + ")");
  return uint64_t(addr);
}

// One output argument of a DPI function and the value it gets: an int output takes the value's low 32 bits.
struct Out {
  template <class T>
  Out(int* p, T v) : i(p), value(int64_t(v)) {}
  template <class T>
  Out(long long* p, T v) : ll(p), value(int64_t(v)) {}
  int* i = nullptr;
  long long* ll = nullptr;
  int64_t value;
};

// Writes each value to its output; a null output is left out.
void set_outs(std::initializer_list<Out> outs) {
  for (const Out& o : outs) {
    if (o.i) *o.i = int(uint32_t(uint64_t(o.value)));
    if (o.ll) *o.ll = static_cast<long long>(o.value);
  }
}

std::string job_name(const Job& j) { return "job tag " + std::to_string(j.tag); }

// Cycles and points of `job` (records `recs`), following d.prev_job back to back or starting a stream. In the
// model a job's completion time is linear in the cycle its first slot reaches the hit test, and that cycle moves
// by an amount fixed by the previous job alone; so job_timing over the pair gives the second job's cycles exactly
// as over the whole stream (tests/ref/dpi/test_dpi_api.cpp checks both on long random streams).
JobTiming next_timing(const Device& d, const Job& job, const std::vector<Record>& recs) {
  if (!d.prev_job) return job_timing(d.cfg, d.mem, {job}, recs).at(0);
  std::vector<Record> pair = d.prev_records;
  pair.insert(pair.end(), recs.begin(), recs.end());
  return job_timing(d.cfg, d.mem, {*d.prev_job, job}, pair).at(1);
}

}  // namespace

extern "C" {

void* voxcd_dpi_new(const char* pairs) {
  return guarded<void*>(nullptr, nullptr, [&]() -> void* {
    const std::string text = pairs ? pairs : "";
    DeviceConfig cfg;
    try {
      cfg = parse_config_pairs(text, "voxcd_dpi_new(\"" + text + "\")");
    } catch (const std::exception& e) {
      throw DpiError(e.what());
    }
    auto* d = new Device;
    d->cfg = cfg;
    d->cfg_text = cfg.to_string();
    return d;
  });
}

void voxcd_dpi_free(void* h) {
  auto* d = static_cast<Device*>(h);
  if (!d || d->magic != kMagic) return;
  d->magic = 0;
  delete d;
}

const char* voxcd_dpi_error(void* h) {
  auto* d = static_cast<Device*>(h);
  if (!d || d->magic != kMagic) return g_error.c_str();
  return d->error.c_str();
}

int voxcd_dpi_param(void* h, const char* name) {
  return guarded(h, -1, [&] {
    const Device* d = device(h, "voxcd_dpi_param");
    const std::string n = name ? name : "";
    const DeviceConfig& c = d->cfg;
    const std::pair<const char*, int> params[] = {{"PW", c.PW},     {"PF", c.PF},       {"MW", c.MW},
                                                  {"MF", c.MF},     {"TW", c.TW},       {"DW", c.DW},
                                                  {"MEMW", c.MEMW}, {"LANES", c.LANES}, {"SAW", c.SAW},
                                                  {"MAW", c.MAW},   {"TAGW", c.TAGW},   {"SB", c.SB},
                                                  {"WB", c.WB},     {"BANKS", c.BANKS}, {"DEPTH", c.depth},
                                                  {"BL", c.BL},     {"IW", c.IW()}};
    for (const auto& p : params)
      if (n == p.first) return p.second;
    throw DpiError("voxcd_dpi_param: no parameter named '" + n +
                   "' (PW, PF, MW, MF, TW, DW, MEMW, LANES, SAW, MAW, TAGW, SB, WB, BANKS, DEPTH, BL, IW)");
  });
}

const char* voxcd_dpi_config(void* h) {
  return guarded<const char*>(h, "", [&] { return device(h, "voxcd_dpi_config")->cfg_text.c_str(); });
}

int voxcd_dpi_write_shell(void* h, int addr, long long x, long long y, long long z) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_write_shell";
    Device* d = device(h, fn);
    const uint64_t a = address(fn, "shell", addr, d->cfg.shell_depth(), "2^SAW words");
    const long long v[3] = {x, y, z};
    for (int i = 0; i < 3; ++i)
      if (!fits_signed(v[i], d->cfg.PW))
        throw DpiError(std::string(fn) + ": shell word " + std::to_string(a) + ": " + "xyz"[i] + " = " +
                       std::to_string(v[i]) + " does not fit PW = " + std::to_string(d->cfg.PW) + " bits (signed)");
    if (d->mem.shell.size() <= a) d->mem.shell.resize(a + 1);
    d->mem.shell[a] = ShellWord{x, y, z};
    d->shell_written.add(a);
    return 0;
  });
}

int voxcd_dpi_write_map(void* h, int addr, long long word) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_write_map";
    Device* d = device(h, fn);
    const uint64_t a = address(fn, "voxmap", addr, d->cfg.map_depth(), "2^MAW words");
    const uint64_t w = uint64_t(word);
    if (d->cfg.MEMW < 64 && (w >> d->cfg.MEMW) != 0)
      throw DpiError(std::string(fn) + ": voxmap word " + std::to_string(a) + " = " + std::to_string(w) +
                     " has bits above MEMW = " + std::to_string(d->cfg.MEMW));
    if (d->mem.map.size() <= a) d->mem.map.resize(a + 1);
    d->mem.map[a] = w;
    d->map_written.add(a);
    return 0;
  });
}

}  // extern "C"

namespace {

// The words job j reads that were never written: the first of them named, or nothing.
void require_written(const Device& d, const char* fn, const Job& j) {
  const DeviceConfig& c = d.cfg;
  const uint64_t map_end = uint64_t(j.map_base) + map_words(c, j);
  if (auto gap = d.shell_written.first_gap(j.shell_base, uint64_t(j.shell_base) + j.shell_count))
    throw DpiError(std::string(fn) + ": " + job_name(j) + " reads shell words [" + std::to_string(j.shell_base) +
                   ", " + std::to_string(uint64_t(j.shell_base) + j.shell_count) + "), and word " +
                   std::to_string(*gap) + " was never written (voxcd_dpi_write_shell)");
  if (auto gap = d.map_written.first_gap(j.map_base, map_end))
    throw DpiError(std::string(fn) + ": " + job_name(j) + " reads voxmap words [" + std::to_string(j.map_base) +
                   ", " + std::to_string(map_end) + "), and word " + std::to_string(*gap) +
                   " was never written (voxcd_dpi_write_map)");
  if (!j.sparse_map()) return;
  const uint64_t bricks_end = uint64_t(j.brick_base) + brick_words(c, j);
  if (auto gap = d.map_written.first_gap(j.brick_base, bricks_end))
    throw DpiError(std::string(fn) + ": " + job_name(j) + " reads brick words [" + std::to_string(j.brick_base) +
                   ", " + std::to_string(bricks_end) + "), and word " + std::to_string(*gap) +
                   " was never written (voxcd_dpi_write_map)");
}

// The job of a submit call's fields (mode and mask checked here; the rest by validate_job).
struct JobFields {
  int tag, mode, mask, shell_base, shell_count, map_base, nx, ny, nz;
  long long m[3][3], t[3], threshold;
  int sparse, brick_base, brick_units;
};
Job job_of(const char* fn, const JobFields& f) {
  Job j;
  j.tag = uint32_t(f.tag);
  if (f.mode < 0 || f.mode > 2)
    throw DpiError(std::string(fn) + ": " + job_name(j) + ": mode " + std::to_string(f.mode) +
                   " is not 0 (ALL), 1 (FIRST) or 2 (COUNT)");
  if (f.mask < 0 || f.mask > 15)
    throw DpiError(std::string(fn) + ": " + job_name(j) + ": hit mask " + std::to_string(f.mask) + " is outside 0..15");
  if (f.sparse < 0 || f.sparse > 3)
    throw DpiError(std::string(fn) + ": " + job_name(j) + ": sparse " + std::to_string(f.sparse) +
                   " is outside 0..3 (1: the map, 2: the shell)");
  j.mode = Mode(f.mode);
  j.hit_mask = uint8_t(f.mask);
  j.shell_base = uint32_t(f.shell_base), j.shell_count = uint32_t(f.shell_count), j.map_base = uint32_t(f.map_base);
  j.nx = uint32_t(f.nx), j.ny = uint32_t(f.ny), j.nz = uint32_t(f.nz);
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k) j.M[r][k] = f.m[r][k];
  for (int i = 0; i < 3; ++i) j.t[i] = f.t[i];
  j.threshold = f.threshold;
  j.sparse = uint8_t(f.sparse);
  j.brick_base = uint32_t(f.brick_base), j.brick_units = uint32_t(f.brick_units);
  return j;
}

// The job of the fields, validated against the whole memories and the words written, run, and its records queued
// with their cycles; returns their number.
int submit_job(Device& d, const char* fn, const JobFields& f) {
  const DeviceConfig& c = d.cfg;
  const Job j = job_of(fn, f);
  try {
    validate_job(c, j, c.shell_depth(), c.map_depth());
  } catch (const std::exception& e) {
    throw DpiError(std::string(fn) + ": " + e.what());
  }
  require_written(d, fn, j);
  std::vector<Record> recs;
  run_job(c, d.mem, j, recs);
  const JobTiming t = next_timing(d, j, recs);
  Record& done = recs.back();
  done.cycles = t.cycles;
  done.points = t.points;
  done.stalls = 0;
  d.expected.insert(d.expected.end(), recs.begin(), recs.end());
  d.prev_job = j;
  d.prev_records = std::move(recs);
  ++d.jobs;
  return int(d.prev_records.size());
}

}  // namespace

extern "C" {

int voxcd_dpi_submit(void* h, int tag, int mode, int mask, int shell_base, int shell_count, int map_base, int nx,
                     int ny, int nz, long long m00, long long m01, long long m02, long long m10, long long m11,
                     long long m12, long long m20, long long m21, long long m22, long long t0, long long t1,
                     long long t2, long long threshold) {
  const JobFields f{tag,  mode, mask, shell_base, shell_count, map_base, nx, ny, nz,
                    {{m00, m01, m02}, {m10, m11, m12}, {m20, m21, m22}},
                    {t0, t1, t2}, threshold, 0, 0, 0};
  return guarded(h, -1, [&] { return submit_job(*device(h, "voxcd_dpi_submit"), "voxcd_dpi_submit", f); });
}

int voxcd_dpi_submit_sparse(void* h, int tag, int mode, int mask, int shell_base, int shell_count, int map_base,
                            int nx, int ny, int nz, long long m00, long long m01, long long m02, long long m10,
                            long long m11, long long m12, long long m20, long long m21, long long m22, long long t0,
                            long long t1, long long t2, long long threshold, int sparse, int brick_base,
                            int brick_units) {
  const JobFields f{tag,  mode, mask, shell_base, shell_count, map_base, nx, ny, nz,
                    {{m00, m01, m02}, {m10, m11, m12}, {m20, m21, m22}},
                    {t0, t1, t2}, threshold, sparse, brick_base, brick_units};
  const char* fn = "voxcd_dpi_submit_sparse";
  return guarded(h, -1, [&] { return submit_job(*device(h, fn), fn, f); });
}

int voxcd_dpi_pop(void* h, int* tag, int* point, int* x, int* y, int* z, int* state, int* hits, long long* cycles,
                  long long* points, long long* distance) {
  return guarded(h, -1, [&] {
    Device* d = device(h, "voxcd_dpi_pop");
    if (d->expected.empty()) return VOXCD_DPI_NONE;
    const Record r = d->expected.front();
    d->expected.pop_front();
    set_outs({{tag, r.tag}, {point, r.point}, {x, r.x}, {y, r.y}, {z, r.z}, {state, r.state}, {hits, r.hits},
              {cycles, r.cycles.value_or(0)}, {points, r.points.value_or(0)}, {distance, r.dist}});
    return r.kind == Record::Hit ? VOXCD_DPI_HIT : VOXCD_DPI_DONE;
  });
}

int voxcd_dpi_pending(void* h) {
  return guarded(h, -1, [&] { return int(device(h, "voxcd_dpi_pending")->expected.size()); });
}

int voxcd_dpi_jobs(void* h) {
  return guarded(h, -1, [&] { return int(device(h, "voxcd_dpi_jobs")->jobs); });
}

int voxcd_dpi_restart(void* h) {
  return guarded(h, -1, [&] {
    Device* d = device(h, "voxcd_dpi_restart");
    d->prev_job.reset();
    d->prev_records.clear();
    return 0;
  });
}

int voxcd_dpi_generate(void* h, long long seed, int jobs, int cloud_points) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_generate";
    Device* d = device(h, fn);
    if (jobs < 0) throw DpiError(std::string(fn) + ": jobs = " + std::to_string(jobs) + " is negative");
    if (cloud_points < 0)
      throw DpiError(std::string(fn) + ": cloud_points = " + std::to_string(cloud_points) + " is negative");
    GenerateOptions opt;
    opt.seed = uint64_t(seed);
    opt.jobs = size_t(jobs);
    opt.cloud_points = size_t(cloud_points);
    opt.config = d->cfg;
    try {
      d->gen = generate_vectors(opt);
    } catch (const std::exception& e) {
      throw DpiError(std::string(fn) + ": " + e.what());
    }
    return 0;
  });
}

namespace {
const GeneratedVectors& generated(const Device* d, const char* fn) {
  if (!d->gen) throw DpiError(std::string(fn) + ": nothing generated yet (call voxcd_dpi_generate first)");
  return *d->gen;
}
size_t index_in(const char* fn, const char* what, int i, size_t n) {
  if (i < 0 || size_t(i) >= n)
    throw DpiError(std::string(fn) + ": " + what + " " + std::to_string(i) + " is outside the generated 0.." +
                   std::to_string(int64_t(n) - 1));
  return size_t(i);
}
}  // namespace

int voxcd_dpi_gen_shell_words(void* h) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_gen_shell_words";
    return int(generated(device(h, fn), fn).memory.shell.size());
  });
}

int voxcd_dpi_gen_map_words(void* h) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_gen_map_words";
    return int(generated(device(h, fn), fn).memory.map.size());
  });
}

int voxcd_dpi_gen_jobs(void* h) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_gen_jobs";
    return int(generated(device(h, fn), fn).jobs.size());
  });
}

int voxcd_dpi_gen_shell(void* h, int addr, long long* x, long long* y, long long* z) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_gen_shell";
    const GeneratedVectors& g = generated(device(h, fn), fn);
    const ShellWord& w = g.memory.shell[index_in(fn, "shell address", addr, g.memory.shell.size())];
    set_outs({{x, w.x}, {y, w.y}, {z, w.z}});
    return 0;
  });
}

int voxcd_dpi_gen_map(void* h, int addr, long long* word) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_gen_map";
    const GeneratedVectors& g = generated(device(h, fn), fn);
    set_outs({{word, g.memory.map[index_in(fn, "voxmap address", addr, g.memory.map.size())]}});
    return 0;
  });
}

int voxcd_dpi_gen_job(void* h, int index, int* tag, int* mode, int* mask, int* shell_base, int* shell_count,
                      int* map_base, int* nx, int* ny, int* nz, long long* m00, long long* m01, long long* m02,
                      long long* m10, long long* m11, long long* m12, long long* m20, long long* m21,
                      long long* m22, long long* t0, long long* t1, long long* t2, long long* threshold) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_gen_job";
    const GeneratedVectors& g = generated(device(h, fn), fn);
    const Job& j = g.jobs[index_in(fn, "job", index, g.jobs.size())];
    set_outs({{tag, j.tag}, {mode, uint64_t(j.mode)}, {mask, j.hit_mask}, {shell_base, j.shell_base},
              {shell_count, j.shell_count}, {map_base, j.map_base}, {nx, j.nx}, {ny, j.ny}, {nz, j.nz}});
    set_outs({{m00, j.M[0][0]}, {m01, j.M[0][1]}, {m02, j.M[0][2]}, {m10, j.M[1][0]}, {m11, j.M[1][1]},
              {m12, j.M[1][2]}, {m20, j.M[2][0]}, {m21, j.M[2][1]}, {m22, j.M[2][2]}});
    set_outs({{t0, j.t[0]}, {t1, j.t[1]}, {t2, j.t[2]}, {threshold, j.threshold}});
    return 0;
  });
}

int voxcd_dpi_gen_job_sparse(void* h, int index, int* sparse, int* brick_base, int* brick_units) {
  return guarded(h, -1, [&] {
    const char* fn = "voxcd_dpi_gen_job_sparse";
    const GeneratedVectors& g = generated(device(h, fn), fn);
    const Job& j = g.jobs[index_in(fn, "job", index, g.jobs.size())];
    set_outs({{sparse, j.sparse}, {brick_base, j.brick_base}, {brick_units, j.brick_units}});
    return 0;
  });
}

}  // extern "C"
