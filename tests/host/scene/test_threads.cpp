// Every core in a process (docs/scale.md): the thread pool's contract (every index once, the lowest index's
// exception, nested loops inline, callers from several threads), and results that never depend on the thread count:
// simulations frame by frame (state hash, counts and every contact) on 1, 2 and 3 threads for scenes of several
// sizes, crowded ones, distance voxmaps and continuous collision; pair queries (contacts, hits, lookups, cycles) on
// 1 and 2 threads, batches and single large queries, every mode; and the first bad pair's error whatever the
// threads. Each case checks that its parallel paths really ran.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <random>
#include <set>
#include <stdexcept>
#include <thread>

#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/ref/util/thread_pool.h"

namespace voxcd {
namespace {

TEST(ThreadPool, EveryIndexOnceAndTheLowestIndexsException) {
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    ThreadPool pool(threads);
    for (size_t n : {size_t(0), size_t(1), size_t(7), size_t(1000)}) {
      std::vector<std::atomic<int>> seen(n);
      pool.parallel_for(n, [&](size_t i) { seen[i].fetch_add(1); });
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i].load(), 1) << "threads " << threads << " n " << n;
    }
    // Indices 300, 301, 700 throw: the pool rethrows 300's, however the threads took them.
    for (int round = 0; round < 20; ++round) {
      try {
        pool.parallel_for(1000, [&](size_t i) {
          if (i == 300 || i == 301 || i == 700) throw std::runtime_error("index " + std::to_string(i));
        });
        FAIL() << "no exception";
      } catch (const std::runtime_error& e) {
        ASSERT_STREQ(e.what(), "index 300") << "threads " << threads;
      }
    }
    // The pool still works after an exception.
    std::atomic<size_t> sum{0};
    pool.parallel_for(100, [&](size_t i) { sum += i; });
    EXPECT_EQ(sum.load(), 4950u);
  }
}

TEST(ThreadPool, NestedLoopsRunInlineAndOutsideCallersTakeTurns) {
  ThreadPool pool(3);
  std::vector<std::atomic<int>> seen(64 * 64);
  pool.parallel_for(64, [&](size_t i) {
    pool.parallel_for(64, [&](size_t k) { seen[i * 64 + k].fetch_add(1); });
  });
  for (auto& s : seen) ASSERT_EQ(s.load(), 1);
  // Four outside threads share the pool: every loop of each gets every index once.
  std::vector<std::thread> callers;
  std::atomic<int> bad{0};
  for (int c = 0; c < 4; ++c)
    callers.emplace_back([&] {
      for (int round = 0; round < 200; ++round) {
        std::vector<int> mine(97, 0);
        pool.parallel_for(mine.size(), [&](size_t i) { ++mine[i]; });
        for (int v : mine) bad += v != 1;
      }
    });
  for (auto& t : callers) t.join();
  EXPECT_EQ(bad.load(), 0);
}

TEST(ThreadPool, RangesCoverEverythingOnceInOrder) {
  for (size_t n : {size_t(0), size_t(1), size_t(5), size_t(64), size_t(1001)})
    for (size_t parts : {size_t(1), size_t(3), size_t(8), size_t(2000)}) {
      const Ranges r(n, parts);
      size_t at = 0;
      for (size_t p = 0; p < r.parts; ++p) {
        ASSERT_EQ(r.begin(p), at);
        ASSERT_LE(r.begin(p), r.end(p));
        at = r.end(p);
      }
      ASSERT_EQ(at, n);
    }
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Every field of every result, contacts bit for bit.
::testing::AssertionResult same_results(const std::vector<PairResult>& a, const std::vector<PairResult>& b) {
  if (a.size() != b.size()) return ::testing::AssertionFailure() << a.size() << " results against " << b.size();
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].hits != b[i].hits || a[i].lookups != b[i].lookups || a[i].device_cycles != b[i].device_cycles ||
        a[i].contacts.size() != b[i].contacts.size())
      return ::testing::AssertionFailure() << "pair " << i << ": hits " << a[i].hits << "/" << b[i].hits
                                           << " lookups " << a[i].lookups << "/" << b[i].lookups << " cycles "
                                           << a[i].device_cycles << "/" << b[i].device_cycles << " contacts "
                                           << a[i].contacts.size() << "/" << b[i].contacts.size();
    for (size_t k = 0; k < a[i].contacts.size(); ++k) {
      const Contact &x = a[i].contacts[k], &y = b[i].contacts[k];
      bool same = x.pair == y.pair && x.a_in_b == y.a_in_b && x.point == y.point && x.voxel == y.voxel &&
                  x.state == y.state && same_bits(x.depth, y.depth);
      for (int c = 0; c < 3; ++c) same &= same_bits(x.position[c], y.position[c]) && same_bits(x.normal[c], y.normal[c]);
      if (!same) return ::testing::AssertionFailure() << "pair " << i << " contact " << k << " differs";
    }
  }
  return ::testing::AssertionSuccess();
}

