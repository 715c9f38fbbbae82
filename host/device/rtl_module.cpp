// The rtl backend's module (host/device/detail/rtl_module.h): the Verilated device (rtl/voxcd_device.sv) driven
// through its pins, cycle by cycle, one class template over every model of rtl/CMakeLists.txt. Built with the models
// (voxcd_rtl_backend, part of voxcd_models), never into the host library, which loads it when the rtl backend is
// first used.
#include <verilated.h>
#include <verilated_fst_c.h>

#include <random>
#include <string>
#include <type_traits>

#include "voxcd/host/device/detail/rtl_module.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vectors.h"
#include "voxcd_rtl_abi.h"  // VOXCD_RTL_MODULE_ABI (host/device/rtl_abi.cmake)
// Every model with its family and configuration (rtl/CMakeLists.txt): voxcd_rtl_models.h, or the coverage models'
// header for the coverage module (voxcd_rtl_cov_backend, whose models count coverage: VM_COVERAGE).
#ifdef VOXCD_RTL_MODELS_HEADER
#include VOXCD_RTL_MODELS_HEADER
#else
#include "voxcd_rtl_models.h"
#endif
#if VM_COVERAGE
#include <verilated_cov.h>

#include <fstream>
#endif

namespace voxcd {
namespace {

// Writes `width` bits of v at bit `lsb` of a Verilator port (an integer or a VlWide).
template <class T>
void put_bits(T& port, int lsb, int width, uint64_t v) {
  const uint64_t mask = width >= 64 ? ~uint64_t{0} : (uint64_t{1} << width) - 1;
  port = T((uint64_t(port) & ~(mask << lsb)) | ((v & mask) << lsb));
}
template <std::size_t N>
void put_bits(VlWide<N>& port, int lsb, int width, uint64_t v) {
  for (int b = 0; b < width; ++b) {
    const int bit = lsb + b;
    const uint32_t m = uint32_t{1} << (bit % 32);
    if ((v >> b) & 1u)
      port[bit / 32] |= m;
    else
      port[bit / 32] &= ~m;
  }
}

template <class T>
T masked(int64_t v, int width) {
  const uint64_t mask = width >= 64 ? ~uint64_t{0} : (uint64_t{1} << width) - 1;
  return T(uint64_t(v) & mask);
}

// The signed value of the low `width` bits of v.
int64_t sign_extend(uint64_t v, int width) {
  if (width >= 64) return int64_t(v);
  const uint64_t sign = uint64_t{1} << (width - 1);
  v &= (sign << 1) - 1;
  return int64_t(v ^ sign) - int64_t(sign);
}

template <class Model>
class RtlDevice final : public Device {
 public:
  RtlDevice(const DeviceConfig& cfg, const DeviceOptions& opt, const RtlFaults& faults)
      : cfg_(cfg), opt_(opt), faults_(faults), stall_rng_(opt.stall_seed) {
    ctx_ = std::make_unique<VerilatedContext>();
    ctx_->fatalOnError(false);  // an assertion in the RTL becomes a DeviceError here, not an abort
    if (!opt_.trace_path.empty()) ctx_->traceEverOn(true);
#ifdef VOXCD_RTL_RANDOM_POWER_UP
    // Models Verilated with --x-initial unique power up with random register values (bench/mutation): the outputs
    // after reset must not depend on them.
    ctx_->randReset(2);
    ctx_->randSeed(int(opt_.stall_seed % 0x7fffffff) + 1);
#endif
    model_ = std::make_unique<Model>(ctx_.get(), "voxcd");
    if (!opt_.trace_path.empty()) {
      trace_ = std::make_unique<VerilatedFstC>();
      model_->trace(trace_.get(), 99);
      trace_->open(opt_.trace_path.c_str());
      if (!trace_->isOpen()) throw DeviceError("rtl: cannot open trace file " + opt_.trace_path);
    }
    open_coverage();
    reset();
  }
  ~RtlDevice() override {
    // The model's scopes unregister from the calling thread's current context: make that this model's own, as
    // another device may have been used since.
    Verilated::threadContextp(ctx_.get());
    model_->final();
    if (trace_) trace_->close();
#if VM_COVERAGE
    if (!opt_.coverage_path.empty()) ctx_->coveragep()->write(opt_.coverage_path.c_str());
#endif
    model_.reset();
  }

