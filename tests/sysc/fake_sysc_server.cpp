// A stand-in for voxcd_sysc_server (sysc/server_main.cpp) that fails the way $VOXCD_FAKE_SERVER says, for
// tests/sysc/test_sysc_server.cpp; the host's sysc backends start it through VOXCD_SYSC_SERVER.
//   end-at-once    says it is ready, then ends without reading anything
//   end-on-run     says it is ready and answers loads; ends when a run request comes
//   empty-record   says it is ready and answers loads; answers the first run with each job's completion record
//                  followed by an empty record (kind 0), later runs with each job's completion record
//   bad-target     runs the real server with --target nosuch (which prints its usage and ends)
// It speaks ref/server_protocol.h on file descriptor kServerFd and links no SystemC.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/address_map.h"
#include "voxcd/ref/server_protocol.h"

using namespace voxcd;
using namespace voxcd::sysc;

namespace {

void skip(Channel& ch, uint64_t bytes) {
  std::vector<uint8_t> b(bytes);
  if (bytes && !ch.get(b.data(), b.size())) throw std::runtime_error("short request");
}

int serve(const std::string& mode) {
  Channel ch(kServerFd);
  ch.put_u64(0);  // ready
  ch.flush();
  if (mode == "end-at-once") return 3;
  bool first_run = true;
  for (;;) {
    uint8_t opb[8];
    if (!ch.get(opb, 8)) return 0;
    const uint64_t op = get_le(opb, 8);
    if (op == kOpLoad) {
      skip(ch, 24 * ch.get_u64());
      skip(ch, 8 * ch.get_u64());
      ch.put_u64(0);
      ch.put_u64(1000);  // simulated time, ps
    } else if (op == kOpRun) {
      if (mode == "end-on-run") return 3;
      std::vector<uint8_t> jobs(kJobBytes * ch.get_u64());
      if (!jobs.empty() && !ch.get(jobs.data(), jobs.size())) return 4;
      const size_t n = jobs.size() / kJobBytes;
      ch.put_u64(0);
      ch.put_u64(n + (first_run ? 1 : 0));
      std::vector<uint8_t> rec(kRecordBytes);
      for (size_t i = 0; i < n; ++i) {
        encode_record(Record::done(uint32_t(get_le(&jobs[i * kJobBytes], 4)), 0, 1), rec.data());
        ch.put(rec.data(), rec.size());
      }
      if (first_run) {
        rec.assign(kRecordBytes, 0);
        ch.put(rec.data(), rec.size());
      }
      first_run = false;
      ch.put_u64(2000);  // simulated time, ps
      ch.put_u64(5);     // wall-clock ns
    } else {
      return 5;
    }
    ch.flush();
  }
}

}  // namespace

int main(int argc, char** argv) {
  const char* m = std::getenv("VOXCD_FAKE_SERVER");
  const std::string mode = m ? m : "";
  if (mode == "bad-target") {
    std::vector<std::string> args = {VOXCD_REAL_SERVER, "--target", "nosuch"};
    for (int i = 1; i + 1 < argc; ++i)
      if (std::string(argv[i]) == "--config") args.insert(args.end(), {"--config", argv[i + 1]});
    std::vector<char*> av;
    for (std::string& a : args) av.push_back(a.data());
    av.push_back(nullptr);
    ::execv(av[0], av.data());
    std::perror("fake_sysc_server: execv");
    return 6;
  }
  if (mode != "end-at-once" && mode != "end-on-run" && mode != "empty-record") {
    std::fprintf(stderr, "fake_sysc_server: unknown VOXCD_FAKE_SERVER '%s'\n", mode.c_str());
    return 2;
  }
  try {
    return serve(mode);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fake_sysc_server: %s\n", e.what());
    return 7;
  }
}
