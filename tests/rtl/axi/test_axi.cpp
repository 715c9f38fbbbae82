// The AXI top (rtl/voxcd_axi.sv), Verilated, driven through its AXI4-Lite slave and its two AXI4-Stream ports
// with random TVALID / TREADY and AXI4-Lite handshakes. Descriptors are packed and records unpacked with the
// address map's own encode_job / decode_record (ref/address_map.h). Checks: the records equal ref/'s
// (vector files and generated vectors), the cycles equal ref/timing.h's (plus the counted stalls) at the model's
// pipeline depth, the latency the top adds is exactly the documented one, the responses are OKAY / SLVERR / DECERR
// as documented, refused descriptors come back as error records with the faults ref/'s job_faults names, and every
// output payload is stable while valid and not taken, with no dropped or repeated beat. A sparse top (BL > 0) runs
// every test too, with sparse maps and shells in its streams and its descriptors' sparse fields (bytes 0x06, 0x44,
// 0x68: sparse_descriptor below) among the rules it refuses. Every test prints its seed; VOXCD_SEED replays.
#include <gtest/gtest.h>
#include <unistd.h>
#include <verilated.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"
#include "voxcd/ref/timing.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"
#include "tests/seed.h"
// The AXI tops (rtl/CMakeLists.txt); test_axi_cov runs the same tests on their coverage models, each test's counts
// written into $VOXCD_COVERAGE_DIR (bench/coverage.sh, docs/verification.md).
#ifdef VOXCD_AXI_MODELS_HEADER
#include VOXCD_AXI_MODELS_HEADER
#else
#include "voxcd_axi_models.h"
#endif
#if VM_COVERAGE
#include <verilated_cov.h>
#endif