  std::string name() const override { return "rtl"; }
  const DeviceConfig& config() const override { return cfg_; }
  bool models_cycles() const override { return true; }

  void load(const DeviceMemory& mem) override {
    validate_memory(cfg_, mem);
    enter();
    Model& m = *model_;
    const size_t n = std::max(mem.shell.size(), mem.map.size());
    for (size_t k = 0; k < n; ++k) {
      m.shell_we_i = k < mem.shell.size();
      if (m.shell_we_i) {
        m.shell_waddr_i = uint32_t(k);
        const ShellWord& p = mem.shell[k];
        for (int i = 0; i < 3; ++i) put_bits(m.shell_wdata_i, i * cfg_.PW, cfg_.PW, uint64_t(p[i]));
      }
      m.map_we_i = k < mem.map.size();
      if (m.map_we_i) {
        m.map_waddr_i = uint32_t(k);
        m.map_wdata_i = mem.map[k];
      }
      tick();
    }
    m.shell_we_i = 0;
    m.map_we_i = 0;
    shell_words_ = mem.shell.size();
    map_words_ = mem.map.size();
    if (cfg_.banked()) mem_ = mem;  // for the check of the conflict counter (check_conflicts)
  }

  std::vector<Record> run(const std::vector<Job>& jobs) override {
    for (const Job& j : jobs) validate_job(cfg_, j, shell_words_, map_words_);
    enter();
    Model& m = *model_;
    std::vector<Record> out;
    std::bernoulli_distribution hit_stall(opt_.hit_stall_prob), done_stall(opt_.done_stall_prob);
    size_t next = 0, dones = 0;
    uint64_t idle = 0;
    const uint32_t conflicts_before = uint32_t(m.conflicts_o);
    // A job takes at most one cycle per point and record plus the pipeline; allow far more before giving up (a sparse
    // shell's word holds up to 64 points).
    const uint64_t patience = 1000 + 64 * (uint64_t{1} << cfg_.SAW) * (cfg_.sparse() ? 64 : 1);
    const size_t completions = jobs.size() - (faults_.miss_last_completion && !jobs.empty() ? 1 : 0);
    bool wrote_while_busy = false;
    while (dones < completions) {
      m.job_valid_i = next < jobs.size();
      if (m.job_valid_i) drive_job(jobs[next]);
      m.hit_ready_i = !hit_stall(stall_rng_);
      m.done_ready_i = !done_stall(stall_rng_);
      m.eval();
      const bool job_fire = m.job_valid_i && m.job_ready_o;
      bool progress = job_fire;
      if (m.hit_valid_o && m.hit_ready_i) {
        out.push_back(Record::hit(m.hit_tag_o, m.hit_point_o, m.hit_x_o, m.hit_y_o, m.hit_z_o, m.hit_state_o,
                                  sign_extend(uint64_t(m.hit_dist_o), cfg_.IW())));
        progress = true;
      }
      if (m.done_valid_o && m.done_ready_i) {
        Record d = Record::done(m.done_tag_o, m.done_hits_o, uint64_t(m.done_cycles_o));
        d.points = m.done_points_o;
        d.stalls = m.done_stalls_o;
        out.push_back(d);
        ++dones;
        progress = true;
      }
      tick();
      if (job_fire) ++next;
      if (faults_.write_while_busy) {  // for the next edge, once
        m.map_we_i = m.busy_o && !wrote_while_busy;
        wrote_while_busy = wrote_while_busy || m.map_we_i;
      }
      idle = progress ? 0 : idle + 1;
      if (idle > patience)
        throw DeviceError("rtl: no record for " + std::to_string(idle) + " cycles after " +
                          std::to_string(dones) + " of " + std::to_string(jobs.size()) + " jobs completed");
    }
    // Slots squashed behind a FIRST job's hit may still drain after the last completion record.
    m.job_valid_i = 0;
    m.hit_ready_i = 1;
    m.done_ready_i = 1;
    m.eval();
    for (int k = 0; k <= pipeline_slots(cfg_) && m.busy_o; ++k) {
      if (m.hit_valid_o || m.done_valid_o) throw DeviceError("rtl: a record came after the last completion record");
      tick();
    }
    if (m.busy_o) throw DeviceError("rtl: the device is still busy after the last completion record");
    check_conflicts(jobs, out, uint32_t(uint32_t(m.conflicts_o) - conflicts_before));
    return out;
  }

