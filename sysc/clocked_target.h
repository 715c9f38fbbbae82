// ClockedTarget: what both Verilated targets share (RtlTarget: the device's pins, AxiRtlTarget: the AXI top's): the
// model's own VerilatedContext and clock, the memory request and the launched batches that the clocked method serves
// at the rising edges, and the waits of b_transport on them. The subclass owns the model and its pins and says what
// one edge does (on_edge) with the steps here.
//
// Time as in DeviceTarget (target.h): b_transport first waits out its annotated delay, then until the clocked
// method has done the access; a memory write starts at an edge strictly after its time once the device is idle, a
// batch at an edge strictly after its launch once no memory write is in progress.
#pragma once

#include <deque>
#include <memory>
#include <vector>

#include "voxcd/sysc/target.h"

class VerilatedContext;

namespace voxcd::sysc {

class ClockedTarget : public DeviceTarget {
 public:
  SC_HAS_PROCESS(ClockedTarget);
  // Clock edges simulated so far.
  uint64_t edges() const { return edge_; }

 protected:
  // Makes the target's VerilatedContext (failed assertions fault the target instead of ending the process) and
  // makes it the calling thread's, so that the model the subclass constructs next takes it; rising edges at T, 2T...
  ClockedTarget(sc_core::sc_module_name name, const DeviceConfig& cfg, sc_core::sc_time clock_period,
                sc_core::sc_time access_latency);
  ~ClockedTarget() override;

  // One memory write transaction: its words go to the device one by one from the edge it starts at.
  struct MemRequest {
    sc_core::sc_time time;
    bool shell = true;
    uint64_t first = 0;
    std::vector<ShellWord> shell_words;
    std::vector<uint64_t> map_words;
    size_t size() const { return shell ? shell_words.size() : map_words.size(); }
    bool started = false;
    size_t written = 0;  // whole words
    bool done = false;
  };
  struct Batch {
    sc_core::sc_time time;
    std::vector<Job> jobs;
  };

  // What one rising edge does: first what happened at this edge (the outputs read now are the values the edge
  // sampled), then the inputs for the next edge. The subclass registers it with start_clocked_method().
  virtual void on_edge() = 0;
  void start_clocked_method();

  // Steps of on_edge. Counts the edge; true at the first one, which resets the device.
  bool first_edge() { return ++edge_ == 1; }
  // The device took the current memory word: the request is done after its last one.
  void word_written();
  // A completion record ended the job whose records partial_ holds: makes them readable (with the bank conflict
  // cycles since the previous completion) and ends the batch after its last job.
  void job_done(uint64_t conflicts = 0);
  // Starts the waiting memory request when it is due and `idle` says the device may take it.
  void start_memory_write(bool idle);
  // Starts the next launched batch when it is due and no memory write is in progress; true if it did.
  bool start_batch(bool writing);
  // Faults the target on a failed assertion (and wakes every waiting transaction when faulted); ends the edge.
  void end_edge();

  bool busy() const override { return running_ || !batches_.empty(); }
  bool faulted() const override { return fault_; }

  std::unique_ptr<VerilatedContext> ctx_;
  sc_core::sc_clock clk_;
  sc_core::sc_event edge_event_, results_event_, mem_event_;
  uint64_t edge_ = 0;
  bool fault_ = false;
  MemRequest* mem_ = nullptr;   // the write transaction waiting or in progress
  std::deque<Batch> batches_;   // launched; the front one runs when running_
  bool running_ = false;
  bool job_valid_ = false;      // a job is offered to the device in this cycle
  size_t fed_ = 0, completed_ = 0;  // jobs of the running batch the device took, and completed
  std::vector<Record> partial_;     // records of the job being completed

 private:
  sc_core::sc_time start(sc_core::sc_time& delay) override;
  sc_core::sc_time write_shell(uint64_t first, const std::vector<ShellWord>& words, sc_core::sc_time t) override;
  sc_core::sc_time write_map(uint64_t first, const std::vector<uint64_t>& words, sc_core::sc_time t) override;
  sc_core::sc_time write_memory(MemRequest& req);
  void launch(std::vector<Job>& jobs, sc_core::sc_time t) override;
  void advance_to(sc_core::sc_time t) override;
  sc_core::sc_time await_results(size_t n, sc_core::sc_time t) override;
};

}  // namespace voxcd::sysc
