#include "voxcd/sysc/axi_target.h"

#include <verilated.h>

#include "voxcd/ref/vectors.h"
#include "voxcd_sysc_models.h"  // Vvoxcd_sc_axi and VOXCD_SYSC_AXI_PAIRS (sysc/CMakeLists.txt)

namespace voxcd::sysc {

using namespace sc_core;

DeviceConfig axi_target_config() { return parse_config_pairs(VOXCD_SYSC_AXI_PAIRS, "SystemC model Vvoxcd_sc_axi"); }

struct AxiPins {
  sc_signal<bool> rst_ni{"rst_ni", false};
  sc_signal<bool> awvalid{"awvalid"}, awready{"awready"}, wvalid{"wvalid"}, wready{"wready"};
  sc_signal<bool> bvalid{"bvalid"}, bready{"bready", true}, arvalid{"arvalid"}, arready{"arready"};
  sc_signal<bool> rvalid{"rvalid"}, rready{"rready", true};
  sc_signal<uint32_t> awaddr{"awaddr"}, awprot{"awprot"}, wstrb{"wstrb"}, bresp{"bresp"}, araddr{"araddr"},
      arprot{"arprot"}, rresp{"rresp"};
  sc_signal<uint64_t> wdata{"wdata"}, rdata{"rdata"};
  sc_signal<bool> jvalid{"jvalid"}, jready{"jready"}, jlast{"jlast"};
  sc_signal<uint64_t> jdata{"jdata"};
  sc_signal<bool> rec_valid{"rec_valid"}, rec_ready{"rec_ready", true}, rec_last{"rec_last"};
  sc_signal<uint64_t> rec_data{"rec_data"};
};

struct AxiModel {
  AxiModel(const char* name, sc_clock& clk, AxiPins& p) : m(name) {
    m.clk_i(clk);
    m.rst_ni(p.rst_ni);
    m.s_axil_awvalid_i(p.awvalid);
    m.s_axil_awready_o(p.awready);
    m.s_axil_awaddr_i(p.awaddr);
    m.s_axil_awprot_i(p.awprot);
    m.s_axil_wvalid_i(p.wvalid);
    m.s_axil_wready_o(p.wready);
    m.s_axil_wdata_i(p.wdata);
    m.s_axil_wstrb_i(p.wstrb);
    m.s_axil_bvalid_o(p.bvalid);
    m.s_axil_bready_i(p.bready);
    m.s_axil_bresp_o(p.bresp);
    m.s_axil_arvalid_i(p.arvalid);
    m.s_axil_arready_o(p.arready);
    m.s_axil_araddr_i(p.araddr);
    m.s_axil_arprot_i(p.arprot);
    m.s_axil_rvalid_o(p.rvalid);
    m.s_axil_rready_i(p.rready);
    m.s_axil_rdata_o(p.rdata);
    m.s_axil_rresp_o(p.rresp);
    m.s_axis_job_tvalid_i(p.jvalid);
    m.s_axis_job_tready_o(p.jready);
    m.s_axis_job_tdata_i(p.jdata);
    m.s_axis_job_tlast_i(p.jlast);
    m.m_axis_rec_tvalid_o(p.rec_valid);
    m.m_axis_rec_tready_i(p.rec_ready);
    m.m_axis_rec_tdata_o(p.rec_data);
    m.m_axis_rec_tlast_o(p.rec_last);
  }
  Vvoxcd_sc_axi m;
};

namespace {
constexpr int kJobBeats = int(kJobBytes / 8), kRecBeats = int(kRecordBytes / 8);  // 64-bit beats
}

AxiRtlTarget::AxiRtlTarget(sc_module_name name, const DeviceConfig& cfg, sc_time clock_period, sc_time access_latency)
    : ClockedTarget(name, cfg, clock_period, access_latency), pins_(std::make_unique<AxiPins>()) {
  if (!(cfg == axi_target_config()))
    throw std::invalid_argument(std::string(this->name()) + ": the AXI top's SystemC model is built for " +
                                axi_target_config().to_string() + ", not for " + cfg.to_string());
  const std::string mname = std::string(basename()) + "_axi";
  model_ = std::make_unique<AxiModel>(mname.c_str(), clk_, *pins_);
  pins_->wstrb.write(0xff);
  start_clocked_method();
}

AxiRtlTarget::~AxiRtlTarget() {
  Verilated::threadContextp(ctx_.get());
  model_->m.final();
  model_.reset();
}

bool AxiRtlTarget::next_lite_write(uint32_t& addr, uint64_t& data) {
  // RUN once, before the first batch's descriptors.
  if (running_ && !run_written_) {
    addr = uint32_t(kRegBase + kRegRun);
    data = 1;
    run_pending_ = true;
    return true;
  }
  if (!mem_ || !mem_->started || mem_->done) return false;
  const uint64_t k = mem_->first + mem_->written;
  if (mem_->shell) {
    // {x, y} at byte 0, then {z, 0} at byte 8: the second write commits the word.
    const ShellWord& w = mem_->shell_words[mem_->written];
    addr = uint32_t(kShellBase + kShellStride * k + 8 * uint64_t(part_));
    data = part_ == 0 ? (uint64_t(uint32_t(w[0])) | uint64_t(uint32_t(w[1])) << 32) : uint64_t(uint32_t(w[2]));
  } else {
    addr = uint32_t(kMapBase + kMapStride * k);
    data = mem_->map_words[mem_->written];
  }
  return true;
}

void AxiRtlTarget::take_lite_response() {
  AxiPins& p = *pins_;
  if (aw_valid_ && p.awready.read()) aw_valid_ = false;
  if (w_valid_ && p.wready.read()) w_valid_ = false;
  if (!lite_busy_ || !p.bvalid.read()) return;  // bready is always high
  lite_busy_ = false;
  if (p.bresp.read() != 0) fault_ = true;
  if (run_pending_) {
    run_pending_ = false;
    run_written_ = true;
  } else if (lite_is_mem_ && mem_ && (!mem_->shell || ++part_ == 2)) {
    part_ = 0;
    word_written();
  }
}

void AxiRtlTarget::take_job_beat() {
  if (job_valid_ && pins_->jready.read() && ++beat_ == kJobBeats) {
    beat_ = 0;
    ++fed_;
  }
}

void AxiRtlTarget::take_record_beat() {
  AxiPins& p = *pins_;
  if (!p.rec_valid.read()) return;  // rec_ready is always high
  put_le(rec_ + 8 * rec_beat_, p.rec_data.read(), 8);
  if (p.rec_last.read() != (++rec_beat_ == kRecBeats)) fault_ = true;  // a record is exactly 4 beats
  if (rec_beat_ < kRecBeats) return;
  rec_beat_ = 0;
  Record r;
  if (!decode_record(rec_, r)) fault_ = true;
  partial_.push_back(r);
  if (r.kind == Record::Done) job_done();
}

void AxiRtlTarget::drive_lite() {
  AxiPins& p = *pins_;
  uint32_t addr = 0;
  uint64_t data = 0;
  if (!lite_busy_ && next_lite_write(addr, data)) {
    lite_busy_ = aw_valid_ = w_valid_ = true;
    lite_is_mem_ = !run_pending_;
    ++lite_writes_;
    p.awaddr.write(addr);
    p.wdata.write(data);
  }
  p.awvalid.write(aw_valid_);
  p.wvalid.write(w_valid_);
}

void AxiRtlTarget::drive_job() {
  AxiPins& p = *pins_;
  job_valid_ = running_ && run_written_ && fed_ < batches_.front().jobs.size();
  if (job_valid_) {
    if (beat_ == 0) encode_job(batches_.front().jobs[fed_], desc_);
    p.jdata.write(get_le(desc_ + 8 * beat_, 8));
    p.jlast.write(beat_ == kJobBeats - 1);
  }
  p.jvalid.write(job_valid_);
}

void AxiRtlTarget::on_edge() {
  if (first_edge()) {
    pins_->rst_ni.write(true);
  } else {
    take_lite_response();
    take_job_beat();
    take_record_beat();
  }
  // Memory writes start once every launched batch is done (the top refuses them while a job runs).
  start_memory_write(!busy());
  if (start_batch(mem_ && mem_->started && !mem_->done)) beat_ = 0;
  drive_lite();
  drive_job();
  end_edge();
}

}  // namespace voxcd::sysc
