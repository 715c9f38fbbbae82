// HostCpu: an initiator standing for the host processor of a virtual platform. Its thread runs posted tasks in
// order; a task loads memories and streams jobs through the device's address map with loosely-timed blocking
// transactions (a quantum keeper holds its local time). It can log every transaction it makes.
#pragma once

#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>

#include <deque>
#include <exception>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/error.h"
#include "voxcd/ref/types.h"

namespace voxcd::sysc {

// An access that got an error response; the message names it and the response.
struct BusError : Error {
  using Error::Error;
};

struct Transaction {
  bool write = false;
  uint64_t address = 0;
  size_t length = 0;
  uint64_t data_hash = 0;  // FNV-1a of the data after the access
  int response = 0;        // tlm::tlm_response_status
  sc_core::sc_time end;    // when the access was done: kernel time plus the annotated delay
  bool operator==(const Transaction& o) const {
    return write == o.write && address == o.address && length == o.length && data_hash == o.data_hash &&
           response == o.response && end == o.end;
  }
  std::string to_string() const;
};

class HostCpu : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(HostCpu);
  tlm_utils::simple_initiator_socket<HostCpu> socket;

  // `burst`: the most bytes one transaction moves.
  HostCpu(sc_core::sc_module_name name, sc_core::sc_time quantum, size_t burst = 4096);

  using Task = std::function<void(HostCpu&)>;
  // Queues a task for the thread (from outside the simulation too). An exception it throws is kept for
  // take_error(). When it has nothing left to do the thread pauses the simulation (sc_pause).
  void post(Task task);
  // Tasks posted and not finished.
  size_t pending() const { return posted_ - finished_; }
  std::exception_ptr take_error();

  // For tasks (they run in the CPU's thread). Each returns the response; the data is little-endian.
  tlm::tlm_response_status access(bool write, uint64_t address, uint8_t* data, size_t length);
  uint64_t read_reg(uint64_t offset);              // throws BusError on an error response
  void write_reg(uint64_t offset, uint64_t value);  // throws BusError on an error response
  // Loads both memories (shell words then voxmap words, in bursts); throws BusError.
  void load(const DeviceMemory& mem);
  // Stages the jobs, launches them as one batch, reads results until every job's completion record has come.
  std::vector<Record> run(const std::vector<Job>& jobs);
  // The same into `out` (replacing its contents, reusing its capacity): the same transactions.
  void run_into(const std::vector<Job>& jobs, std::vector<Record>& out);
  // The same transactions for `jobs` descriptors already encoded (kJobBytes each, ref/address_map.h), leaving the
  // result records as the device gave them (kRecordBytes each, the empty slots after the last one dropped) in
  // `records` (replaced, its capacity reused): for a caller that forwards them as bytes.
  void run_encoded(const uint8_t* descriptors, size_t jobs, std::vector<uint8_t>& records);
  // Spends `t` computing (local time; synchronised at the end of the quantum).
  void compute(sc_core::sc_time t);
  // The CPU's notion of now: kernel time plus its local time.
  sc_core::sc_time now() const;

  bool logging = false;
  std::vector<Transaction> log;

 private:
  void thread();
  void must(tlm::tlm_response_status s, const char* what, uint64_t address);

  tlm_utils::tlm_quantumkeeper qk_;
  size_t burst_;
  std::vector<uint8_t> descriptors_, records_;  // run_into's encoded jobs and records
  std::deque<Task> tasks_;
  sc_core::sc_event task_event_;
  size_t posted_ = 0, finished_ = 0;
  std::exception_ptr error_;
};

}  // namespace voxcd::sysc
