#include "voxcd/sysc/target.h"

#include <algorithm>
#include <cstring>
#include <optional>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd::sysc {

using namespace sc_core;
using tlm::tlm_response_status;

DeviceTarget::DeviceTarget(sc_module_name name, const DeviceConfig& cfg, sc_time clock_period, sc_time access_latency)
    : sc_module(name), socket("socket"), cfg_(cfg), period_(clock_period), latency_(access_latency) {
  cfg_.validate();
  if (period_ == SC_ZERO_TIME) throw std::invalid_argument(std::string(basename()) + ": the clock period is zero");
  socket.register_b_transport(this, &DeviceTarget::b_transport);
}

uint64_t DeviceTarget::edge_after(sc_time t) const { return t.value() / period_.value() + 1; }
uint64_t DeviceTarget::edge_at_or_before(sc_time t) const { return t.value() / period_.value(); }

void DeviceTarget::publish(const Record* job_records, size_t n, uint64_t conflicts) {
  uint8_t* out = queue_records(n);
  JobCounts c;
  c.conflicts = conflicts;
  for (size_t i = 0; i < n; ++i) {
    const Record& r = job_records[i];
    encode_record(r, out + i * kRecordBytes);
    if (r.kind != Record::Done) continue;
    c.hits += r.hits;
    c.points += r.points.value_or(0);
    c.cycles += r.cycles.value_or(0);
    c.stalls += r.stalls.value_or(0);
  }
  publish_queued(n, c);
}

uint8_t* DeviceTarget::queue_records(size_t n) {
  const size_t bytes = n * kRecordBytes;
  if (head_ > 0 && end_ + bytes > cap_) {
    // Move what is left to the front before growing.
    std::memmove(results_.get(), results_.get() + head_, end_ - head_);
    ready_ -= head_;
    end_ -= head_;
    head_ = 0;
  }
  if (end_ + bytes > cap_) {
    const size_t cap = std::max(end_ + bytes, 2 * cap_);
    std::unique_ptr<uint8_t[]> grown(new uint8_t[cap]);
    if (end_) std::memcpy(grown.get(), results_.get(), end_);
    results_ = std::move(grown);
    cap_ = cap;
  }
  uint8_t* out = results_.get() + end_;
  end_ += bytes;
  return out;
}

void DeviceTarget::publish_queued(size_t n, const JobCounts& c) {
  ready_ += n * kRecordBytes;
  ++jobs_done_;
  hits_ += c.hits;
  points_ += c.points;
  cycles_ += c.cycles;
  stalls_ += c.stalls;
  conflicts_ += c.conflicts;
}

void DeviceTarget::take_records(uint8_t* out, size_t n) {
  const size_t bytes = std::min(n * kRecordBytes, ready_ - head_);
  if (bytes) std::memcpy(out, results_.get() + head_, bytes);
  if (bytes < n * kRecordBytes) std::memset(out + bytes, 0, n * kRecordBytes - bytes);
  head_ += bytes;
  if (head_ == end_) head_ = ready_ = end_ = 0;  // nothing left: start again at the front
}

tlm_response_status DeviceTarget::fail(tlm_response_status s, std::string why) {
  last_error_ = std::string(name()) + ": " + why;
  return s;
}

void DeviceTarget::b_transport(tlm::tlm_generic_payload& tr, sc_time& delay) {
  const sc_time t = start(delay);
  sc_time done = t;
  tr.set_response_status(access(tr, t, done));
  delay = done + latency_ - sc_time_stamp();
}

