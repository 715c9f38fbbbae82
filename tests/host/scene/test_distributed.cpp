// A distributed simulation (RunConfig::exchange) against one process: 2 and 3 ranks, here threads of one process
// exchanging through memory (the MPI exchange is tested under mpirun in tests/host/mpi), give the same per-frame counts
// and the same state hash as one Simulation, on a plain scene, on fast bodies that cross the slabs every frame, on
// bodies crowded into one corner, and with distance voxmaps and continuous collision; the slabs split the work;
// the slab helpers keep every pair with exactly one rank.
#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <random>
#include <thread>

#include "voxcd/host/scene/exchange.h"
#include "voxcd/host/scene/partition.h"
#include "voxcd/host/scene/scene.h"
#include "tests/seed.h"

namespace voxcd {
namespace {

// Ranks as threads: each deposits its outcomes, waits for all, and reads the merge.
class MemoryExchange {
 public:
  explicit MemoryExchange(int ranks) : ranks_(ranks), slots_(size_t(ranks)), counts_(size_t(ranks)) {}

  std::vector<PairOutcome> exchange(int rank, const std::vector<PairOutcome>& mine, const RankCounts& own,
                                    RankCounts& total) {
    std::unique_lock<std::mutex> lock(mu_);
    slots_[size_t(rank)] = mine;
    counts_[size_t(rank)] = own;
    own_tested_.resize(size_t(ranks_));
    own_tested_[size_t(rank)] += own.tested;
    barrier(lock);
    const std::vector<PairOutcome> all = merge_outcomes(slots_);
    total = RankCounts{};
    for (const RankCounts& c : counts_) {
      total.pairs += c.pairs;
      total.tested += c.tested;
      total.cycles = std::max(total.cycles, c.cycles);
    }
    barrier(lock);  // nobody overwrites a slot before every rank has read them
    return all;
  }
  std::vector<uint64_t> own_tested_;  // per rank, over the run

 private:
  void barrier(std::unique_lock<std::mutex>& lock) {
    const uint64_t gen = generation_;
    if (++arrived_ == ranks_) {
      arrived_ = 0;
      ++generation_;
      cv_.notify_all();
    } else {
      cv_.wait(lock, [&] { return generation_ != gen; });
    }
  }
  int ranks_;
  std::vector<std::vector<PairOutcome>> slots_;
  std::vector<RankCounts> counts_;
  std::mutex mu_;
  std::condition_variable cv_;
  int arrived_ = 0;
  uint64_t generation_ = 0;
};

class RankView final : public FrameExchange {
 public:
  RankView(MemoryExchange& m, int rank, int ranks) : m_(m), rank_(rank), ranks_(ranks) {}
  int rank() const override { return rank_; }
  int ranks() const override { return ranks_; }
  std::vector<PairOutcome> exchange(uint64_t frame, const Slabs&, const std::vector<PairOutcome>& mine,
                                    const RankCounts& own, RankCounts& total) override {
    // Through the message encoding, as the MPI exchange sends them.
    uint64_t f = 0;
    RankCounts c;
    std::vector<PairOutcome> back;
    decode_outcomes(encode_outcomes(frame, own, mine), f, c, back);
    EXPECT_EQ(f, frame);
    return m_.exchange(rank_, back, c, total);
  }

