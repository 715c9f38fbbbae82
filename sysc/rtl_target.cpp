#include "voxcd/sysc/rtl_target.h"

#include <verilated.h>
#include <verilated_fst_sc.h>

#include <type_traits>

#include "voxcd/ref/vectors.h"
#include "voxcd_sysc_models.h"  // every model this build has, with its configuration (sysc/CMakeLists.txt)

namespace voxcd::sysc {

using namespace sc_core;

std::vector<int> rtl_target_lanes() { return {VOXCD_SYSC_LANES}; }

std::vector<DeviceConfig> rtl_target_configs() {
  std::vector<DeviceConfig> out;
#define VOXCD_SYSC_MODEL_ENTRY(model, pairs) out.push_back(parse_config_pairs(pairs, "SystemC model " #model));
  VOXCD_SYSC_MODELS(VOXCD_SYSC_MODEL_ENTRY)
#undef VOXCD_SYSC_MODEL_ENTRY
  return out;
}

// The pins with a signal of their own, named as the model's ports and typed as Verilator types the ports of the
// default-width device: X(type, name), stream by stream (write ports, job, hit, completion, status). A sparse
// device's ports have the same types: its point index (SAW + 6 bits) and counts (SAW + 7) stay within 32 bits.
#define VOXCD_RTL_PINS(X)                                                                                          \
  X(bool, shell_we_i) X(uint32_t, shell_waddr_i) X(sc_dt::sc_bv<72>, shell_wdata_i)                               \
  X(bool, map_we_i) X(uint32_t, map_waddr_i) X(uint64_t, map_wdata_i)                                             \
  X(bool, job_valid_i) X(bool, job_ready_o) X(uint32_t, job_tag_i) X(uint32_t, job_mode_i) X(uint32_t, job_mask_i) \
  X(uint32_t, job_shell_base_i) X(uint32_t, job_shell_count_i) X(uint32_t, job_map_base_i)                        \
  X(uint32_t, job_nx_i) X(uint32_t, job_ny_i) X(uint32_t, job_nz_i)                                               \
  X(uint32_t, job_sparse_i) X(uint32_t, job_brick_base_i) X(uint32_t, job_brick_units_i)                           \
  X(bool, hit_valid_o) X(uint32_t, hit_tag_o) X(uint32_t, hit_point_o) X(uint32_t, hit_x_o) X(uint32_t, hit_y_o)  \
  X(uint32_t, hit_z_o) X(uint32_t, hit_state_o)                                                                    \
  X(bool, done_valid_o) X(uint32_t, done_tag_o) X(uint32_t, done_hits_o) X(uint32_t, done_cycles_o)              \
  X(uint32_t, done_points_o) X(uint32_t, done_stalls_o)                                                           \
  X(bool, busy_o) X(uint32_t, conflicts_o)

// One signal per pin: those of VOXCD_RTL_PINS, then the ones bound apart: the reset, the consumer's two ready inputs
// (always high), the matrix and translation entries, and the threshold and distance, which are IW = SB + 3*WB bits:
// a uint32_t pin up to 32 bits, a uint64_t one above; a model binds the one of its type. conflicts_o counts the bank
// conflict cycles since reset (0 with a copy per lane).
struct RtlPins {
#define VOXCD_RTL_PIN_SIGNAL(type, name) sc_signal<type> name{#name};
  VOXCD_RTL_PINS(VOXCD_RTL_PIN_SIGNAL)
#undef VOXCD_RTL_PIN_SIGNAL
  sc_signal<bool> rst_ni{"rst_ni", false};
  sc_signal<bool> hit_ready_i{"hit_ready_i", true}, done_ready_i{"done_ready_i", true};
  sc_signal<uint32_t> job_m_i[9];
  sc_signal<uint64_t> job_t_i[3];
  sc_signal<uint32_t> job_threshold32_i{"job_threshold32_i"}, hit_dist32_o{"hit_dist32_o"};
  sc_signal<uint64_t> job_threshold64_i{"job_threshold64_i"}, hit_dist64_o{"hit_dist64_o"};
};

struct RtlModel {
  virtual ~RtlModel() = default;
  virtual void final() = 0;
  virtual void trace(VerilatedFstC* tfp) = 0;
};

namespace {

// Binds `port` to the signal of its own width.
template <class Port>
void bind_iw(Port& port, sc_signal<uint32_t>& s32, sc_signal<uint64_t>& s64) {
  if constexpr (std::is_same_v<typename Port::data_type, uint64_t>)
    port(s64);
  else
    port(s32);
}

template <class M>
struct ModelOf final : RtlModel {
  ModelOf(const char* name, sc_clock& clk, RtlPins& p) : m(name) {
    m.clk_i(clk);
    m.rst_ni(p.rst_ni);
    m.hit_ready_i(p.hit_ready_i);
    m.done_ready_i(p.done_ready_i);
#define VOXCD_RTL_PIN_BIND(type, name) m.name(p.name);
    VOXCD_RTL_PINS(VOXCD_RTL_PIN_BIND)
#undef VOXCD_RTL_PIN_BIND
    // The matrix's entries (row by row) and the translation's, one port each, bound to the pin arrays in order.
    sc_in<uint32_t>* const m_ports[9] = {&m.job_m00_i, &m.job_m01_i, &m.job_m02_i, &m.job_m10_i, &m.job_m11_i,
                                         &m.job_m12_i, &m.job_m20_i, &m.job_m21_i, &m.job_m22_i};
    sc_in<uint64_t>* const t_ports[3] = {&m.job_t0_i, &m.job_t1_i, &m.job_t2_i};
    for (int i = 0; i < 9; ++i) (*m_ports[i])(p.job_m_i[i]);
    for (int i = 0; i < 3; ++i) (*t_ports[i])(p.job_t_i[i]);
    bind_iw(m.job_threshold_i, p.job_threshold32_i, p.job_threshold64_i);
    bind_iw(m.hit_dist_o, p.hit_dist32_o, p.hit_dist64_o);
  }
  void final() override { m.final(); }
  void trace(VerilatedFstC* tfp) override { m.trace(tfp, 99); }
  M m;
};

uint32_t masked(int64_t v, int width) { return uint32_t(uint64_t(v) & ((uint64_t{1} << width) - 1)); }

// The signed value of the low `width` bits of v.
int64_t sign_extend(uint64_t v, int width) {
  if (width >= 64) return int64_t(v);
  const uint64_t sign = uint64_t{1} << (width - 1);
  v &= (sign << 1) - 1;
  return int64_t(v ^ sign) - int64_t(sign);
}

}  // namespace

RtlTarget::RtlTarget(sc_module_name name, const DeviceConfig& cfg, sc_time clock_period, sc_time access_latency,
                     const std::string& trace_path)
    : ClockedTarget(name, cfg, clock_period, access_latency),
      trace_path_(trace_path),
      pins_(std::make_unique<RtlPins>()) {
  if (!trace_path_.empty()) ctx_->traceEverOn(true);
  const std::string mname = std::string(basename()) + "_rtl";
#define VOXCD_SYSC_MODEL_ENTRY(model, pairs)                                    \
  if (!model_ && cfg == parse_config_pairs(pairs, "SystemC model " #model))      \
    model_ = std::make_unique<ModelOf<model>>(mname.c_str(), clk_, *pins_);
  VOXCD_SYSC_MODELS(VOXCD_SYSC_MODEL_ENTRY)
#undef VOXCD_SYSC_MODEL_ENTRY
  if (!model_) {
    std::string built;
    for (const DeviceConfig& c : rtl_target_configs()) built += (built.empty() ? "" : "; ") + c.to_string();
    throw std::invalid_argument(std::string(this->name()) +
                                ": the RTL models are built for the default widths with the lane counts, and for "
                                "the distance, shared-bank, deeper-pipeline and sparse devices listed here (" +
                                built + "), not for " + cfg.to_string());
  }
  start_clocked_method();
}

RtlTarget::~RtlTarget() {
  Verilated::threadContextp(ctx_.get());
  model_->final();
  if (trace_) trace_->close();
  model_.reset();
}

void RtlTarget::start_of_simulation() {
  if (trace_path_.empty()) return;
  trace_ = std::make_unique<VerilatedFstSc>();
  model_->trace(trace_.get());
  trace_->open(trace_path_.c_str());
}

void RtlTarget::drive_job(const Job& j) {
  RtlPins& p = *pins_;
  p.job_tag_i.write(j.tag);
  p.job_mode_i.write(uint32_t(j.mode));
  p.job_mask_i.write(j.hit_mask);
  p.job_shell_base_i.write(j.shell_base);
  p.job_shell_count_i.write(j.shell_count);
  p.job_map_base_i.write(j.map_base);
  p.job_nx_i.write(j.nx);
  p.job_ny_i.write(j.ny);
  p.job_nz_i.write(j.nz);
  // A sparse device's fields (0 for a dense job, the only kind a dense device takes).
  p.job_sparse_i.write(j.sparse);
  p.job_brick_base_i.write(j.brick_base);
  p.job_brick_units_i.write(j.brick_units);
  for (int i = 0; i < 9; ++i) p.job_m_i[i].write(masked(j.M[i / 3][i % 3], cfg_.MW));
  const uint64_t tmask = cfg_.TW >= 64 ? ~uint64_t{0} : (uint64_t{1} << cfg_.TW) - 1;
  for (int i = 0; i < 3; ++i) p.job_t_i[i].write(uint64_t(j.t[i]) & tmask);
  const int iw = cfg_.IW();  // 0 on a 2-bit device
  const uint64_t thr = uint64_t(j.threshold) & (iw >= 64 ? ~uint64_t{0} : (uint64_t{1} << iw) - 1);
  p.job_threshold32_i.write(uint32_t(thr));
  p.job_threshold64_i.write(thr);
}

void RtlTarget::drive_word(const MemRequest& req) {
  RtlPins& p = *pins_;
  const size_t k = req.written;
  if (req.shell) {
    sc_dt::sc_bv<72> w;
    const ShellWord& s = req.shell_words[k];
    for (int c = 0; c < 3; ++c)
      for (int b = 0; b < cfg_.PW; ++b) w[c * cfg_.PW + b] = bool((uint64_t(s[c]) >> b) & 1u);
    p.shell_we_i.write(true);
    p.shell_waddr_i.write(uint32_t(req.first + k));
    p.shell_wdata_i.write(w);
  } else {
    p.map_we_i.write(true);
    p.map_waddr_i.write(uint32_t(req.first + k));
    p.map_wdata_i.write(req.map_words[k]);
  }
}

// The records the device emitted at this edge: a hit, or a completion that ends its job.
void RtlTarget::take_records() {
  RtlPins& p = *pins_;
  if (p.hit_valid_o.read()) {
    const int iw = cfg_.IW();
    const uint64_t dist = iw > 32 ? p.hit_dist64_o.read() : p.hit_dist32_o.read();
    partial_.push_back(Record::hit(p.hit_tag_o.read(), p.hit_point_o.read(), p.hit_x_o.read(), p.hit_y_o.read(),
                                   p.hit_z_o.read(), uint8_t(p.hit_state_o.read()), sign_extend(dist, iw)));
  }
  if (p.done_valid_o.read()) {
    Record d = Record::done(p.done_tag_o.read(), p.done_hits_o.read(), p.done_cycles_o.read());
    d.points = p.done_points_o.read();
    d.stalls = p.done_stalls_o.read();
    partial_.push_back(d);
    // The conflict cycles since the previous completion (the counter wraps at 2^32 as the register does).
    const uint64_t conflicts = p.conflicts_o.read();
    job_done(uint32_t(conflicts - conflicts_seen_));
    conflicts_seen_ = conflicts;
  }
}

// The inputs for the next edge: a memory word (once every launched batch is done and the device is idle, unless
// start_writes_while_busy), else the running batch's next job.
void RtlTarget::drive_inputs() {
  RtlPins& p = *pins_;
  start_memory_write((!busy() && !p.busy_o.read()) || !writes_wait_for_idle_);
  const bool writing = mem_ && mem_->started;
  if (writing) drive_word(*mem_);
  p.shell_we_i.write(writing && mem_->shell);
  p.map_we_i.write(writing && !mem_->shell);
  start_batch(writing);
  job_valid_ = running_ && fed_ < batches_.front().jobs.size();
  if (job_valid_) drive_job(batches_.front().jobs[fed_]);
  p.job_valid_i.write(job_valid_);
}

void RtlTarget::on_edge() {
  RtlPins& p = *pins_;
  if (first_edge()) {
    p.rst_ni.write(true);  // this edge reset the device; its outputs before it mean nothing
  } else {
    if (job_valid_ && p.job_ready_o.read()) ++fed_;
    take_records();
    if (mem_ && mem_->started) word_written();
  }
  drive_inputs();
  end_edge();
}

}  // namespace voxcd::sysc
