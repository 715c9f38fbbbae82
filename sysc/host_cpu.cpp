#include "voxcd/sysc/host_cpu.h"

#include <algorithm>
#include <cstdio>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/fnv1a.h"

namespace voxcd::sysc {

using namespace sc_core;

std::string Transaction::to_string() const {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s 0x%08llx %6zu bytes data %016llx response %d at %s", write ? "write" : "read ",
                (unsigned long long)address, length, (unsigned long long)data_hash, response, end.to_string().c_str());
  return buf;
}

HostCpu::HostCpu(sc_module_name name, sc_time quantum, size_t burst)
    : sc_module(name), socket("socket"), burst_(std::max<size_t>(burst, kJobBytes)) {
  tlm::tlm_global_quantum::instance().set(quantum);
  qk_.reset();
  SC_THREAD(thread);
}

void HostCpu::post(Task task) {
  tasks_.push_back(std::move(task));
  ++posted_;
  task_event_.notify(SC_ZERO_TIME);
}

std::exception_ptr HostCpu::take_error() {
  std::exception_ptr e = error_;
  error_ = nullptr;
  return e;
}

void HostCpu::compute(sc_time t) {
  qk_.inc(t);
  if (qk_.need_sync()) qk_.sync();
}

sc_time HostCpu::now() const { return sc_time_stamp() + qk_.get_local_time(); }

void HostCpu::thread() {
  for (;;) {
    // Nothing to do: let sc_start() return to whoever posts the next task.
    while (tasks_.empty()) {
      sc_pause();
      wait(task_event_);
    }
    Task task = std::move(tasks_.front());
    tasks_.pop_front();
    try {
      task(*this);
    } catch (...) {
      if (!error_) error_ = std::current_exception();
    }
    qk_.sync();
    ++finished_;
  }
}

tlm::tlm_response_status HostCpu::access(bool write, uint64_t address, uint8_t* data, size_t length) {
  tlm::tlm_generic_payload tr;
  tr.set_command(write ? tlm::TLM_WRITE_COMMAND : tlm::TLM_READ_COMMAND);
  tr.set_address(address);
  tr.set_data_ptr(data);
  tr.set_data_length(unsigned(length));
  tr.set_streaming_width(unsigned(length));
  tr.set_byte_enable_ptr(nullptr);
  tr.set_dmi_allowed(false);
  tr.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  sc_time delay = qk_.get_local_time();
  socket->b_transport(tr, delay);
  qk_.set(delay);
  if (logging) {
    log.push_back({write, address, length, fnv1a(data, length), int(tr.get_response_status()),
                   sc_time_stamp() + delay});
  }
  if (qk_.need_sync()) qk_.sync();
  return tr.get_response_status();
}

void HostCpu::must(tlm::tlm_response_status s, const char* what, uint64_t address) {
  if (s == tlm::TLM_OK_RESPONSE) return;
  tlm::tlm_generic_payload p;
  p.set_response_status(s);
  throw BusError(std::string(name()) + ": " + what + " at address " + std::to_string(address) + " got " +
                 p.get_response_string());
}

uint64_t HostCpu::read_reg(uint64_t offset) {
  uint8_t b[8] = {};
  must(access(false, kRegBase + offset, b, 8), "register read", kRegBase + offset);
  return get_le(b, 8);
}

void HostCpu::write_reg(uint64_t offset, uint64_t value) {
  uint8_t b[8];
  put_le(b, value, 8);
  must(access(true, kRegBase + offset, b, 8), "register write", kRegBase + offset);
}

void HostCpu::load(const DeviceMemory& mem) {
  std::vector<uint8_t> buf;
  const size_t shell_burst = burst_ / kShellStride;
  for (size_t k = 0; k < mem.shell.size(); k += shell_burst) {
    const size_t n = std::min(shell_burst, mem.shell.size() - k);
    buf.assign(n * kShellStride, 0);
    for (size_t i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) put_le(&buf[i * kShellStride + 4 * size_t(c)], uint64_t(mem.shell[k + i][c]), 4);
    const uint64_t a = kShellBase + k * kShellStride;
    must(access(true, a, buf.data(), buf.size()), "shell write", a);
  }
  const size_t map_burst = burst_ / kMapStride;
  for (size_t k = 0; k < mem.map.size(); k += map_burst) {
    const size_t n = std::min(map_burst, mem.map.size() - k);
    buf.assign(n * kMapStride, 0);
    for (size_t i = 0; i < n; ++i) put_le(&buf[i * kMapStride], mem.map[k + i], 8);
    const uint64_t a = kMapBase + k * kMapStride;
    must(access(true, a, buf.data(), buf.size()), "voxmap write", a);
  }
}

std::vector<Record> HostCpu::run(const std::vector<Job>& jobs) {
  std::vector<Record> out;
  run_into(jobs, out);
  return out;
}

void HostCpu::run_into(const std::vector<Job>& jobs, std::vector<Record>& out) {
  descriptors_.resize(jobs.size() * kJobBytes);
  for (size_t i = 0; i < jobs.size(); ++i) encode_job(jobs[i], &descriptors_[i * kJobBytes]);
  run_encoded(descriptors_.data(), jobs.size(), records_);
  out.resize(records_.size() / kRecordBytes);
  for (size_t i = 0; i < out.size(); ++i) decode_record(&records_[i * kRecordBytes], out[i]);
}

void HostCpu::run_encoded(const uint8_t* descriptors, size_t jobs, std::vector<uint8_t>& records) {
  const size_t job_burst = burst_ / kJobBytes;
  for (size_t k = 0; k < jobs; k += job_burst) {
    const size_t n = std::min(job_burst, jobs - k);
    // The target only reads the data of a write: the descriptors go out from where they are.
    uint8_t* d = const_cast<uint8_t*>(descriptors + k * kJobBytes);
    must(access(true, kJobBase, d, n * kJobBytes), "job write", kJobBase);
  }
  write_reg(kRegRun, 1);
  // Each read lands after the records already taken, in slots zeroed first (resize); the empty slots after the
  // last record are dropped.
  records.clear();
  if (records.capacity() < 2 * jobs * kRecordBytes) records.reserve(2 * jobs * kRecordBytes);
  size_t done = 0;
  const size_t rec_burst = std::max<size_t>(1, burst_ / kRecordBytes);
  while (done < jobs) {
    const size_t at = records.size();
    records.resize(at + rec_burst * kRecordBytes);
    must(access(false, kResultBase, &records[at], rec_burst * kRecordBytes), "result read", kResultBase);
    size_t got = 0;
    for (const uint8_t* r = &records[at]; got < rec_burst && (r[0] == kKindHit || r[0] == kKindDone);
         ++got, r += kRecordBytes)
      done += r[0] == kKindDone;
    records.resize(at + got * kRecordBytes);
    if (got == 0)
      throw BusError(std::string(name()) + ": the device is idle after " + std::to_string(done) + " of " +
                     std::to_string(jobs) + " completion records");
  }
}

}  // namespace voxcd::sysc