struct SimCase {
  const char* name;
  RunConfig spec;
  RunConfig opt;
  int frames;
  // What the run must exercise: the largest frame's lookups and contacts at least this many.
  uint64_t min_lookups = 0, min_contacts = 0;
};

std::vector<SimCase> sim_cases() {
  std::vector<SimCase> v;
  {
    SimCase c{"40 objects", {}, {}, 120};
    c.spec.types[0].count = 40, c.spec.density = 0.05, c.spec.speed = 0.3, c.spec.types[0].voxel = 1.5, c.spec.seed = 3;
    v.push_back(c);
  }
  {
    // The default scene as `voxcd simulate --objects 256` runs it.
    SimCase c{"256 objects", {}, {}, 60, 4096};
    c.spec.types[0].count = 256;
    v.push_back(c);
  }
  {
    // Crowded: near the densest packing the random placement reaches, fast: many contacts every frame.
    SimCase c{"crowded 1500 objects", {}, {}, 25, 4096, 256};
    c.spec.types[0].count = 1500, c.spec.density = 0.12, c.spec.speed = 0.3, c.spec.seed = 7;
    v.push_back(c);
  }
  {
    SimCase c{"crowded, FIRST, both directions", {}, {}, 25, 4096};
    c.spec.types[0].count = 1500, c.spec.density = 0.12, c.spec.speed = 0.3, c.spec.seed = 8;
    c.opt.mode = Mode::First;
    c.opt.both_directions = true;
    v.push_back(c);
  }
  {
    SimCase c{"crowded, distance voxmaps", {}, {}, 20, 4096, 256};
    c.spec.types[0].count = 800, c.spec.density = 0.12, c.spec.speed = 0.3, c.spec.seed = 9, c.spec.distance_bits = 8;
    c.opt.distance_bits = 8;
    c.opt.margin = 0.05;
    v.push_back(c);
  }
  {
    SimCase c{"crowded, distance voxmaps, ccd", {}, {}, 8, 4096};
    c.spec.types[0].count = 1600, c.spec.density = 0.12, c.spec.speed = 0.5, c.spec.seed = 10, c.spec.distance_bits = 8;
    c.opt.distance_bits = 8;
    c.opt.ccd = true;
    v.push_back(c);
  }
  {
    // Many objects, so that every stage has work for several parts.
    SimCase c{"4096 objects", {}, {}, 6, 4096};
    c.spec.types[0].count = 4096;
    v.push_back(c);
  }
  return v;
}

