// The byte protocol between a host-side Device (host/device/sysc.cpp) and voxcd_sysc_server (sysc/server_main.cpp),
// which runs the SystemC platform in its own process (SystemC elaborates once per process; a Device may be made many
// times). Here in ref/ because both sides use it and host/ may use nothing of sysc/; internal (not installed).
// Every number is a little-endian u64. The server reads requests from file descriptor kServerFd and answers on it.
//
//   request LOAD: kOpLoad, shell words N, N x (x, y, z) as i64, voxmap words M, M x u64
//   request RUN:  kOpRun, jobs N, N job descriptors (ref/address_map.h, each kJobBytes bytes)
//   answer: 0 then the payload, or 1 then a message (length, bytes)
//     LOAD payload: simulated time at the end (ps)
//     RUN payload:  records N, N result records (kRecordBytes bytes each), simulated time at the end (ps),
//                   wall-clock nanoseconds spent simulating the batch
#pragma once

#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxcd::sysc {

constexpr int kServerFd = 3;
constexpr uint64_t kOpLoad = 1;
constexpr uint64_t kOpRun = 2;

// A byte stream over a socket; throws std::runtime_error when the peer has gone.
class Channel {
 public:
  // `buffered`: reads take whatever the socket has (up to 64 KiB) into the Channel, so a Channel that reads must
  // live as long as the connection; unbuffered, every get() is its own read and a Channel may be a temporary.
  explicit Channel(int fd, bool buffered = false) : fd_(fd), buffered_(buffered) {}
  void put(const void* p, size_t n) {
    out_.insert(out_.end(), static_cast<const uint8_t*>(p), static_cast<const uint8_t*>(p) + n);
  }
  void put_u64(uint64_t v) {
    uint8_t b[8];
    for (int i = 0; i < 8; ++i) b[i] = uint8_t(v >> (8 * i));
    put(b, 8);
  }
  void put_string(const std::string& s) {
    put_u64(s.size());
    put(s.data(), s.size());
  }
  void flush() {
    size_t off = 0;
    while (off < out_.size()) {
      const ssize_t w = ::send(fd_, out_.data() + off, out_.size() - off, MSG_NOSIGNAL);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) throw std::runtime_error("the peer closed the connection");
      off += size_t(w);
    }
    out_.clear();
  }
  // False at a clean end of stream before the first byte.
  bool get(void* p, size_t n) {
    uint8_t* d = static_cast<uint8_t*>(p);
    size_t off = 0;
    while (off < n) {
      if (in_pos_ < in_.size()) {
        const size_t k = std::min(n - off, in_.size() - in_pos_);
        std::memcpy(d + off, in_.data() + in_pos_, k);
        in_pos_ += k;
        off += k;
        continue;
      }
      if (buffered_) {
        in_.resize(65536);
        const ssize_t r = ::read(fd_, in_.data(), in_.size());
        in_.resize(r > 0 ? size_t(r) : 0);
        in_pos_ = 0;
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) {
          if (off == 0 && r == 0) return false;
          throw std::runtime_error("the peer closed the connection");
        }
        continue;
      }
      const ssize_t r = ::read(fd_, d + off, n - off);
      if (r < 0 && errno == EINTR) continue;
      if (r <= 0) {
        if (off == 0 && r == 0) return false;
        throw std::runtime_error("the peer closed the connection");
      }
      off += size_t(r);
    }
    return true;
  }
  uint64_t get_u64() {
    uint8_t b[8];
    if (!get(b, 8)) throw std::runtime_error("the peer closed the connection");
    uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= uint64_t(b[i]) << (8 * i);
    return v;
  }
  std::string get_string() {
    std::string s(get_u64(), '\0');
    if (!s.empty() && !get(&s[0], s.size())) throw std::runtime_error("the peer closed the connection");
    return s;
  }

 private:
  int fd_;
  bool buffered_;
  std::vector<uint8_t> out_;
  std::vector<uint8_t> in_;  // buffered: bytes read, not yet taken from in_pos_ on
  size_t in_pos_ = 0;
};

}  // namespace voxcd::sysc