namespace voxcd {
namespace {

using namespace voxcd::sysc;

constexpr uint8_t kOkay = 0, kSlverr = 2, kDecerr = 3;

uint64_t test_seed() { return test::seed(20261125); }

// ---- Descriptors with a sparse device's fields ----
// The address map's descriptor (encode_job, decode_job) with the sparse fields at their offsets: byte 0x06 `sparse`
// (bits 0 and 1; bits 2..7 and byte 0x07 reserved), 0x44 u32 brick_units, 0x68 u32 brick_base (the rest zero).
constexpr size_t kSparseByte = 0x06, kBrickUnits = 0x44, kBrickBase = 0x68, kReservedFrom = 0x6c;

std::vector<uint8_t> sparse_descriptor(const Job& j) {
  std::vector<uint8_t> bytes(kJobBytes);
  Job dense = j;
  dense.sparse = 0, dense.brick_base = dense.brick_units = 0;
  encode_job(dense, bytes.data());
  bytes[kSparseByte] = j.sparse;
  put_le(&bytes[kBrickUnits], j.brick_units, 4);
  put_le(&bytes[kBrickBase], j.brick_base, 4);
  return bytes;
}

// The job of descriptor bytes whose reserved bytes are zero (false and `why` otherwise).
bool decode_sparse_descriptor(const std::vector<uint8_t>& bytes, Job& j, std::string& why) {
  std::vector<uint8_t> dense = bytes;
  dense[kSparseByte] = 0;
  std::memset(&dense[kBrickUnits], 0, 4);
  std::memset(&dense[kBrickBase], 0, 4);
  if (!decode_job(dense.data(), j, why)) return false;
  j.sparse = bytes[kSparseByte];
  j.brick_units = uint32_t(get_le(&bytes[kBrickUnits], 4));
  j.brick_base = uint32_t(get_le(&bytes[kBrickBase], 4));
  return true;
}

// ---- The model's pins, whatever their Verilated types ----
struct In {
  bool awvalid = false, wvalid = false, bready = false, arvalid = false, rready = false;
  uint32_t awaddr = 0, araddr = 0;
  uint64_t wdata = 0;
  uint32_t wstrb = 0;
  bool jvalid = false, jlast = false;
  const uint8_t* jdata = nullptr;  // JobDw / 8 bytes
  bool rec_ready = false;
};
struct Out {
  bool awready = false, wready = false, bvalid = false, arready = false, rvalid = false;
  uint32_t bresp = 0, rresp = 0;
  uint64_t rdata = 0;
  bool jready = false, rec_valid = false, rec_last = false;
  uint8_t rec_data[32] = {};
};

template <class T>
void put_bytes(T& port, const uint8_t* p, int n) {
  uint64_t v = 0;
  for (int i = 0; i < n; ++i) v |= uint64_t(p[i]) << (8 * i);
  port = T(v);
}
template <std::size_t N>
void put_bytes(VlWide<N>& port, const uint8_t* p, int n) {
  for (std::size_t w = 0; w < N; ++w) {
    uint32_t v = 0;
    for (int b = 0; b < 4 && int(4 * w) + b < n; ++b) v |= uint32_t(p[4 * w + b]) << (8 * b);
    port[w] = v;
  }
}
template <class T>
void get_bytes(const T& port, uint8_t* p, int n) {
  for (int i = 0; i < n; ++i) p[i] = uint8_t(uint64_t(port) >> (8 * i));
}
template <std::size_t N>
void get_bytes(const VlWide<N>& port, uint8_t* p, int n) {
  for (int i = 0; i < n; ++i) p[i] = uint8_t(port[i / 4] >> (8 * (i % 4)));
}

struct Ports {
  virtual ~Ports() = default;
  virtual void reset(bool rst_n) = 0;
  virtual void set(const In& in, int job_bytes) = 0;
  virtual void eval(bool clk) = 0;
  virtual void get(Out& o, int rec_bytes) = 0;
  virtual void final() = 0;
};

template <class M>
struct PortsOf final : Ports {
  explicit PortsOf(VerilatedContext* ctx) : m(std::make_unique<M>(ctx, "axi")) {}
  void reset(bool rst_n) override { m->rst_ni = rst_n; }
  void set(const In& in, int job_bytes) override {
    m->s_axil_awvalid_i = in.awvalid;
    m->s_axil_awaddr_i = in.awaddr;
    m->s_axil_awprot_i = 0;
    m->s_axil_wvalid_i = in.wvalid;
    m->s_axil_wdata_i = std::remove_reference_t<decltype(m->s_axil_wdata_i)>(in.wdata);
    m->s_axil_wstrb_i = std::remove_reference_t<decltype(m->s_axil_wstrb_i)>(in.wstrb);
    m->s_axil_bready_i = in.bready;
    m->s_axil_arvalid_i = in.arvalid;
    m->s_axil_araddr_i = in.araddr;
    m->s_axil_arprot_i = 0;
    m->s_axil_rready_i = in.rready;
    m->s_axis_job_tvalid_i = in.jvalid;
    m->s_axis_job_tlast_i = in.jlast;
    if (in.jdata) put_bytes(m->s_axis_job_tdata_i, in.jdata, job_bytes);
    m->m_axis_rec_tready_i = in.rec_ready;
  }
  void eval(bool clk) override {
    m->clk_i = clk;
    m->eval();
  }
  void get(Out& o, int rec_bytes) override {
    o.awready = m->s_axil_awready_o;
    o.wready = m->s_axil_wready_o;
    o.bvalid = m->s_axil_bvalid_o;
    o.bresp = m->s_axil_bresp_o;
    o.arready = m->s_axil_arready_o;
    o.rvalid = m->s_axil_rvalid_o;
    o.rresp = m->s_axil_rresp_o;
    o.rdata = uint64_t(m->s_axil_rdata_o);
    o.jready = m->s_axis_job_tready_o;
    o.rec_valid = m->m_axis_rec_tvalid_o;
    o.rec_last = m->m_axis_rec_tlast_o;
    get_bytes(m->m_axis_rec_tdata_o, o.rec_data, rec_bytes);
  }
  void final() override { m->final(); }
  std::unique_ptr<M> m;
};

struct ModelEntry {
  std::string name, params;
  std::function<std::unique_ptr<Ports>(VerilatedContext*)> make;
};
std::vector<ModelEntry> models() {
  std::vector<ModelEntry> v;
#define VOXCD_AXI_ENTRY(model, pairs) \
  v.push_back({#model, pairs, [](VerilatedContext* c) { return std::unique_ptr<Ports>(new PortsOf<model>(c)); }});
  VOXCD_AXI_MODELS(VOXCD_AXI_ENTRY)
#undef VOXCD_AXI_ENTRY
  return v;
}

// ---- The harness: a cycle loop with an AXI4-Lite master, a job stream master and a record stream slave ----
class Axi {
 public:
  // The parameters of a model: the device's config, and AxilDw, JobDw, RecDw.
  Axi(const ModelEntry& e, uint64_t seed) : rng_(seed), ctx_(std::make_unique<VerilatedContext>()) {
    std::istringstream is(e.params);
    std::string name, rest;
    int value = 0;
    while (is >> name >> value) {
      if (name == "AxilDw") axil_dw = value;
      else if (name == "JobDw") job_dw = value;
      else if (name == "RecDw") rec_dw = value;
      else rest += name + " " + std::to_string(value) + " ";
    }
    cfg = parse_config_pairs(rest, e.name);
    job_beats = int(8 * kJobBytes) / job_dw;
    rec_beats = int(8 * kRecordBytes) / rec_dw;
    ctx_->fatalOnError(false);  // an RTL assertion is a test failure with its message, not an abort
#ifdef VOXCD_RTL_RANDOM_POWER_UP
    ctx_->randReset(2);  // random power-up values (bench/mutation's models): reset must clear what matters
    ctx_->randSeed(int(seed % 0x7fffffff) + 1);
#endif
    ports_ = e.make(ctx_.get());
    ports_->reset(false);
    apply();
    ports_->eval(false);
    ports_->eval(true);
    ports_->eval(false);
    ports_->reset(true);
  }
  ~Axi() {
    Verilated::threadContextp(ctx_.get());
    ports_->final();
#if VM_COVERAGE
    static int written = 0;
    if (const char* dir = std::getenv("VOXCD_COVERAGE_DIR"))
      ctx_->coveragep()->write((std::string(dir) + "/axi-" + std::to_string(::getpid()) + "-" +
                                std::to_string(written++) + ".dat").c_str());
#endif
  }

  DeviceConfig cfg;
  int axil_dw = 32, job_dw = 64, rec_dw = 64, job_beats = 1, rec_beats = 1;
  // Probabilities per cycle: the job stream's TVALID, the record stream's TREADY, and the AXI4-Lite master's
  // VALIDs and READYs.
  double p_job_valid = 1, p_rec_ready = 1, p_lite = 1;

  std::vector<std::string> errors;  // protocol violations seen, with their cycle
  uint64_t cycle = 0;               // rising edges so far; events are numbered by the cycle they happen in

  // Received hit and completion records, with the cycle of their last beat.
  std::vector<Record> records;
  std::vector<uint64_t> record_cycle;
  // Received error records: where in `records` they came (the number of records before them), tag and faults.
  struct Refusal {
    size_t at = 0;
    uint32_t tag = 0, faults = 0;
  };
  std::vector<Refusal> refusals;
  // The cycle of each queued descriptor's first beat (in queue order).
  std::vector<uint64_t> job_first_cycle;

  // Queues a descriptor (its bytes as they go on the stream; `beats` beats, TLAST on the last one).
  void queue_bytes(const std::vector<uint8_t>& bytes, int beats, bool tlast_on_last = true) {
    const int bb = job_dw / 8;
    for (int b = 0; b < beats; ++b) {
      Beat beat;
      beat.data.assign(bytes.begin() + std::min<size_t>(bytes.size(), size_t(b) * bb),
                       bytes.begin() + std::min<size_t>(bytes.size(), size_t(b + 1) * bb));
      beat.data.resize(bb, 0);
      beat.last = tlast_on_last && b == beats - 1;
      beat.first = b == 0;
      beats_.push_back(std::move(beat));
    }
  }
  void queue_job(const Job& j) { queue_bytes(sparse_descriptor(j), job_beats); }
  bool jobs_pending() const { return !beats_.empty(); }

  // One clock cycle of every agent.
  void tick() {
    // The stream agents' choices for this cycle (a VALID stays up until its beat is taken).
    if (!in_.jvalid && !beats_.empty() && chance(p_job_valid)) in_.jvalid = true;
    in_.jlast = in_.jvalid && beats_.front().last;
    in_.jdata = in_.jvalid ? beats_.front().data.data() : nullptr;
    in_.rec_ready = chance(p_rec_ready);
    lite_drive();
    apply();
    ports_->eval(false);
    Out o;
    ports_->get(o, rec_dw / 8);
    check_stable(o);
    if (in_.jvalid && o.jready) {
      if (beats_.front().first) job_first_cycle.push_back(cycle);
      beats_.pop_front();
      in_.jvalid = false;
    }
    if (o.rec_valid && in_.rec_ready) take_beat(o);
    lite_observe(o);
    ports_->eval(true);
    ++cycle;
    if (ctx_->gotError()) {
      errors.push_back("cycle " + std::to_string(cycle) + ": an RTL assertion failed (see its message above)");
      ctx_->gotError(false);
    }
  }
  void ticks(int n) {
    for (int i = 0; i < n; ++i) tick();
  }

  // AXI4-Lite transactions, one at a time (the streams keep running meanwhile). Returns the response.
  uint32_t write(uint32_t addr, uint64_t data, uint32_t strb = ~0u) {
    lite_ = Lite{};
    lite_.write = true;
    lite_.addr = addr;
    lite_.data = data;
    lite_.strb = strb & ((1u << (axil_dw / 8)) - 1);
    return lite_run();
  }
  uint32_t read(uint32_t addr, uint64_t& data) {
    lite_ = Lite{};
    lite_.write = false;
    lite_.addr = addr;
    const uint32_t r = lite_run();
    data = lite_.data;
    return r;
  }
  // A 64-bit register or memory word: one access with AxilDw = 64, two (low half first) with 32. The first
  // response that is not OKAY, else OKAY.
  uint32_t write64(uint32_t addr, uint64_t v) {
    if (axil_dw == 64) return write(addr, v);
    const uint32_t a = write(addr, v & 0xffffffffu), b = write(addr + 4, v >> 32);
    return a != kOkay ? a : b;
  }
  uint32_t read64(uint32_t addr, uint64_t& v) {
    if (axil_dw == 64) return read(addr, v);
    uint64_t lo = 0, hi = 0;
    const uint32_t a = read(addr, lo), b = read(addr + 4, hi);
    v = (lo & 0xffffffffu) | hi << 32;
    return a != kOkay ? a : b;
  }
  uint64_t reg(uint64_t off) {
    uint64_t v = 0;
    const uint32_t r = read64(uint32_t(kRegBase + off), v);
    EXPECT_EQ(r, kOkay) << "register " << off;
    return v;
  }
  // Shell word k: {x, y, z, 0} as 32-bit values; z commits it.
  uint32_t write_shell(uint64_t k, const ShellWord& w) {
    const uint32_t a = uint32_t(kShellBase + kShellStride * k);
    const uint64_t x = uint32_t(w[0]), y = uint32_t(w[1]), z = uint32_t(w[2]);
    uint32_t r[3];
    if (axil_dw == 64) {
      r[0] = write(a, x | y << 32);
      r[1] = kOkay;
      r[2] = write(a + 8, z);
    } else {
      r[0] = write(a, x);
      r[1] = write(a + 4, y);
      r[2] = write(a + 8, z);
    }
    for (uint32_t v : r)
      if (v != kOkay) return v;
    return kOkay;
  }
  void load(const DeviceMemory& mem) {
    for (size_t k = 0; k < mem.shell.size(); ++k) ASSERT_EQ(write_shell(k, mem.shell[k]), kOkay) << "shell " << k;
    for (size_t k = 0; k < mem.map.size(); ++k)
      ASSERT_EQ(write64(uint32_t(kMapBase + kMapStride * k), mem.map[k]), kOkay) << "voxmap " << k;
  }
  // Runs until `n` records have arrived (or the limit passes).
  void run_until_records(size_t n, uint64_t limit = 2'000'000) {
    const uint64_t end = cycle + limit;
    while (records.size() < n && cycle < end) tick();
    EXPECT_EQ(records.size(), n) << "records missing after " << limit << " cycles";
  }

 private:
  struct Beat {
    std::vector<uint8_t> data;
    bool last = false, first = false;
  };
  struct Lite {
    bool write = false;
    uint32_t addr = 0, strb = 0;
    uint64_t data = 0;
    bool aw_done = false, w_done = false, ar_done = false, done = false;
    uint32_t resp = 0;
  };

  bool chance(double p) { return p >= 1 || std::uniform_real_distribution<double>(0, 1)(rng_) < p; }
  void apply() { ports_->set(in_, job_dw / 8); }

  void lite_drive() {
    if (lite_.write) {
      if (!in_.awvalid && !lite_.aw_done && chance(p_lite)) in_.awvalid = true;
      if (!in_.wvalid && !lite_.w_done && chance(p_lite)) in_.wvalid = true;
      in_.awaddr = in_.awvalid ? lite_.addr : 0;
      in_.wdata = in_.wvalid ? lite_.data : 0;
      in_.wstrb = in_.wvalid ? lite_.strb : 0;
      in_.bready = chance(p_lite);
    } else {
      if (!in_.arvalid && !lite_.ar_done && !lite_.done && active_ && chance(p_lite)) in_.arvalid = true;
      in_.araddr = in_.arvalid ? lite_.addr : 0;
      in_.rready = chance(p_lite);
    }
    if (!active_) in_.awvalid = in_.wvalid = in_.arvalid = false;
  }
  void lite_observe(const Out& o) {
    if (!active_) {
      if (o.bvalid || o.rvalid) errors.push_back("cycle " + std::to_string(cycle) + ": a response nobody asked for");
      return;
    }
    if (lite_.write) {
      if (o.bvalid && in_.bready) {
        if (!lite_.aw_done || !lite_.w_done)
          errors.push_back("cycle " + std::to_string(cycle) + ": B before both AW and W were taken");
        lite_.resp = o.bresp;
        lite_.done = true;
      }
      if (in_.awvalid && o.awready) {
        lite_.aw_done = true;
        in_.awvalid = false;
      }
      if (in_.wvalid && o.wready) {
        lite_.w_done = true;
        in_.wvalid = false;
      }
    } else {
      if (o.rvalid && in_.rready) {
        if (!lite_.ar_done) errors.push_back("cycle " + std::to_string(cycle) + ": R before AR was taken");
        lite_.resp = o.rresp;
        lite_.data = o.rdata;
        lite_.done = true;
      }
      if (in_.arvalid && o.arready) {
        lite_.ar_done = true;
        in_.arvalid = false;
      }
    }
  }
  uint32_t lite_run() {
    active_ = true;
    for (int i = 0; i < 100000 && !lite_.done; ++i) tick();
    active_ = false;
    in_.awvalid = in_.wvalid = in_.arvalid = in_.bready = in_.rready = false;
    EXPECT_TRUE(lite_.done) << "AXI4-Lite access to " << std::hex << lite_.addr << " never completed";
    return lite_.resp;
  }

  // A payload offered and not taken must be offered again, unchanged, in the next cycle.
  void check_stable(const Out& o) {
    const std::string at = "cycle " + std::to_string(cycle) + ": ";
    if (prev_b_stalled_ && !(o.bvalid && o.bresp == prev_.bresp)) errors.push_back(at + "B changed while stalled");
    if (prev_r_stalled_ && !(o.rvalid && o.rresp == prev_.rresp && o.rdata == prev_.rdata))
      errors.push_back(at + "R changed while stalled");
    if (prev_rec_stalled_ && !(o.rec_valid && o.rec_last == prev_.rec_last &&
                               std::memcmp(o.rec_data, prev_.rec_data, size_t(rec_dw / 8)) == 0))
      errors.push_back(at + "record beat changed while stalled");
    prev_b_stalled_ = o.bvalid && !in_.bready;
    prev_r_stalled_ = o.rvalid && !in_.rready;
    prev_rec_stalled_ = o.rec_valid && !in_.rec_ready;
    prev_ = o;
  }
  // A record is rec_beats beats, TLAST on the last and only there.
  void take_beat(const Out& o) {
    const int bb = rec_dw / 8;
    std::memcpy(rec_buf_ + rec_beat_ * bb, o.rec_data, size_t(bb));
    ++rec_beat_;
    if (o.rec_last != (rec_beat_ == rec_beats))
      errors.push_back("cycle " + std::to_string(cycle) + ": TLAST " + (o.rec_last ? "on" : "missing on") +
                       " record beat " + std::to_string(rec_beat_ - 1));
    if (rec_beat_ < rec_beats) return;
    rec_beat_ = 0;
    Refusal refusal;
    if (decode_error_record(rec_buf_, refusal.tag, refusal.faults)) {
      refusal.at = records.size();
      refusals.push_back(refusal);
      for (size_t b = 12; b < kRecordBytes; ++b)
        if (rec_buf_[b] != 0) errors.push_back("cycle " + std::to_string(cycle) + ": an error record's byte " +
                                               std::to_string(b) + " is not zero");
      return;
    }
    Record r;
    if (!decode_record(rec_buf_, r)) errors.push_back("cycle " + std::to_string(cycle) + ": a record of kind 0");
    records.push_back(r);
    record_cycle.push_back(cycle);
  }

  std::mt19937_64 rng_;
  std::unique_ptr<VerilatedContext> ctx_;
  std::unique_ptr<Ports> ports_;
  In in_;
  Lite lite_;
  bool active_ = false;
  std::deque<Beat> beats_;
  uint8_t rec_buf_[kRecordBytes] = {};
  int rec_beat_ = 0;
  Out prev_;
  bool prev_b_stalled_ = false, prev_r_stalled_ = false, prev_rec_stalled_ = false;
};

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size() && i < 10; ++i) s += v[i] + "\n";
  return s;
}

// Checks `got` against ref/'s stream for the jobs; with `cycles`, every completion's cycles equal the exact timing
// model's plus its counted stalls.
void expect_stream(const Axi& axi, const DeviceMemory& mem, const std::vector<Job>& jobs,
                   const std::vector<Record>& got, bool cycles, uint64_t seed) {
  std::vector<Record> want = run_stream(axi.cfg, mem, jobs);
  if (cycles) annotate_cycles(axi.cfg, mem, jobs, want);
  ASSERT_EQ(got.size(), want.size()) << "seed " << seed;
  for (size_t i = 0; i < want.size(); ++i) {
    ASSERT_TRUE(got[i].same_as(want[i], false))
        << "record " << i << ": got " << got[i].to_string(true) << ", want " << want[i].to_string(true) << ", seed "
        << seed;
    if (cycles && want[i].kind == Record::Done) {
      ASSERT_EQ(*got[i].cycles, *want[i].cycles + *got[i].stalls)
          << "record " << i << " (" << got[i].to_string() << "): cycles = timing model + stalls; seed " << seed;
    }
  }
}

class AxiTest : public ::testing::TestWithParam<size_t> {
 protected:
  void SetUp() override {
    seed_ = test_seed();
    axi_ = std::make_unique<Axi>(models()[GetParam()], seed_);
  }
  void TearDown() override { EXPECT_TRUE(axi_->errors.empty()) << join(axi_->errors) << "seed " << seed_; }
  uint64_t seed_ = 0;
  std::unique_ptr<Axi> axi_;
};

// 1. The identification and configuration registers read as the SystemC address map defines them.
TEST_P(AxiTest, RegistersAfterReset) {
  Axi& a = *axi_;
  a.p_lite = 0.4;
  EXPECT_EQ(a.reg(kRegId), kDeviceId);
  EXPECT_EQ(a.reg(kRegConfig0), config_word0(a.cfg));
  EXPECT_EQ(a.reg(kRegConfig1), config_word1(a.cfg) | uint64_t(a.cfg.BL) << 56) << "CONFIG1 holds BL in 56..63";
  EXPECT_EQ(a.reg(kRegClockPs), 10000u);
  EXPECT_EQ(a.reg(kRegStatus), 0u);
  for (uint64_t r : {kRegStaged, kRegResultCount, kRegJobsDone, kRegHits, kRegPoints, kRegCycles, kRegStalls,
                     kRegShellWords, kRegMapWords, kRegDropped, kRegConflicts})
    EXPECT_EQ(a.reg(r), 0u) << "register " << r;
}

// 2. Every documented error response, and that a refused write has no effect.
TEST_P(AxiTest, ErrorResponses) {
  Axi& a = *axi_;
  a.p_lite = 0.5;
  uint64_t v = 0;
  EXPECT_EQ(a.read(uint32_t(kRegBase + kRegRun), v), kSlverr) << "RUN is write-only";
  EXPECT_EQ(a.write(uint32_t(kRegBase + kRegId), 1), kSlverr) << "ID is read-only";
  EXPECT_EQ(a.write(uint32_t(kRegBase + kRegDropped), 1), kSlverr) << "DROPPED is read-only";
  EXPECT_EQ(a.write(uint32_t(kRegBase + kRegConflicts), 1), kSlverr) << "CONFLICTS is read-only";
  EXPECT_EQ(a.read(uint32_t(kRegBase + 0x88), v), kDecerr) << "no register at 0x88";
  EXPECT_EQ(a.write(uint32_t(kRegBase + 0xff8), 0), kDecerr) << "no register at 0xff8";
  EXPECT_EQ(a.read(uint32_t(kRegBase + 0x1000), v), kDecerr) << "0x1000 is past the register window";
  EXPECT_EQ(a.read(uint32_t(kRegBase + 1), v), kSlverr) << "unaligned";
  EXPECT_EQ(a.read(uint32_t(kJobBase), v), kDecerr) << "the job window is the job stream here";
  EXPECT_EQ(a.write(uint32_t(kJobBase), 0), kDecerr);
  EXPECT_EQ(a.read(uint32_t(kResultBase), v), kDecerr) << "the result window is the record stream here";
  EXPECT_EQ(a.read(uint32_t(kShellBase), v), kSlverr) << "the shell memory is write-only";
  EXPECT_EQ(a.read(uint32_t(kMapBase + 8), v), kSlverr) << "the voxmap memory is write-only";
  EXPECT_EQ(a.write(uint32_t(kShellBase + kShellStride * a.cfg.shell_depth()), 0), kDecerr) << "past the shell";
  EXPECT_EQ(a.write(uint32_t(kMapBase + kMapStride * a.cfg.map_depth()), 0), kDecerr) << "past the voxmap";
  // Memory words: z without x and y, a coordinate that does not fit PW, reserved bytes, a partial strobe.
  EXPECT_EQ(a.write(uint32_t(kShellBase + 8), 1), kSlverr) << "z commits only after x and y";
  const int64_t big = int64_t{1} << (a.cfg.PW - 1);
  EXPECT_EQ(a.write_shell(0, {int32_t(big), 0, 0}), kSlverr) << "x = 2^(PW-1) does not fit";
  EXPECT_EQ(a.write_shell(0, {0, 0, int32_t(-big - 1)}), kSlverr) << "z = -2^(PW-1) - 1 does not fit";
  if (a.axil_dw == 64) EXPECT_EQ(a.write(uint32_t(kShellBase + 8), uint64_t{1} << 32), kSlverr) << "reserved";
  else EXPECT_EQ(a.write(uint32_t(kShellBase + 12), 1), kSlverr) << "reserved bytes 12..15";
  if (a.axil_dw == 32) {
    EXPECT_EQ(a.write(uint32_t(kShellBase + 12), 0), kOkay) << "zero into the reserved bytes";
  }
  EXPECT_EQ(a.write(uint32_t(kMapBase), 5, 0x1), kSlverr) << "partial WSTRB";
  EXPECT_EQ(a.reg(kRegShellWords), 0u) << "a refused shell write took effect";
  EXPECT_EQ(a.reg(kRegMapWords), 0u) << "a refused voxmap write took effect";
  if (a.axil_dw == 32) {
    // z commits only the x and y written since the word's last commit, both of them.
    EXPECT_EQ(a.write(uint32_t(kShellBase + kShellStride * 5), 1), kOkay);
    EXPECT_EQ(a.write(uint32_t(kShellBase + kShellStride * 5 + 8), 1), kSlverr) << "z after x alone";
  }
  // The same words written properly.
  EXPECT_EQ(a.write_shell(3, {int32_t(big - 1), int32_t(-big), 7}), kOkay);
  if (a.axil_dw == 32) {
    EXPECT_EQ(a.write(uint32_t(kShellBase + kShellStride * 3 + 4), 2), kOkay);
    EXPECT_EQ(a.write(uint32_t(kShellBase + kShellStride * 3 + 8), 2), kSlverr) << "z after y alone, once committed";
  }
  EXPECT_EQ(a.write64(uint32_t(kMapBase + kMapStride * 9), 0x0123456789abcdefull), kOkay);
  EXPECT_EQ(a.reg(kRegShellWords), 4u);
  EXPECT_EQ(a.reg(kRegMapWords), 10u);
  EXPECT_EQ(a.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
}

// 3. The job stream stays closed until RUN; memory writes are refused while a job runs and accepted after.
TEST_P(AxiTest, RunOpensTheStreamAndBusyRefusesWrites) {
  Axi& a = *axi_;
  DeviceMemory mem;
  for (int k = 0; k < 4096; ++k) mem.shell.push_back({0, 0, 0});
  Job j;
  j.tag = 7;
  j.mode = Mode::Count;
  j.shell_count = 4096;
  mem.map.assign(map_words(a.cfg, j), 0);  // one word of 2-bit states; a distance map's eight banks
  a.load(mem);
  a.queue_job(j);
  a.ticks(200);
  EXPECT_TRUE(a.job_first_cycle.empty()) << "a descriptor beat was taken before RUN";
  EXPECT_EQ(a.write(uint32_t(kRegBase + kRegRun), 0), kOkay);
  while (a.jobs_pending()) a.tick();
  a.ticks(a.job_beats + 2);  // the device has the job
  EXPECT_EQ(a.reg(kRegStatus) & kStatusBusy, kStatusBusy);
  EXPECT_EQ(a.write64(uint32_t(kMapBase), 1), kSlverr) << "a memory write while a job runs";
  EXPECT_EQ(a.write(uint32_t(kShellBase), 1), kSlverr) << "a shell write while a job runs";
  a.run_until_records(1);
  a.ticks(4);
  EXPECT_EQ(a.reg(kRegStatus), 0u);
  EXPECT_EQ(a.reg(kRegJobsDone), 1u);
  EXPECT_EQ(a.reg(kRegPoints), 4096u);
  EXPECT_EQ(a.write64(uint32_t(kMapBase), 1), kOkay);
  ASSERT_EQ(a.records.size(), 1u);
  EXPECT_EQ(a.records[0].tag, 7u);
  // Every point lands in voxel (0, 0, 0): empty in a 2-bit map of zeros, at distance 0 (a hit) in a distance one.
  EXPECT_EQ(a.records[0].hits, a.cfg.distance() ? 4096u : 0u);
}

// 3b. From a descriptor's first beat until its job has run, the top is busy: a memory write issued in any cycle
// around the descriptor's last beat (before, as it is taken, while the descriptor is staged and while the device
// takes it) is refused, so no write lands between a job's descriptor and its run.
TEST_P(AxiTest, WritesAreRefusedFromADescriptorsFirstBeat) {
  Axi& a = *axi_;
  DeviceMemory mem;
  for (int k = 0; k < 4096; ++k) mem.shell.push_back({0, 0, 0});
  Job j;
  j.mode = Mode::Count;
  j.shell_count = 4096;
  mem.map.assign(map_words(a.cfg, j), 0);
  a.load(mem);
  ASSERT_EQ(a.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
  const int last = a.job_beats + 4;
  for (int wait = 0; wait <= last; ++wait) {
    j.tag = uint32_t(wait);
    a.queue_job(j);
    a.ticks(wait);
    EXPECT_EQ(a.write(uint32_t(kShellBase), 1), kSlverr) << "a shell write " << wait << " cycles after the first beat";
    a.run_until_records(size_t(wait) + 1);
    a.ticks(4);
    EXPECT_EQ(a.write(uint32_t(kShellBase), 0), kOkay) << "and accepted once the job has run";
  }
}

// 4. Added latency: a job alone whose one record is its completion (COUNT), streams always valid and ready: the
// completion's last beat comes exactly cycles + 2 + 1024/JobDw + 256/RecDw cycles after the job's first
// descriptor beat (docs/hardware.md), and cycles is the timing model's at the model's depth.
TEST_P(AxiTest, AddedLatencyIsExact) {
  Axi& a = *axi_;
  const GeneratedVectors g = generate_vectors({seed_, 40, 500, a.cfg, {}});
  a.load(g.memory);
  ASSERT_EQ(a.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
  for (size_t i = 0; i < g.jobs.size(); ++i) {
    Job j = g.jobs[i];
    j.mode = Mode::Count;  // one record: a hit record before it would hold the completion for RecBeats cycles
    const std::vector<Record> want = run_stream(a.cfg, g.memory, {j});
    const std::vector<JobTiming> t = job_timing(a.cfg, g.memory, {j}, want);
    const size_t before = a.records.size();
    a.queue_job(j);
    a.run_until_records(before + want.size());
    const Record& done = a.records.back();
    ASSERT_EQ(done.kind, Record::Done);
    EXPECT_EQ(*done.cycles, t[0].cycles) << "job " << i;
    EXPECT_EQ(a.record_cycle.back() - a.job_first_cycle[i],
              *done.cycles + 2 + uint64_t(a.job_beats) + uint64_t(a.rec_beats))
        << "job " << i << " (" << job_line(j) << ")";
    a.ticks(3);
  }
}

// 5. Generated vectors under random TVALID / TREADY and AXI4-Lite handshakes: ref/'s exact stream; with one-beat
// descriptors the jobs reach the device back to back, so the cycles are the timing model's plus the stalls.
TEST_P(AxiTest, GeneratedVectorsUnderRandomHandshakes) {
  for (double p : {1.0, 0.7, 0.3}) {
    Axi b(models()[GetParam()], seed_ + uint64_t(p * 100));
    b.p_lite = p;
    const GeneratedVectors g = generate_vectors({seed_ + 17, 150, 1500, b.cfg, {}});
    b.load(g.memory);
    ASSERT_EQ(b.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
    b.p_job_valid = b.job_beats == 1 ? 1.0 : p;
    b.p_rec_ready = p;
    for (const Job& j : g.jobs) b.queue_job(j);
    const std::vector<Record> want = run_stream(b.cfg, g.memory, g.jobs);
    b.run_until_records(want.size());
    expect_stream(b, g.memory, g.jobs, b.records, b.job_beats == 1, seed_);
    // The counters add up the completion records.
    uint64_t hits = 0, points = 0, cycles = 0, stalls = 0;
    for (const Record& r : b.records)
      if (r.kind == Record::Done) {
        hits += r.hits;
        points += *r.points;
        cycles += *r.cycles;
        stalls += *r.stalls;
      }
    b.ticks(4);
    EXPECT_EQ(b.reg(kRegJobsDone), g.jobs.size());
    EXPECT_EQ(b.reg(kRegHits), hits);
    EXPECT_EQ(b.reg(kRegPoints), points);
    EXPECT_EQ(b.reg(kRegCycles), cycles);
    EXPECT_EQ(b.reg(kRegStalls), stalls);
    EXPECT_EQ(b.reg(kRegShellWords), g.memory.shell.size());
    EXPECT_EQ(b.reg(kRegMapWords), g.memory.map.size());
    EXPECT_EQ(b.reg(kRegStatus), 0u);
    if (p < 1) {
      EXPECT_GT(stalls, 0u) << "record back-pressure at " << p << " never stalled the device";
    }
    EXPECT_TRUE(b.errors.empty()) << join(b.errors) << "seed " << seed_;
  }
}

// 6. The vector files of tests/vectors whose widths this model has: their expected records.
TEST_P(AxiTest, VectorFiles) {
  int ran = 0;
  for (const char* f : {"hand_basic.vec", "hand_format.vec"}) {
    const VectorFile v = read_vectors(std::string(VOXCD_VECTORS_DIR) + "/" + f);
    DeviceConfig c = v.config;
    c.LANES = axi_->cfg.LANES;
    c.depth = axi_->cfg.depth;  // the files have no cycles to compare: any depth gives their records
    c.BL = axi_->cfg.BL;        // and a sparse device runs their dense jobs with the same records
    if (!(c == axi_->cfg) || (v.has_lanes && v.config.LANES != axi_->cfg.LANES)) continue;
    Axi a(models()[GetParam()], seed_);
    a.p_lite = a.p_rec_ready = a.p_job_valid = 0.6;
    a.load(v.memory);
    ASSERT_EQ(a.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
    for (const Job& j : v.jobs) a.queue_job(j);
    a.run_until_records(v.expected.size());
    EXPECT_EQ(compare_streams(v, a.records, false), "") << f;
    EXPECT_TRUE(a.errors.empty()) << join(a.errors);
    ++ran;
  }
  // The hand-written files are of 2-bit devices; a distance top runs generated vectors (the tests above and below).
  if (!axi_->cfg.distance()) {
    EXPECT_GT(ran, 0) << "no vector file has this model's widths";
  }
}

// 7. A descriptor whose frame is wrong is dropped and counted; one that breaks a rule of the contract is answered
// with an error record (its tag, the rule) in its place in the stream, and counted; the jobs around them run as if
// they were not there.
TEST_P(AxiTest, MalformedDescriptorsAreRefused) {
  Axi& a = *axi_;
  a.p_job_valid = a.p_rec_ready = 0.7;
  const GeneratedVectors g = generate_vectors({seed_ + 5, 12, 300, a.cfg, {}});
  a.load(g.memory);
  ASSERT_EQ(a.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
  std::vector<uint8_t> good(kJobBytes);
  int dropped = 0;
  std::vector<Axi::Refusal> want_refused;  // the error records, where they come in the stream
  std::vector<Job> ran;
  size_t before = 0;                  // records of the jobs that ran so far
  const uint32_t faults[] = {kFaultMode, kFaultDescriptor, kFaultDims, kFaultTag, kFaultShell, 0};
  for (size_t i = 0; i < g.jobs.size(); ++i) {
    a.queue_job(g.jobs[i]);
    ran.push_back(g.jobs[i]);
    before = run_stream(a.cfg, g.memory, ran).size();
    std::vector<uint8_t> bad = sparse_descriptor(g.jobs[i]);
    const uint32_t tag = 1000 + uint32_t(i);
    put_le(&bad[0x00], tag, 4);
    switch (i % 6) {
      case 0: bad[0x04] = 3; break;                       // mode 3
      case 1: bad[0x70] = 1; break;                       // a reserved byte
      case 2: std::memset(&bad[0x14], 0, 4); break;       // nx = 0
      case 3: put_le(&bad[0x00], 1u << a.cfg.TAGW, 4); break;  // a tag wider than TAGW
      case 4: put_le(&bad[0x0c], g.memory.shell.size() + 1, 4); break;  // past the loaded shell words
      case 5: break;                                      // framing, below
    }
    if (i % 6 != 5) want_refused.push_back({before, i % 6 == 3 ? 1u << a.cfg.TAGW : tag, faults[i % 6]});
    if (i % 6 != 5) {
      a.queue_bytes(bad, a.job_beats);
    } else if (a.job_beats > 1) {
      a.queue_bytes(bad, a.job_beats - 1);  // TLAST one beat early
    } else {
      a.queue_bytes(bad, 1, false);         // no TLAST: the next beat belongs to it too
      a.queue_bytes(bad, 1);
    }
    ++dropped;
  }
  a.queue_bytes(good, a.job_beats + 1);  // TLAST one beat late (all-zero bytes: also nx = 0)
  ++dropped;
  // TLAST a whole turn of the beat counter late (it counts to a power of two, at least 2): a counter that kept
  // counting past the frame's last beat would end this one on a frame's last beat and take it.
  const int turn = a.job_beats > 1 ? a.job_beats : 2;
  a.queue_bytes(good, a.job_beats + turn);
  ++dropped;
  a.queue_job(g.jobs[0]);
  std::vector<Job> jobs = g.jobs;
  jobs.push_back(g.jobs[0]);
  const std::vector<Record> want = run_stream(a.cfg, g.memory, jobs);
  a.run_until_records(want.size());
  expect_stream(a, g.memory, jobs, a.records, false, seed_);
  ASSERT_EQ(a.refusals.size(), want_refused.size());
  for (size_t k = 0; k < want_refused.size(); ++k) {
    EXPECT_EQ(a.refusals[k].at, want_refused[k].at) << "error record " << k << " out of its place";
    EXPECT_EQ(a.refusals[k].tag, want_refused[k].tag) << "error record " << k;
    EXPECT_EQ(a.refusals[k].faults, want_refused[k].faults) << "error record " << k;
  }
  EXPECT_EQ(a.reg(kRegDropped), uint64_t(dropped));
  EXPECT_EQ(a.reg(kRegJobsDone), jobs.size());
}

// A random descriptor near the rules' boundaries: a generated job with none, one or several fields pushed over (or
// onto) the edge of what the device and the loaded memory allow. Returns its bytes and the faults ref/ gives it.
std::vector<uint8_t> random_descriptor(const DeviceConfig& cfg, const DeviceMemory& mem, Job j, std::mt19937_64& rng,
                                       uint32_t& faults) {
  auto pick = [&](uint64_t n) { return std::uniform_int_distribution<uint64_t>(0, n - 1)(rng); };
  const uint64_t loaded_shell = mem.shell.size(), loaded_map = mem.map.size();
  bool reserved = false;
  const int changes = int(pick(3));  // 0, 1 or 2 fields changed
  // Half the changed fields just past their limit, half anywhere in the descriptor's 32 bits (every bit of the
  // descriptor's fields and of the sums the top checks them with toggles).
  auto any32 = [&] { return uint32_t(rng()); };
  for (int c = 0; c < changes; ++c) {
    const bool anywhere = pick(2);
    switch (pick(cfg.sparse() ? 15 : 14)) {
      case 0: j.mode = Mode(3); break;
      case 1: j.hit_mask = uint8_t(16 + pick(240)); break;
      case 2: j.tag = anywhere ? any32() : uint32_t((uint64_t{1} << cfg.TAGW) + pick(1000)); break;
      case 3:  // up to the end, or past it
        j.shell_count = anywhere ? any32() : uint32_t(loaded_shell - j.shell_base + pick(3));
        break;
      case 4:
        j.shell_base = anywhere ? any32() : uint32_t((uint64_t{1} << cfg.SAW) + pick(4)), j.shell_count = 0;
        break;
      case 5:
        (pick(3) == 0 ? j.nx : pick(2) ? j.ny : j.nz) =
            anywhere ? any32() : pick(2) ? 0 : uint32_t(cfg.max_dim() + 1 + pick(5));
        break;
      case 6: {  // the map's last word at, or one or two past, the last loaded word
        const uint64_t words = map_words(cfg, j);
        if (words <= loaded_map) j.map_base = uint32_t(loaded_map - words + pick(3));
        break;
      }
      case 7: j.map_base = anywhere ? any32() : uint32_t((uint64_t{1} << cfg.MAW) + pick(8)); break;
      case 8: j.M[pick(3)][pick(3)] = pick(2) ? (int64_t{1} << (cfg.MW - 1)) : -(int64_t{1} << (cfg.MW - 1)) - 1; break;
      case 9: j.t[pick(3)] = pick(2) ? (int64_t{1} << (cfg.TW - 1)) : -(int64_t{1} << (cfg.TW - 1)) - 1; break;
      case 10: j.threshold = int64_t(pick(5)) - 2; break;  // 0 is the only threshold of a 2-bit device
      case 11: reserved = true; break;
      case 12: j.sparse ^= uint8_t(1 + pick(3)); break;  // a map or shell made sparse (or dense)
      case 13: (pick(2) ? j.brick_base : j.brick_units) = anywhere ? any32() : uint32_t(1 + pick(8)); break;
      case 14: {  // a sparse map's bricks up to, or one or two words past, the end of the loaded words
        const uint64_t words = brick_words(cfg, j);
        if (j.sparse_map() && words <= loaded_map) j.brick_base = uint32_t(loaded_map - words + pick(3));
        break;
      }
    }
  }
  std::vector<uint8_t> bytes = sparse_descriptor(j);
  if (reserved) {
    // A reserved bit of the sparse byte (so also the rule of sparse bits other than 0 and 1), byte 0x07, or a
    // reserved byte after brick_base.
    const uint64_t where = pick(3);
    if (where == 0) bytes[kSparseByte] |= uint8_t(4 << pick(6));
    else bytes[where == 1 ? kSparseByte + 1 : kReservedFrom + pick(kJobBytes - kReservedFrom)] = uint8_t(1 + pick(255));
    j.sparse = bytes[kSparseByte];
  }
  faults = job_faults(cfg, j, loaded_shell, loaded_map) | (reserved ? kFaultDescriptor : 0u);
  return bytes;
}

// The records of jobs that ran in `runs` (split where a refused descriptor came between them) against ref/'s, run by
// run; with one-beat descriptors the jobs of a run reach the device back to back (the first after a refusal an idle
// device), so their cycles are the timing model's plus the stalls.
void expect_runs(const Axi& a, const DeviceMemory& mem, const std::vector<std::vector<Job>>& runs, uint64_t seed) {
  size_t at = 0;
  for (const std::vector<Job>& run : runs) {
    std::vector<Record> want = run_stream(a.cfg, mem, run);
    annotate_cycles(a.cfg, mem, run, want);
    for (size_t i = 0; i < want.size(); ++i, ++at) {
      ASSERT_LT(at, a.records.size());
      ASSERT_TRUE(a.records[at].same_as(want[i], false))
          << "record " << at << ": got " << a.records[at].to_string(true) << ", want " << want[i].to_string(true)
          << "; seed " << seed;
      if (a.job_beats == 1 && want[i].kind == Record::Done) {
        ASSERT_EQ(*a.records[at].cycles, *want[i].cycles + *a.records[at].stalls)
            << "record " << at << ": cycles = timing model + stalls; seed " << seed;
      }
    }
  }
  EXPECT_EQ(at, a.records.size());
}

// 8. Random descriptors, about half of them refused: the records of the jobs that run are ref/'s, each refused
// descriptor is one error record, in its place, with its tag and exactly the faults ref/'s job_faults gives. With
// one-beat descriptors the jobs between two refusals reach the device back to back (and the first job after a
// refusal an idle device), so their cycles are the timing model's, stream by stream, plus the stalls.
// Sends each descriptor of `sent` (its bytes, and the faults ref/'s job_faults gives it) on a running top loaded
// with `mem`, then checks that every refused one is one error record, in its place, with its tag and exactly those
// faults, and that the jobs between them run as ref/'s (expect_runs).
void expect_descriptors(Axi& a, const DeviceMemory& mem,
                        const std::vector<std::pair<std::vector<uint8_t>, uint32_t>>& sent, uint64_t seed,
                        size_t min_refused, size_t min_run, size_t min_kinds) {
  std::vector<Axi::Refusal> want_refused;
  std::vector<std::vector<Job>> runs(1);  // the jobs that run, split at the refusals
  std::vector<Job> all;
  size_t records = 0;
  for (const auto& [bytes, faults] : sent) {
    a.queue_bytes(bytes, a.job_beats);
    if (faults) {
      want_refused.push_back({records, uint32_t(get_le(bytes.data(), 4)), faults});
      if (!runs.back().empty()) runs.emplace_back();
      continue;
    }
    Job job;
    std::string why;
    ASSERT_TRUE(decode_sparse_descriptor(bytes, job, why)) << why;
    records += run_stream(a.cfg, mem, {job}).size();
    runs.back().push_back(job);
    all.push_back(job);
  }
  ASSERT_GE(want_refused.size(), min_refused) << "the descriptors must exercise the refusals";
  ASSERT_GE(all.size(), min_run) << "and run jobs between them";
  std::set<uint32_t> kinds;
  for (const Axi::Refusal& r : want_refused)
    for (uint32_t b = 1; b; b <<= 1)
      if (r.faults & b) kinds.insert(b);
  EXPECT_GE(kinds.size(), min_kinds) << "the rules broken";
  a.run_until_records(records);
  for (int i = 0; i < 100000 && a.refusals.size() < want_refused.size(); ++i) a.tick();  // refusals after the last job
  ASSERT_EQ(a.refusals.size(), want_refused.size()) << "seed " << seed;
  for (size_t k = 0; k < want_refused.size(); ++k) {
    ASSERT_EQ(a.refusals[k].at, want_refused[k].at) << "error record " << k << " out of its place; seed " << seed;
    ASSERT_EQ(a.refusals[k].tag, want_refused[k].tag) << "error record " << k << "; seed " << seed;
    ASSERT_EQ(a.refusals[k].faults, want_refused[k].faults) << "error record " << k << " (tag "
                                                            << want_refused[k].tag << "); seed " << seed;
  }
  expect_runs(a, mem, runs, seed);
  EXPECT_EQ(a.reg(kRegDropped), want_refused.size());
  EXPECT_EQ(a.reg(kRegJobsDone), all.size());
  EXPECT_EQ(a.reg(kRegStatus), 0u);
}

TEST_P(AxiTest, RandomDescriptorsAreRefusedAsTheReferenceRefusesThem) {
  Axi& a = *axi_;
  a.p_lite = 0.8;
  a.p_rec_ready = 0.7;
  const GeneratedVectors g = generate_vectors({seed_ + 23, 300, 600, a.cfg, {}});
  a.load(g.memory);
  ASSERT_EQ(a.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
  std::mt19937_64 rng(seed_ * 7 + 1);
  std::vector<std::pair<std::vector<uint8_t>, uint32_t>> sent;
  for (const Job& j : g.jobs) {
    uint32_t faults = 0;
    std::vector<uint8_t> bytes = random_descriptor(a.cfg, g.memory, j, rng, faults);
    sent.emplace_back(std::move(bytes), faults);
  }
  expect_descriptors(a, g.memory, sent, seed_, g.jobs.size() / 4 + 1, g.jobs.size() / 4 + 1, 7);
}

// 9. The map's words at the edge of the loaded words, for every extent of each axis in turn (odd and even, the
// smallest and the largest the device takes): a map whose last word is the last loaded one runs, one a word further
// is refused (the map rule), so the words the top computes for each axis's extent are ref/'s map_words (a dense
// map's states or distance nodes, a sparse map's table). On a sparse device the same for sparse maps, their bricks
// at the start of the memory.
TEST_P(AxiTest, MapAtTheEdgeOfTheLoadedWordsOnEveryAxis) {
  Axi& a = *axi_;
  a.p_rec_ready = 0.8;
  const GeneratedVectors g = generate_vectors({seed_ + 41, 4, 600, a.cfg, {}});
  a.load(g.memory);
  ASSERT_EQ(a.write(uint32_t(kRegBase + kRegRun), 1), kOkay);
  const uint64_t loaded = g.memory.map.size();
  const uint64_t top = a.cfg.max_dim();
  std::vector<uint32_t> extents = {1, 2, 3, 4, 5, 6, 7, 8, 9, 15, 16, 17, 31, 33};
  extents.push_back(uint32_t(top - 1));
  extents.push_back(uint32_t(top));
  std::vector<std::pair<std::vector<uint8_t>, uint32_t>> sent;
  uint32_t tag = 0;
  for (const bool sparse_map : {false, true}) {
    if (sparse_map && !a.cfg.sparse()) continue;
    for (int axis = 0; axis < 3; ++axis) {
      for (const uint32_t n : extents) {
        if (n == 0 || n > top) continue;
        Job j = g.jobs[0];
        j.mode = Mode::Count;
        j.shell_base = 0, j.shell_count = 1;
        j.sparse = sparse_map ? kSparseMap : 0;
        j.brick_base = 0, j.brick_units = 0;
        j.nx = j.ny = j.nz = 3;
        (axis == 0 ? j.nx : axis == 1 ? j.ny : j.nz) = n;
        const uint64_t words = map_words(a.cfg, j);
        if (words > loaded) continue;
        for (const uint64_t past : {0, 1}) {
          j.tag = tag++ & uint32_t(a.cfg.max_tag());
          j.map_base = uint32_t(loaded - words + past);
          if (a.cfg.distance()) j.map_base &= ~7u;  // on a bank boundary; past the edge by 8 words instead
          if (a.cfg.distance() && past) j.map_base = uint32_t(loaded - words + 8);
          sent.emplace_back(sparse_descriptor(j), job_faults(a.cfg, j, g.memory.shell.size(), loaded));
        }
      }
    }
  }
  expect_descriptors(a, g.memory, sent, seed_, sent.size() / 4, sent.size() / 4, 1);
}

std::string model_name(const ::testing::TestParamInfo<size_t>& i) { return models()[i.param].name; }
INSTANTIATE_TEST_SUITE_P(Models, AxiTest, ::testing::Range(size_t{0}, models().size()), model_name);

}  // namespace
}  // namespace voxcd
