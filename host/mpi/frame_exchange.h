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

}  // namespace voxcd::mpi
