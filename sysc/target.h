// DeviceTarget: what both SystemC targets share: the TLM-2.0 socket, the address map (ref/address_map.h), access
// checks and error responses, the staging of job descriptors, the result queue and the counters. How memory
// writes, batches and time happen is the subclass's: the Verilated RTL (rtl_target.h) or the timing model
// (tlm_target.h).
//
// Time, the same in both (docs/systemc.md): the device's clock has period T and its rising edges at T, 2T, 3T...
// A transaction at time t acts on the device from the first edge strictly after t. A memory write of n words
// takes the write port for n edges once the device is idle; a launched batch starts when the previous one has
// finished and runs its jobs back to back; a job's records become readable together, at the edge at which its
// completion record is taken from the device. Every transaction completes at the time its effect is done, plus
// the access latency (a constructor argument).
#pragma once

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_target_socket.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd::sysc {

class DeviceTarget : public sc_core::sc_module {
 public:
  tlm_utils::simple_target_socket<DeviceTarget> socket;

  DeviceTarget(sc_core::sc_module_name name, const DeviceConfig& cfg, sc_core::sc_time clock_period,
               sc_core::sc_time access_latency);
  const DeviceConfig& config() const { return cfg_; }
  sc_core::sc_time clock_period() const { return period_; }
  // Why the last access got an error response ("" if none did).
  const std::string& last_error() const { return last_error_; }

 protected:
  // The transaction's start time; the RTL target first waits until then (its pins live in simulated time).
  virtual sc_core::sc_time start(sc_core::sc_time& delay) = 0;
  // Writes words [first, first + n) of the shell or voxmap memory at time t; returns when the write is done.
  virtual sc_core::sc_time write_shell(uint64_t first, const std::vector<ShellWord>& words, sc_core::sc_time t) = 0;
  virtual sc_core::sc_time write_map(uint64_t first, const std::vector<uint64_t>& words, sc_core::sc_time t) = 0;
  // Launches jobs (valid for the loaded memory) as one batch at time t. The target may take the vector's contents;
  // the caller clears it afterwards (and so keeps its capacity when the target only read it).
  virtual void launch(std::vector<Job>& jobs, sc_core::sc_time t) = 0;
  // Makes every job whose records are readable at t readable (publish()).
  virtual void advance_to(sc_core::sc_time t) = 0;
  // From t, the time at which at least n records are readable or no launched batch is left; publishes up to then.
  virtual sc_core::sc_time await_results(size_t n, sc_core::sc_time t) = 0;
  // After advance_to(t): a launched batch has not finished.
  virtual bool busy() const = 0;
  // The RTL reported an assertion failure: every later access fails.
  virtual bool faulted() const { return false; }

  // Makes one job's records (hits, then its completion record) readable and counts them, with the bank conflict
  // cycles the device counted up to its completion (shared voxmap banks; 0 otherwise).
  void publish(const Record* job_records, size_t n, uint64_t conflicts = 0);
  void publish(const std::vector<Record>& job_records, uint64_t conflicts = 0) {
    publish(job_records.data(), job_records.size(), conflicts);
  }
  // The result queue holds encoded records (kRecordBytes each, ref/address_map.h): the readable ones, then those a
  // target queued ahead of time and has not made readable yet. queue_records appends n slots after everything
  // queued and returns them for the caller to fill (valid until the next call); publish_queued makes the next n
  // queued records, one job's, readable and adds the job's counts.
  struct JobCounts {
    uint64_t hits = 0, points = 0, cycles = 0, stalls = 0;
    uint64_t conflicts = 0;  // bank conflict cycles (shared voxmap banks)
  };
  uint8_t* queue_records(size_t n);
  void publish_queued(size_t n, const JobCounts& counts);
  size_t readable() const { return (ready_ - head_) / kRecordBytes; }
  // Edge index k of the first rising edge strictly after t (edges at k * T, k >= 1).
  uint64_t edge_after(sc_core::sc_time t) const;
  // The last edge at or before t (0 before the first).
  uint64_t edge_at_or_before(sc_core::sc_time t) const;
  sc_core::sc_time edge_time(uint64_t k) const { return sc_core::sc_time::from_value(k * period_.value()); }

  const DeviceConfig cfg_;
  const sc_core::sc_time period_;
  const sc_core::sc_time latency_;

 private:
  // One transaction's address, length, data and direction.
  struct Access {
    uint64_t addr = 0;
    size_t len = 0;
    uint8_t* data = nullptr;
    bool wr = false;
    bool in(uint64_t base, uint64_t size) const { return addr >= base && addr - base < size; }
    bool fits(uint64_t base, uint64_t size) const { return addr - base + len <= size; }
  };

  void b_transport(tlm::tlm_generic_payload& tr, sc_core::sc_time& delay);
  tlm::tlm_response_status access(tlm::tlm_generic_payload& tr, sc_core::sc_time t, sc_core::sc_time& done);
  // The windows of the address map (ref/address_map.h), each with its own checks.
  tlm::tlm_response_status reg_access(const Access& a, sc_core::sc_time t);
  tlm::tlm_response_status stage_jobs(const Access& a);
  tlm::tlm_response_status read_results(const Access& a, sc_core::sc_time t, sc_core::sc_time& done);
  tlm::tlm_response_status shell_access(const Access& a, sc_core::sc_time t, sc_core::sc_time& done);
  tlm::tlm_response_status map_access(const Access& a, sc_core::sc_time t, sc_core::sc_time& done);
  std::optional<tlm::tlm_response_status> check_memory_write(const Access& a, uint64_t base, uint64_t stride,
                                                             uint64_t depth, const std::string& memory);
  tlm::tlm_response_status reg_read(uint64_t off, uint8_t* data, sc_core::sc_time t);
  tlm::tlm_response_status fail(tlm::tlm_response_status s, std::string why);

  // Copies up to n readable records to `out` (the slots after them read as zero) and removes them from the queue.
  void take_records(uint8_t* out, size_t n);

  // Jobs staged_[0, staged_count_) are staged. The vector keeps the size it had (a target that only reads the
  // jobs it launches leaves them), so staging decodes into jobs that exist instead of constructing new ones.
  std::vector<Job> staged_;
  size_t staged_count_ = 0;
  // The result queue: bytes [head_, ready_) readable, [ready_, end_) queued; capacity cap_. Not a std::vector: growing
  // it would zero bytes that are written right after.
  std::unique_ptr<uint8_t[]> results_;
  size_t head_ = 0, ready_ = 0, end_ = 0, cap_ = 0;
  uint64_t shell_words_ = 0, map_words_ = 0;
  uint64_t jobs_done_ = 0, hits_ = 0, points_ = 0, cycles_ = 0, stalls_ = 0, conflicts_ = 0;
  std::string last_error_;
};

}  // namespace voxcd::sysc
