// An sc_main of your own: voxcd's loosely-timed TLM-2.0 target (voxcd::sysc::TlmTarget) bound to a minimal
// initiator that speaks the device's address map (<voxcd/ref/address_map.h>, docs/systemc.md): it reads the ID and
// CONFIG registers, writes a memory image into the shell and voxmap windows, writes job descriptors, starts them
// with RUN, reads the result records back and checks each against the reference (ref/pipeline.h and the cycle
// model of ref/timing.h). Exit status 0 when every record matches.
#include <systemc>
#include <tlm>
#include <tlm_utils/simple_initiator_socket.h>

#include <voxcd/host/device/clock.h>
#include <voxcd/ref/address_map.h>
#include <voxcd/ref/pipeline.h>
#include <voxcd/ref/timing.h>
#include <voxcd/ref/vector_gen.h>
#include <voxcd/sysc/tlm_target.h>

#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

using namespace voxcd;
using namespace voxcd::sysc;

// The initiator: one thread, blocking transport, its own notion of local time (annotated delays are waited).
struct Cpu : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Cpu> socket{"socket"};
  GeneratedVectors vectors;
  int mismatches = -1;

  SC_HAS_PROCESS(Cpu);
  Cpu(sc_core::sc_module_name name, GeneratedVectors v) : sc_module(name), vectors(std::move(v)) {
    SC_THREAD(main);
  }

  void access(bool write, uint64_t addr, uint8_t* data, size_t len) {
    tlm::tlm_generic_payload p;
    p.set_command(write ? tlm::TLM_WRITE_COMMAND : tlm::TLM_READ_COMMAND);
    p.set_address(addr);
    p.set_data_ptr(data);
    p.set_data_length(static_cast<unsigned>(len));
    p.set_streaming_width(static_cast<unsigned>(len));
    p.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    socket->b_transport(p, delay);
    wait(delay);
    if (p.is_response_error()) throw std::runtime_error("bus error at address 0x" + std::to_string(addr));
  }
  uint64_t read_reg(uint64_t offset) {
    uint8_t b[8] = {};
    access(false, kRegBase + offset, b, 8);
    return get_le(b, 8);
  }
  void write_reg(uint64_t offset, uint64_t value) {
    uint8_t b[8];
    put_le(b, value, 8);
    access(true, kRegBase + offset, b, 8);
  }

  void main() {
    const DeviceConfig& cfg = vectors.config;
    std::printf("ID %016llx, CONFIG0 %016llx (expected %016llx)\n", (unsigned long long)read_reg(kRegId),
                (unsigned long long)read_reg(kRegConfig0), (unsigned long long)config_word0(cfg));
    // The memory image: shell words (3 x i32 in a 16-byte slot) and voxmap words (8 bytes), one write per word.
    for (size_t k = 0; k < vectors.memory.shell.size(); ++k) {
      uint8_t b[kShellStride] = {};
      for (int c = 0; c < 3; ++c) put_le(b + 4 * c, uint64_t(vectors.memory.shell[k][c]), 4);
      access(true, kShellBase + k * kShellStride, b, kShellStride);
    }
    for (size_t k = 0; k < vectors.memory.map.size(); ++k) {
      uint8_t b[kMapStride];
      put_le(b, vectors.memory.map[k], 8);
      access(true, kMapBase + k * kMapStride, b, kMapStride);
    }
    // The jobs, staged one descriptor at a time, then launched as one batch.
    for (const Job& job : vectors.jobs) {
      uint8_t d[kJobBytes];
      encode_job(job, d);
      access(true, kJobBase, d, kJobBytes);
    }
    const sc_core::sc_time launched = sc_core::sc_time_stamp();
    write_reg(kRegRun, 1);
    // Result records until every job's completion record is in.
    std::vector<Record> got;
    size_t done = 0;
    while (done < vectors.jobs.size()) {
      uint8_t r[kRecordBytes] = {};
      access(false, kResultBase, r, kRecordBytes);
      Record rec;
      if (!decode_record(r, rec)) throw std::runtime_error("the device went idle before every job completed");
      done += rec.kind == Record::Done;
      got.push_back(rec);
    }
    // The reference: the specification's records with the cycle model's counts.
    std::vector<Record> want = run_stream(cfg, vectors.memory, vectors.jobs);
    annotate_cycles(cfg, vectors.jobs, want);
    mismatches = 0;
    if (got.size() != want.size()) ++mismatches;
    for (size_t i = 0; i < got.size() && i < want.size(); ++i) {
      const Record &g = got[i], &w = want[i];
      const bool same = g.kind == w.kind && g.tag == w.tag &&
                        (g.kind == Record::Hit ? g.point == w.point && g.x == w.x && g.y == w.y && g.z == w.z &&
                                                     g.state == w.state
                                               : g.hits == w.hits && g.cycles == w.cycles);
      if (!same && mismatches++ < 5) std::printf("record %zu differs from the reference\n", i);
    }
    std::printf("%zu jobs, %zu records, %d mismatches; %llu device cycles, %s of simulated time\n",
                vectors.jobs.size(), got.size(), mismatches, (unsigned long long)read_reg(kRegCycles),
                (sc_core::sc_time_stamp() - launched).to_string().c_str());
    sc_core::sc_stop();
  }
};

int sc_main(int, char*[]) {
  GenerateOptions g;
  g.seed = 7;
  g.jobs = 200;
  GeneratedVectors v = generate_vectors(g);
  const DeviceConfig cfg = v.config;
  // The clock of this configuration (host/device/clock.h): the largest clock OpenSTA found for it on 0.18 um standard
  // cells, or an estimate from the nearest configuration measured, which its text says (docs/hardware.md, "The
  // default clock").
  const voxcd::DeviceClock clock = voxcd::clock_for(cfg);
  std::printf("device clock %s\n", clock.text().c_str());
  TlmTarget device("device", cfg, sc_core::sc_time(1e3 / clock.mhz, sc_core::SC_NS));
  Cpu cpu("cpu", std::move(v));
  cpu.socket.bind(device.socket);
  sc_core::sc_start();
  return cpu.mismatches == 0 ? 0 : 1;
}