// Checks the transaction's form and routes it to the window its address is in.
tlm_response_status DeviceTarget::access(tlm::tlm_generic_payload& tr, sc_time t, sc_time& done) {
  using namespace tlm;
  const Access a{tr.get_address(), tr.get_data_length(), tr.get_data_ptr(), tr.get_command() == TLM_WRITE_COMMAND};
  if (tr.get_command() == TLM_IGNORE_COMMAND) return TLM_OK_RESPONSE;
  if (tr.get_byte_enable_ptr()) return fail(TLM_BYTE_ENABLE_ERROR_RESPONSE, "byte enables are not supported");
  if (tr.get_streaming_width() < a.len) return fail(TLM_BURST_ERROR_RESPONSE, "streaming is not supported");
  if (a.len == 0 || !a.data) return fail(TLM_BURST_ERROR_RESPONSE, "an access of zero bytes");
  // A faulted RTL can still say so through its registers.
  if (faulted() && (a.wr || !a.in(kRegBase, kRegSize)))
    return fail(TLM_GENERIC_ERROR_RESPONSE, "the RTL has failed an assertion");
  if (a.in(kRegBase, kRegSize)) return reg_access(a, t);
  if (a.in(kJobBase, kJobSize)) return stage_jobs(a);
  if (a.in(kResultBase, kResultSize)) return read_results(a, t, done);
  if (a.in(kShellBase, cfg_.shell_depth() * kShellStride)) return shell_access(a, t, done);
  if (a.in(kMapBase, cfg_.map_depth() * kMapStride)) return map_access(a, t, done);
  return fail(TLM_ADDRESS_ERROR_RESPONSE, "no window at this address");
}

// A register access: a read, or the write of RUN, which launches the staged jobs as one batch.
tlm_response_status DeviceTarget::reg_access(const Access& a, sc_time t) {
  using namespace tlm;
  const uint64_t off = a.addr - kRegBase;
  if (a.len != 8 || off % 8) return fail(TLM_BURST_ERROR_RESPONSE, "registers take aligned 8-byte accesses");
  if (!a.wr) return reg_read(off, a.data, t);
  if (off != kRegRun) {
    if (off <= kRegConflicts) return fail(TLM_COMMAND_ERROR_RESPONSE, "register is read-only");
    return fail(TLM_ADDRESS_ERROR_RESPONSE, "no register at this offset");
  }
  if (staged_count_) {
    staged_.resize(staged_count_);
    launch(staged_, t);
    staged_count_ = 0;
  }
  return TLM_OK_RESPONSE;
}

// A write of whole job descriptors to the job window: each is decoded and checked, then staged.
tlm_response_status DeviceTarget::stage_jobs(const Access& a) {
  using namespace tlm;
  if (!a.wr) return fail(TLM_COMMAND_ERROR_RESPONSE, "the job window is write-only");
  if (a.addr != kJobBase || a.len % kJobBytes || !a.fits(kJobBase, kJobSize))
    return fail(TLM_BURST_ERROR_RESPONSE, "write whole job descriptors at the job window's base");
  // Decoded in place after the staged jobs; they count as staged once the whole transaction is accepted.
  const size_t n = a.len / kJobBytes, old = staged_count_;
  if (staged_.size() < old + n) staged_.resize(old + n);
  std::string why;
  for (size_t i = 0; i < n; ++i) {
    if (!decode_job(a.data + i * kJobBytes, staged_[old + i], why))
      return fail(TLM_GENERIC_ERROR_RESPONSE, "descriptor " + std::to_string(i) + ": " + why);
    try {
      validate_job(cfg_, staged_[old + i], shell_words_, map_words_);
    } catch (const std::exception& e) {
      return fail(TLM_GENERIC_ERROR_RESPONSE, "descriptor " + std::to_string(i) + ": " + e.what());
    }
  }
  staged_count_ = old + n;
  return TLM_OK_RESPONSE;
}

// A read of whole records from the result window: waits until they are readable or no batch is left.
tlm_response_status DeviceTarget::read_results(const Access& a, sc_time t, sc_time& done) {
  using namespace tlm;
  if (a.wr) return fail(TLM_COMMAND_ERROR_RESPONSE, "the result window is read-only");
  if (a.addr != kResultBase || a.len % kRecordBytes || !a.fits(kResultBase, kResultSize))
    return fail(TLM_BURST_ERROR_RESPONSE, "read whole result records at the result window's base");
  const size_t n = a.len / kRecordBytes;
  done = await_results(n, t);
  take_records(a.data, n);
  return TLM_OK_RESPONSE;
}

// The checks both memory windows make: written only, in whole words of `stride` bytes, inside the memory.
std::optional<tlm_response_status> DeviceTarget::check_memory_write(const Access& a, uint64_t base, uint64_t stride,
                                                                    uint64_t depth, const std::string& memory) {
  if (!a.wr) return fail(tlm::TLM_COMMAND_ERROR_RESPONSE, "the " + memory + " memory is write-only");
  if ((a.addr - base) % stride || a.len % stride || !a.fits(base, depth * stride))
    return fail(tlm::TLM_BURST_ERROR_RESPONSE, "write whole " + std::to_string(stride) + "-byte " + memory +
                                                   " words inside the " + memory + " memory");
  return std::nullopt;
}

