// The frame exchange of a distributed `voxcd simulate` over MPI (host/scene/exchange.h): every rank sends its
// outcomes to rank 0, which merges them and sends the merge back; each wait has a deadline, so a rank that fails or a
// message that does not arrive ends the run with an error naming the rank and its slab, never a hang.
#pragma once

#include <cstdint>
#include <memory>

#include "voxcd/host/mpi/world.h"
#include "voxcd/host/scene/exchange.h"

namespace voxcd::mpi {

class Watchdog;  // frame_exchange.cpp

class MpiFrameExchange final : public FrameExchange {
 public:
  // timeout: seconds a rank waits for a frame's messages.
  MpiFrameExchange(World& world, double timeout);
  ~MpiFrameExchange() override;
  int rank() const override { return world_.rank(); }
  int ranks() const override { return world_.size(); }
  std::vector<PairOutcome> exchange(uint64_t frame, const Slabs& slabs, const std::vector<PairOutcome>& mine,
                                    const RankCounts& own, RankCounts& total) override;
  uint64_t bytes_sent() const { return sent_; }
  uint64_t bytes_received() const { return received_; }

 private:
  World& world_;
  double timeout_;
  uint64_t sent_ = 0, received_ = 0;
  std::unique_ptr<Watchdog> dog_;  // one thread holding every exchange's deadline
};

// A testing aid (docs/scale.md, "Testing aids"): a hook called by rank `rank` as it reaches the exchange of frame
// `frame`, which may throw, never return or end the process, so that tests drive the faults a distributed run must
// name. Only the test build's tool (build/voxcd_testing, tests/testing/) sets it (nullptr: none, the default); the
// shipped tool reads no environment variable for it. Set it before a run starts; it is not synchronised.
using FrameFaultTestingHook = void (*)(int rank, uint64_t frame);
void set_frame_fault_testing_hook(FrameFaultTestingHook hook);

}  // namespace voxcd::mpi