TEST(ThreadsSimulate, FramesAreIdenticalOnOneTwoAndThreeThreads) {
  for (const SimCase& c : sim_cases()) {
    SCOPED_TRACE(c.name);
    const Scene scene = make_scene(c.spec);
    std::vector<std::unique_ptr<Simulation>> sims;
    for (unsigned threads : {1u, 2u, 3u}) {
      RunConfig o = c.opt;
      o.threads = threads;
      sims.push_back(std::make_unique<Simulation>(scene, o));
      if (threads > 1) {
        ASSERT_TRUE(sims.back()->pool());
        sims.back()->pool()->enable_stats(true);
      }
    }
    uint64_t most_lookups = 0, most_contacts = 0, touching = 0;
    for (int f = 0; f < c.frames; ++f) {
      std::vector<FrameStats> st;
      for (auto& s : sims) st.push_back(s->step());
      for (size_t k = 1; k < sims.size(); ++k) {
        const FrameStats &a = st[0], &b = st[k];
        const std::string at = "frame " + std::to_string(f) + ", " + std::to_string(k + 1) + " threads";
        ASSERT_EQ(a.pairs, b.pairs) << at;
        ASSERT_EQ(a.tested, b.tested) << at;
        ASSERT_EQ(a.touching, b.touching) << at;
        ASSERT_EQ(a.responses, b.responses) << at;
        ASSERT_EQ(a.wall_hits, b.wall_hits) << at;
        ASSERT_EQ(a.lookups, b.lookups) << at;
        ASSERT_EQ(a.hits, b.hits) << at;
        ASSERT_EQ(a.contacts, b.contacts) << at;
        ASSERT_EQ(a.device_cycles, b.device_cycles) << at;
        ASSERT_EQ(a.ccd_iterations, b.ccd_iterations) << at;
        ASSERT_EQ(a.ccd_queries, b.ccd_queries) << at;
        ASSERT_EQ(a.ccd_limited, b.ccd_limited) << at;
        ASSERT_EQ(a.ccd_toi, b.ccd_toi) << at;
        ASSERT_EQ(a.ccd_dropped, b.ccd_dropped) << at;
        ASSERT_EQ(a.ccd_lookups, b.ccd_lookups) << at;
        ASSERT_EQ(sims[0]->tested_pairs(), sims[k]->tested_pairs()) << at;
        ASSERT_TRUE(same_results(sims[0]->results(), sims[k]->results())) << at;
        ASSERT_EQ(sims[0]->state_hash(), sims[k]->state_hash()) << at;
      }
      most_lookups = std::max(most_lookups, st[0].lookups);
      most_contacts = std::max(most_contacts, st[0].contacts);
      touching += st[0].touching + st[0].ccd_toi;  // with ccd, the advancement responds at the times of impact
    }
    EXPECT_GT(touching, 0u) << "the run must have collisions for the comparison to mean something";
    EXPECT_GE(most_lookups, c.min_lookups) << "a frame large enough for the device's parallel batches";
    EXPECT_GE(most_contacts, c.min_contacts) << "a frame with enough contacts to build them in parallel";
    for (size_t k = 1; k < sims.size(); ++k) EXPECT_GT(sims[k]->pool()->stats().loops, 0u) << "no loop on the pool";
    std::printf("%s: %llu touching pairs and times of impact, at most %llu lookups and %llu contacts a frame, %llu loops a frame\n",
                c.name, (unsigned long long)touching, (unsigned long long)most_lookups,
                (unsigned long long)most_contacts,
                (unsigned long long)(sims[1]->pool()->stats().loops / uint64_t(c.frames)));
  }
}

TEST(ThreadsSimulate, TheDefaultRunKeepsItsHash) {
  // `voxcd simulate --frames 20` (tests/host/python/test_scenes.py pins the same hash), on 1, 2 and 3 threads.
  for (unsigned threads : {1u, 2u, 3u}) {
    RunConfig o;
    o.threads = threads;
    Simulation sim(make_scene(RunConfig{}), o);
    for (int f = 0; f < 20; ++f) sim.step();
    EXPECT_EQ(sim.state_hash(), 0xde188b9acc918936ull) << threads << " threads";
  }
}

TEST(ThreadsSimulate, ManyObjectsKeepTheirHashAndStageTimes) {
  // `voxcd simulate --objects 65536 --frames 4` as revision 2194d6a ran it (before the grid visited its boxes in the
  // last frame's order, the mid-phase read compact spheres and the integration and bounds became one pass), on 1
  // and 2 threads: the same pairs, tested pairs and state; the fused integration and bounds still time each step.
  for (unsigned threads : {1u, 2u}) {
    RunConfig c;
    c.types[0].count = 65536;
    c.threads = threads;
    Simulation sim(make_scene(c), c);
    uint64_t pairs = 0, tested = 0;
    for (int f = 0; f < 4; ++f) {
      const FrameStats st = sim.step();
      pairs += st.pairs, tested += st.tested;
      EXPECT_GT(st.t_integrate, 0) << "frame " << f;
      EXPECT_GT(st.t_bounds, 0) << "frame " << f;
    }
    EXPECT_EQ(pairs, 189672u) << threads << " threads";
    EXPECT_EQ(tested, 8847u) << threads << " threads";
    EXPECT_EQ(sim.state_hash(), 0x9589b37c3919a5d8ull) << std::hex << sim.state_hash() << ", " << threads << " threads";
  }
}