  // Cycles simulated since the model was made (loading included).
  uint64_t cycles() const { return cycles_; }

 private:
  // The bank conflict counter (conflicts_o, CW = 32 bits, which the AXI top reads as its CONFLICTS register) against
  // ref/'s count for the stream (ref/banks.h, bank_conflicts; docs/contract.md, "Shared voxmap banks"): a mismatch is
  // a DeviceError. A stream that is not the jobs' is left to the caller's comparison, which names its first wrong
  // record; so is a run with a planted fault.
  void check_conflicts(const std::vector<Job>& jobs, const std::vector<Record>& out, uint32_t counted) const {
    if (!cfg_.banked() || faults_.write_while_busy || faults_.miss_last_completion) return;
    std::vector<uint64_t> want;
    try {
      want = bank_conflicts(cfg_, mem_, jobs, out);
    } catch (const std::invalid_argument&) {
      return;
    }
    uint64_t sum = 0;
    for (uint64_t n : want) sum += n;
    if (uint32_t(sum) != counted)
      throw DeviceError("rtl: the bank conflict counter (conflicts_o) counted " + std::to_string(counted) +
                        " cycles over " + std::to_string(jobs.size()) + " jobs; the contract's count is " +
                        std::to_string(sum) + " (ref/banks.h, bank_conflicts)");
  }

  void drive_job(const Job& j) {
    Model& m = *model_;
    m.job_tag_i = j.tag;
    m.job_mode_i = uint8_t(j.mode);
    m.job_mask_i = j.hit_mask;
    m.job_shell_base_i = j.shell_base;
    m.job_shell_count_i = j.shell_count;
    m.job_map_base_i = j.map_base;
    m.job_nx_i = uint16_t(j.nx);
    m.job_ny_i = uint16_t(j.ny);
    m.job_nz_i = uint16_t(j.nz);
    const int mw = cfg_.MW, tw = cfg_.TW;
    m.job_m00_i = masked<uint32_t>(j.M[0][0], mw);
    m.job_m01_i = masked<uint32_t>(j.M[0][1], mw);
    m.job_m02_i = masked<uint32_t>(j.M[0][2], mw);
    m.job_m10_i = masked<uint32_t>(j.M[1][0], mw);
    m.job_m11_i = masked<uint32_t>(j.M[1][1], mw);
    m.job_m12_i = masked<uint32_t>(j.M[1][2], mw);
    m.job_m20_i = masked<uint32_t>(j.M[2][0], mw);
    m.job_m21_i = masked<uint32_t>(j.M[2][1], mw);
    m.job_m22_i = masked<uint32_t>(j.M[2][2], mw);
    m.job_t0_i = masked<uint64_t>(j.t[0], tw);
    m.job_t1_i = masked<uint64_t>(j.t[1], tw);
    m.job_t2_i = masked<uint64_t>(j.t[2], tw);
    // IW bits: a 32-bit or a 64-bit port depending on the model (0 on a 2-bit device).
    m.job_threshold_i = masked<std::remove_reference_t<decltype(m.job_threshold_i)>>(j.threshold, cfg_.IW());
    // Sparse devices: which of the map and the shell are sparse, and the map's bricks (0 on a dense device).
    m.job_sparse_i = j.sparse;
    m.job_brick_base_i = j.brick_base;
    m.job_brick_units_i = j.brick_units;
  }