// A write of shell words: each {x, y, z, 0} fits PW bits signed.
tlm_response_status DeviceTarget::shell_access(const Access& a, sc_time t, sc_time& done) {
  using namespace tlm;
  if (auto bad = check_memory_write(a, kShellBase, kShellStride, cfg_.shell_depth(), "shell")) return *bad;
  std::vector<ShellWord> words(a.len / kShellStride);
  const int64_t lim = int64_t{1} << (cfg_.PW - 1);
  for (size_t i = 0; i < words.size(); ++i) {
    const uint8_t* p = a.data + i * kShellStride;
    words[i] = {int32_t(uint32_t(get_le(p, 4))), int32_t(uint32_t(get_le(p + 4, 4))),
                int32_t(uint32_t(get_le(p + 8, 4)))};
    for (int c = 0; c < 3; ++c)
      if (words[i][c] < -lim || words[i][c] >= lim)
        return fail(TLM_GENERIC_ERROR_RESPONSE, "shell word " + std::to_string(i) + " does not fit PW bits");
    if (get_le(p + 12, 4) != 0)
      return fail(TLM_GENERIC_ERROR_RESPONSE, "shell word " + std::to_string(i) + ": reserved bytes not zero");
  }
  const uint64_t first = (a.addr - kShellBase) / kShellStride;
  done = write_shell(first, words, t);
  shell_words_ = std::max(shell_words_, first + words.size());
  return TLM_OK_RESPONSE;
}

// A write of voxmap words: none has bits above MEMW.
tlm_response_status DeviceTarget::map_access(const Access& a, sc_time t, sc_time& done) {
  using namespace tlm;
  if (auto bad = check_memory_write(a, kMapBase, kMapStride, cfg_.map_depth(), "voxmap")) return *bad;
  std::vector<uint64_t> words(a.len / kMapStride);
  for (size_t i = 0; i < words.size(); ++i) {
    words[i] = get_le(a.data + i * kMapStride, 8);
    if (cfg_.MEMW < 64 && (words[i] >> cfg_.MEMW) != 0)
      return fail(TLM_GENERIC_ERROR_RESPONSE, "voxmap word " + std::to_string(i) + " has bits above MEMW");
  }
  const uint64_t first = (a.addr - kMapBase) / kMapStride;
  done = write_map(first, words, t);
  map_words_ = std::max(map_words_, first + words.size());
  return TLM_OK_RESPONSE;
}

tlm_response_status DeviceTarget::reg_read(uint64_t off, uint8_t* data, sc_time t) {
  advance_to(t);
  uint64_t v = 0;
  switch (off) {
    case kRegId: v = kDeviceId; break;
    case kRegConfig0: v = config_word0(cfg_); break;
    case kRegConfig1: v = config_word1(cfg_); break;
    case kRegClockPs: v = uint64_t(period_.to_seconds() * 1e12 + 0.5); break;
    case kRegStatus:
      v = (busy() ? kStatusBusy : 0) | (readable() == 0 ? 0 : kStatusResults) | (staged_count_ == 0 ? 0 : kStatusStaged) |
          (faulted() ? kStatusFault : 0);
      break;
    case kRegStaged: v = staged_count_; break;
    case kRegResultCount: v = readable(); break;
    case kRegRun: return fail(tlm::TLM_COMMAND_ERROR_RESPONSE, "RUN is write-only");
    case kRegJobsDone: v = jobs_done_; break;
    case kRegHits: v = hits_; break;
    case kRegPoints: v = points_; break;
    case kRegCycles: v = cycles_; break;
    case kRegStalls: v = stalls_; break;
    case kRegShellWords: v = shell_words_; break;
    case kRegMapWords: v = map_words_; break;
    case kRegDropped: v = 0; break;
    case kRegConflicts: v = conflicts_; break;
    default: return fail(tlm::TLM_ADDRESS_ERROR_RESPONSE, "no register at this offset");
  }
  put_le(data, v, 8);
  return tlm::TLM_OK_RESPONSE;
}

}  // namespace voxcd::sysc