// Two 10,000-triangle tori (bench_pair's) at `voxel`, the device a cpu backend of `threads` threads.
struct Tori {
  std::shared_ptr<const ObjectType> a, b;
  Tori(double voxel, int distance_bits = 0) {
    ObjectOptions o;
    o.voxel = voxel;
    o.distance_bits = distance_bits;
    a = std::make_shared<ObjectType>(make_object_type(make_object(make_torus(1.0, 0.35, 100, 50), "A", 0, o), "A"));
    b = std::make_shared<ObjectType>(make_object_type(make_object(make_torus(0.8, 0.3, 100, 50), "B", 0, o), "B"));
  }
  std::unique_ptr<PairCollider> collider(unsigned threads, int distance_bits = 0) const {
    DeviceConfig cfg;
    if (distance_bits) cfg.SB = distance_bits;
    cfg = fit_memory(cfg, {a.get(), b.get()});
    DeviceOptions d;
    d.threads = threads;
    return std::make_unique<PairCollider>(make_device("cpu", cfg, d),
                                          std::vector<std::shared_ptr<const ObjectType>>{a, b});
  }
};

std::vector<PairRequest> tori_poses(size_t n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> nd(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PairRequest> reqs;
  for (size_t k = 0; k < n; ++k) {
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_a.rotation = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
    r.pose_b.rotation = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
    r.pose_b.translation = Eigen::Vector3d(nd(rng), nd(rng), nd(rng)).normalized() * 1.2 * std::cbrt(u(rng));
    reqs.push_back(r);
  }
  return reqs;
}

TEST(ThreadsPairs, QueriesAreIdenticalOnOneAndTwoThreads) {
  // Voxel 0.03: about 45,000 points in A's shell, more than PairCollider::kParallelClusters clusters, so one
  // query culls on the pool, looks up on it and builds its thousands of contacts on it.
  const Tori tori(0.03);
  ASSERT_GT(tori.a->shell().size() / 32, PairCollider::kParallelClusters);
  auto one = tori.collider(1), two = tori.collider(2);
  ASSERT_FALSE(one->pool());
  ASSERT_TRUE(two->pool());
  const std::vector<PairRequest> reqs = tori_poses(24, 11);
  for (Mode mode : {Mode::All, Mode::First, Mode::Count})
    for (bool both : {false, true})
      for (bool cull : {true, false}) {
        PairOptions opt;
        opt.mode = mode;
        opt.both_directions = both;
        opt.cull = cull;
        const std::string what = std::string(mode_name(mode)) + (both ? " both" : " A in B") + (cull ? " cull" : "");
        // The whole batch at once, then one query at a time into reused results.
        EXPECT_TRUE(same_results(one->collide(reqs, opt), two->collide(reqs, opt))) << what;
        std::vector<PairResult> r1, r2;
        size_t contacts = 0;
        for (const PairRequest& r : reqs) {
          one->collide({r}, opt, r1);
          two->collide({r}, opt, r2);
          ASSERT_TRUE(same_results(r1, r2)) << what;
          contacts = std::max(contacts, r1[0].contacts.size());
        }
        if (mode == Mode::All) {
          EXPECT_GT(contacts, PairCollider::kParallelContacts) << what;
        }
      }
}

TEST(ThreadsPairs, DistanceQueriesAreIdenticalOnOneAndTwoThreads) {
  const Tori tori(0.04, 8);
  auto one = tori.collider(1, 8), two = tori.collider(2, 8);
  const std::vector<PairRequest> reqs = tori_poses(16, 12);
  PairOptions opt;
  opt.both_directions = true;
  opt.margin = 0.02;
  size_t contacts = 0;
  std::vector<PairResult> r1, r2;
  for (const PairRequest& r : reqs) {
    one->collide({r}, opt, r1);
    two->collide({r}, opt, r2);
    ASSERT_TRUE(same_results(r1, r2));
    contacts = std::max(contacts, r1[0].contacts.size());
  }
  EXPECT_GT(contacts, PairCollider::kParallelContacts);
  EXPECT_TRUE(same_results(one->collide(reqs, opt), two->collide(reqs, opt)));
}

TEST(ThreadsPairs, TheFirstBadPairIsTheErrorWhateverTheThreads) {
  const Tori tori(0.08);
  std::vector<PairRequest> reqs = tori_poses(64, 13);
  reqs[23].pose_b.translation.x() = std::nan("");
  reqs[41].pose_a.translation.y() = std::nan("");
  std::string want;
  for (unsigned threads : {1u, 2u, 3u}) {
    auto c = tori.collider(threads);
    try {
      c->collide(reqs);
      FAIL() << "no error";
    } catch (const RangeError& e) {
      if (want.empty()) want = e.what();
      EXPECT_EQ(e.what(), want) << threads << " threads";
    }
  }
  EXPECT_NE(want.find("pair 23"), std::string::npos) << want;
}

}  // namespace
}  // namespace voxcd