  // Verilator reports a failed assertion to the calling thread's current context, and making any context makes
  // it the current one: make it this model's own before driving the pins, or a failure would be another
  // device's (tests/rtl/test_rtl_faults.cpp).
  void enter() { Verilated::threadContextp(ctx_.get()); }

  void reset() {
    Model& m = *model_;
    m.clk_i = 0;
    m.rst_ni = 0;
    m.shell_we_i = 0;
    m.map_we_i = 0;
    m.job_valid_i = 0;
    m.hit_ready_i = 1;
    m.done_ready_i = 1;
    m.eval();
    tick();
    tick();
    m.rst_ni = 1;
    m.eval();
  }

  // One clock cycle: rising edge, then falling edge; inputs are set while the clock is low.
  void tick() {
    Model& m = *model_;
    m.clk_i = 1;
    m.eval();
    dump();
    m.clk_i = 0;
    m.eval();
    dump();
    ++cycles_;
    if (ctx_->gotError())
      throw DeviceError("rtl: an assertion in the RTL failed at cycle " + std::to_string(cycles_) +
                        " (its message is printed above)");
  }

  void dump() {
    if (trace_) trace_->dump(ctx_->time());
    ctx_->timeInc(1);
  }

  // The coverage file, checked writable now: it is written when the device is destroyed (its counts over the
  // device's life), where no error can be reported.
  void open_coverage() {
    if (opt_.coverage_path.empty()) return;
#if VM_COVERAGE
    if (!std::ofstream(opt_.coverage_path))
      throw DeviceError("rtl: cannot write the coverage file " + opt_.coverage_path);
#else
    throw DeviceError("rtl: these models count no coverage (the coverage models are voxcd_rtl_cov_backend's: "
                      "docs/verification.md)");
#endif
  }

  DeviceConfig cfg_;
  DeviceOptions opt_;
  RtlFaults faults_;
  std::mt19937_64 stall_rng_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<VerilatedFstC> trace_;
  uint64_t cycles_ = 0;
  size_t shell_words_ = 0, map_words_ = 0;
  DeviceMemory mem_;  // what load() wrote, kept on a banked device (check_conflicts)
};

std::vector<RtlModelInfo> models() {
  std::vector<RtlModelInfo> out;
#define VOXCD_RTL_MODEL_ENTRY(model, family, pairs) \
  out.push_back({#family, parse_config_pairs(pairs, "rtl model " #model)});
  VOXCD_RTL_MODELS(VOXCD_RTL_MODEL_ENTRY)
#undef VOXCD_RTL_MODEL_ENTRY
  return out;
}

std::unique_ptr<Device> make(const DeviceConfig& cfg, const DeviceOptions& opt, const RtlFaults& faults) {
#define VOXCD_RTL_MODEL_ENTRY(model, family, pairs)          \
  if (cfg == parse_config_pairs(pairs, "rtl model " #model)) \
    return std::make_unique<RtlDevice<model>>(cfg, opt, faults);
  VOXCD_RTL_MODELS(VOXCD_RTL_MODEL_ENTRY)
#undef VOXCD_RTL_MODEL_ENTRY
  return nullptr;
}

const RtlModule kModule{&models, &make};

}  // namespace
}  // namespace voxcd

extern "C" const char* voxcd_rtl_module_abi() { return VOXCD_RTL_MODULE_ABI; }
extern "C" const voxcd::RtlModule* voxcd_rtl_module() { return &voxcd::kModule; }