 private:
  MemoryExchange& m_;
  int rank_, ranks_;
};

struct Run {
  std::vector<FrameStats> frames;
  uint64_t hash = 0;
};

Run run_one(const Scene& scene, RunConfig opt, uint64_t frames) {
  Simulation sim(scene, opt);
  Run r;
  for (uint64_t f = 0; f < frames; ++f) r.frames.push_back(sim.step());
  r.hash = sim.state_hash();
  return r;
}

// Every rank's run (they must agree with each other), and the per-rank tested counts.
std::vector<Run> run_ranks(const Scene& scene, RunConfig opt, uint64_t frames, int ranks,
                           std::vector<uint64_t>* tested) {
  MemoryExchange mem(ranks);
  std::vector<Run> runs(static_cast<size_t>(ranks));
  std::vector<std::thread> threads;
  std::vector<std::exception_ptr> errors(static_cast<size_t>(ranks));
  for (int r = 0; r < ranks; ++r)
    threads.emplace_back([&, r] {
      try {
        RunConfig o = opt;
        o.exchange = std::make_shared<RankView>(mem, r, ranks);
        runs[size_t(r)] = run_one(scene, o, frames);
      } catch (...) {
        errors[size_t(r)] = std::current_exception();
      }
    });
  for (auto& t : threads) t.join();
  for (auto& e : errors)
    if (e) std::rethrow_exception(e);
  if (tested) *tested = mem.own_tested_;
  return runs;
}

void expect_same(const Run& want, const Run& got, const std::string& what) {
  ASSERT_EQ(want.frames.size(), got.frames.size());
  for (size_t f = 0; f < want.frames.size(); ++f) {
    const FrameStats &a = want.frames[f], &b = got.frames[f];
    ASSERT_EQ(a.pairs, b.pairs) << what << " frame " << f;
    ASSERT_EQ(a.tested, b.tested) << what << " frame " << f;
    ASSERT_EQ(a.touching, b.touching) << what << " frame " << f;
    ASSERT_EQ(a.responses, b.responses) << what << " frame " << f;
    ASSERT_EQ(a.wall_hits, b.wall_hits) << what << " frame " << f;
    ASSERT_EQ(a.lookups, b.lookups) << what << " frame " << f;
    ASSERT_EQ(a.hits, b.hits) << what << " frame " << f;
    ASSERT_EQ(a.contacts, b.contacts) << what << " frame " << f;
    ASSERT_EQ(a.ccd_queries, b.ccd_queries) << what << " frame " << f;
    ASSERT_EQ(a.ccd_toi, b.ccd_toi) << what << " frame " << f;
  }
  EXPECT_EQ(want.hash, got.hash) << what;
}

void check_scene(const Scene& scene, const RunConfig& opt, uint64_t frames, const std::string& what) {
  const Run one = run_one(scene, opt, frames);
  uint64_t responses = 0;
  for (const FrameStats& f : one.frames) responses += f.responses;
  EXPECT_GT(responses, 0u) << what << ": the scene must have collisions";
  for (int ranks : {2, 3}) {
    std::vector<uint64_t> tested;
    const std::vector<Run> runs = run_ranks(scene, opt, frames, ranks, &tested);
    uint64_t all_tested = 0, busiest = 0;
    for (uint64_t t : tested) all_tested += t, busiest = std::max(busiest, t);
    for (int r = 0; r < ranks; ++r)
      expect_same(one, runs[size_t(r)], what + ", " + std::to_string(ranks) + " ranks, rank " + std::to_string(r));
    uint64_t one_tested = 0;
    for (const FrameStats& f : one.frames) one_tested += f.tested;
    EXPECT_EQ(all_tested, one_tested) << what << ": every pair tested once";
    std::printf("%s, %d ranks: pairs tested per rank", what.c_str(), ranks);
    for (uint64_t t : tested) std::printf(" %llu", (unsigned long long)t);
    std::printf(" (one process %llu)\n", (unsigned long long)one_tested);
  }
}

RunConfig options() {
  RunConfig o;
  o.threads = 1;
  return o;
}

TEST(Distributed, SameAsOneProcess) {
  RunConfig spec;
  spec.types[0].count = 256;
  check_scene(make_scene(spec), options(), 60, "256 polytopes");
}

TEST(Distributed, BodiesCrossingSlabsEveryFrame) {
  RunConfig spec;
  spec.types[0].count = 128;
  spec.speed = 1.5;  // 1.5 radii a frame: bodies cross the slabs' cuts all the time
  check_scene(make_scene(spec), options(), 60, "fast bodies");
}

TEST(Distributed, BodiesCrowdedIntoOneCorner) {
  RunConfig spec;
  spec.types[0].count = 200;
  spec.density = 0.02;
  Scene scene = make_scene(spec);
  // Squeeze every body into the corner octant's corner: overlapping, touching, and all in what would be one rank's
  // region of an even split of the cube.
  for (Body& b : scene.bodies) b.pose.translation *= 0.3;
  check_scene(scene, options(), 30, "crowded corner");
}

TEST(Distributed, DistanceVoxmapsWithContinuousCollision) {
  RunConfig spec;
  spec.types[0].count = 64;
  spec.distance_bits = 8;
  spec.speed = 0.8;
  RunConfig o = options();
  o.distance_bits = 8;
  o.ccd = true;
  check_scene(make_scene(spec), o, 30, "distance + ccd");
}

TEST(Distributed, EveryBroadphaseGivesTheSameRun) {
  RunConfig spec;
  spec.types[0].count = 96;
  const Scene scene = make_scene(spec);
  for (const char* b : {"sap", "tree", "queue", "coherent", "sphere"}) {
    RunConfig o = options();
    o.broadphase = b;
    check_scene(scene, o, 25, std::string("broadphase ") + b);
  }
  RunConfig all = options();
  all.broadphase = "all";
  MemoryExchange two(2);
  all.exchange = std::make_shared<RankView>(two, 0, 2);
  EXPECT_THROW(Simulation(scene, all), std::invalid_argument);
}

TEST(Partition, EveryOverlappingPairHasOneOwnerThatSeesBoth) {
  std::mt19937_64 rng(test::seed(7));
  std::uniform_real_distribution<double> u(0, 10), rad(0.05, 1.5);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<BodyBounds> b(150);
    for (auto& x : b) {
      x.centre = Eigen::Vector3d(u(rng), u(rng) * (trial % 2 ? 0.1 : 1), u(rng));
      x.radius = rad(rng);
      // A box that may poke out of the sphere (an oriented box's AABB does).
      const Eigen::Vector3d half = Eigen::Vector3d(rad(rng), rad(rng), rad(rng));
      x.box.lo = x.centre - half;
      x.box.hi = x.centre + half;
    }
    if (trial == 3)
      for (auto& x : b) x.centre = Eigen::Vector3d(1, 2, 3);  // all at one point
    for (int ranks = 1; ranks <= 5; ++ranks) {
      const Slabs s = split_slabs(b, ranks);
      ASSERT_EQ(s.ranks(), ranks);
      std::vector<std::vector<uint32_t>> local;
      for (int r = 0; r < ranks; ++r) local.push_back(slab_bodies(s, r, b));
      for (uint32_t i = 0; i < b.size(); ++i)
        for (uint32_t j = i + 1; j < b.size(); ++j) {
          if (!spheres_overlap(b[i], b[j]) && !b[i].box.overlaps(b[j].box)) continue;
          const int o = pair_owner(s, b[i], b[j]);
          ASSERT_GE(o, 0);
          ASSERT_LT(o, ranks);
          const auto& l = local[size_t(o)];
          EXPECT_TRUE(std::binary_search(l.begin(), l.end(), i) && std::binary_search(l.begin(), l.end(), j))
              << "pair " << i << "," << j << " owned by rank " << o << " that does not see both";
        }
      // Balanced: no slab holds many more centres than its share (unless they coincide).
      if (trial != 3) {
        std::vector<int> count(size_t(ranks), 0);
        for (const auto& x : b) ++count[size_t(s.slab_of(x.centre[s.axis]))];
        for (int c : count) EXPECT_LE(c, int(b.size()) / ranks + 1);
      }
    }
  }
}

}  // namespace
}  // namespace voxcd
