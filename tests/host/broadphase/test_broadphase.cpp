// Every broadphase against brute force of its own predicate, frame by frame, on random moving scenes: the exact
// sorted pair set, no pair twice. Seeded (printed; VOXCD_SEED replays).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "voxcd/host/broadphase/broadphase.h"
#include "voxcd/ref/util/thread_pool.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

using Vec = Eigen::Vector3d;

std::vector<BodyPair> brute_force(const std::string& predicate, const std::vector<BodyBounds>& b) {
  std::vector<BodyPair> out;
  for (uint32_t i = 0; i < b.size(); ++i)
    for (uint32_t j = i + 1; j < b.size(); ++j) {
      const bool hit = predicate == "all"      ? true
                       : predicate == "sphere" ? spheres_overlap(b[i], b[j])
                                               : b[i].box.overlaps(b[j].box);
      if (hit) out.push_back({i, j});
    }
  return out;
}

struct SceneOptions {
  uint32_t n = 100;
  double world = 100;      // bodies live in [0, world]^3
  bool dyadic = false;     // coordinates, sizes and velocities multiples of 1/4: many exact touches
  double max_half = 5;     // largest half side
  double min_half = 0.05;  // smallest half side (but for the points)
  double teleport = 0.01;  // chance a frame that a body jumps (flagged)
  double kick = 0.01;      // chance a frame that a body gets a new, faster velocity (flagged)
  bool flag = true;        // false: kicks are not flagged (breaks the motion bounds)
  double clump = 0;        // share of bodies stacked at a few shared positions with identical boxes
};

// Bodies in a box world: constant velocity (max_speed the speed, no acceleration), accelerating (max_speed the
// current speed, max_accel a bound on the velocity change a frame), or at rest (no motion at all); all bounce
// off the walls, which keeps the speed. Positions move by the new velocity: p += (v += dv).
class TestScene {
 public:
  TestScene(const SceneOptions& o, uint64_t seed) : o_(o), rng_(seed) {
    for (uint32_t i = 0; i < o.n; ++i) body_.push_back(make_body());
    if (o.clump > 0) {
      const uint32_t k = uint32_t(o.clump * o.n);
      for (uint32_t i = 0; i < k; ++i) {
        const Body& src = body_[i % 3];
        body_[o.n - 1 - i].p = src.p;
        body_[o.n - 1 - i].half = src.half;
      }
    }
    fill(false);
  }
  void step() {
    for (auto& b : body_) {
      b.flagged = false;
      const double u = uni(0, 1);
      if (u < o_.teleport) {
        b.p = random_position(b.half);
        b.flagged = true;
      } else if (u < o_.teleport + o_.kick) {
        b.v = random_velocity(b.half.maxCoeff() * 0.5 + 0.5) * 3;
        b.kind = 0;
        b.flagged = o_.flag;
      } else if (b.kind == 1) {
        Vec dv = random_velocity(b.accel);
        if (o_.dyadic) dv = Vec::Zero();
        b.v += dv;
        const double cap = b.half.maxCoeff() + 1;
        if (b.v.norm() > cap) b.v *= cap / b.v.norm();
      }
      b.p += b.v;
      for (int a = 0; a < 3; ++a) {
        if (b.p[a] - b.half[a] < 0 && b.v[a] < 0) b.v[a] = -b.v[a];
        if (b.p[a] + b.half[a] > o_.world && b.v[a] > 0) b.v[a] = -b.v[a];
      }
    }
    fill(true);
  }
  const std::vector<BodyBounds>& bounds() const { return bounds_; }

 private:
  struct Body {
    Vec p, v, half;
    int kind = 0;  // 0 constant velocity, 1 accelerating, 2 at rest
    double accel = 0;
    bool flagged = false;
  };
  double uni(double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng_); }
  double quarter(double a, double b) { return std::floor(uni(a, b) * 4) / 4; }
  Vec random_position(const Vec& half) {
    Vec p;
    for (int a = 0; a < 3; ++a) p[a] = o_.dyadic ? quarter(half[a], o_.world - half[a]) : uni(half[a], o_.world - half[a]);
    return p;
  }
  Vec random_velocity(double speed) {
    Vec v;
    if (o_.dyadic) {
      for (int a = 0; a < 3; ++a) v[a] = std::floor(uni(-2, 3)) / 4;
      return v;
    }
    do v = Vec(uni(-1, 1), uni(-1, 1), uni(-1, 1));
    while (v.squaredNorm() > 1);
    return v * speed;
  }
  Body make_body() {
    Body b;
    const double s = uni(0, 1);
    if (o_.dyadic) {
      for (int a = 0; a < 3; ++a) b.half[a] = std::floor(uni(0, 4)) / 2;
    } else if (s < 0.05) {
      b.half = Vec::Zero();  // points
    } else if (s < 0.1) {
      b.half = Vec::Constant(o_.max_half * 3);  // a few large bodies
    } else {
      for (int a = 0; a < 3; ++a) b.half[a] = std::exp(uni(std::log(o_.min_half), std::log(o_.max_half)));
    }
    b.p = random_position(b.half);
    const double k = uni(0, 1);
    b.kind = k < 0.6 ? 0 : k < 0.85 ? 1 : 2;
    if (b.kind != 2) b.v = random_velocity(0.1 * b.half.maxCoeff() + 0.05);
    else b.v = Vec::Zero();
    b.accel = b.kind == 1 ? 0.01 : 0;
    return b;
  }
  void fill(bool flags) {
    bounds_.resize(body_.size());
    for (size_t i = 0; i < body_.size(); ++i) {
      const Body& b = body_[i];
      BodyBounds& o = bounds_[i];
      o.box.lo = b.p - b.half;
      o.box.hi = b.p + b.half;
      o.centre = b.p;
      o.radius = o_.dyadic ? b.half.maxCoeff() : b.half.norm();  // dyadic: exact sums of radii, exact touches
      // The speed bound: this frame's speed, slightly enlarged for the rounding of norm() and of p += v.
      o.max_speed = b.kind == 2 ? 0 : b.v.norm() * (1 + 1e-12) + 1e-12;
      o.max_accel = b.kind == 1 ? b.accel * (1 + 1e-12) : 0;
      o.moved_unexpectedly = flags && b.flagged;
    }
  }
  SceneOptions o_;
  std::mt19937_64 rng_;
  std::vector<Body> body_;
  std::vector<BodyBounds> bounds_;
};

// Runs `frames` frames and returns how many frames differed from brute force (each reported, up to a few).
int run_against_brute_force(Broadphase& bp, TestScene& scene, int frames, uint64_t first_frame,
                            const std::string& what, bool report = true) {
  int bad = 0;
  for (int f = 0; f < frames; ++f) {
    if (f) scene.step();
    const auto& b = scene.bounds();
    bp.update(b, first_frame + f);
    const auto want = brute_force(bp.predicate(), b);
    const auto& got = bp.pairs();
    bool ok = got == want && bp.stats().pairs == got.size();
    for (size_t k = 0; k < got.size() && ok; ++k) ok = got[k].first < got[k].second && (k == 0 || got[k - 1] < got[k]);
    if (!ok) {
      ++bad;
      if (report && bad <= 3) {
        std::vector<BodyPair> missing, extra;
        std::set_difference(want.begin(), want.end(), got.begin(), got.end(), std::back_inserter(missing));
        std::set_difference(got.begin(), got.end(), want.begin(), want.end(), std::back_inserter(extra));
        ADD_FAILURE() << bp.name() << " " << what << " frame " << f << ": " << got.size() << " pairs, brute force "
                      << want.size() << "; missing " << missing.size() << ", extra " << extra.size()
                      << (missing.empty() ? "" : " e.g. (" + std::to_string(missing[0].first) + ", " +
                                                     std::to_string(missing[0].second) + ")")
                      << "; seed " << test::seed();
      }
    }
  }
  return bad;
}

class EachBroadphase : public ::testing::TestWithParam<std::string> {};

TEST_P(EachBroadphase, MatchesBruteForceOnRandomScenes) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED replays)\n", (unsigned long long)seed);
  struct Case {
    SceneOptions o;
    int frames;
  };
  std::vector<Case> cases;
  for (uint32_t n : {0u, 1u, 2u, 3u, 7u, 40u, 300u}) {
    SceneOptions o;
    o.n = n;
    o.world = 60;
    cases.push_back({o, 60});
  }
  {  // crowded: large bodies in a small world, many overlaps
    SceneOptions o;
    o.n = 200;
    o.world = 30;
    cases.push_back({o, 40});
  }
  {  // exact touches of boxes and spheres on a quarter-unit lattice
    SceneOptions o;
    o.n = 400;
    o.world = 20;
    o.dyadic = true;
    cases.push_back({o, 60});
  }
  {  // identical boxes at the same positions
    SceneOptions o;
    o.n = 150;
    o.world = 40;
    o.clump = 0.5;
    o.teleport = 0;
    o.kick = 0;
    cases.push_back({o, 20});
  }
  {  // many teleports and kicks
    SceneOptions o;
    o.n = 250;
    o.teleport = 0.1;
    o.kick = 0.1;
    cases.push_back({o, 40});
  }
  {  // sizes over five orders of magnitude (box sizes at every level of a grid's hierarchy)
    SceneOptions o;
    o.n = 400;
    o.world = 100;
    o.min_half = 1e-4;
    o.max_half = 8;
    cases.push_back({o, 30});
  }
  {  // a few thousand: the paper's density, small bodies
    SceneOptions o;
    o.n = 2500;
    o.world = 100;
    o.max_half = 2;
    cases.push_back({o, 8});
  }
  for (size_t c = 0; c < cases.size(); ++c) {
    const auto& cs = cases[c];
    TestScene scene(cs.o, seed + c);
    auto bp = make_broadphase(GetParam());
    EXPECT_EQ(bp->name(), GetParam());
    const int bad = run_against_brute_force(*bp, scene, cs.frames, 1000 * c, "case " + std::to_string(c));
    EXPECT_EQ(bad, 0) << "case " << c << " n " << cs.o.n << " seed " << seed;
  }
}

TEST_P(EachBroadphase, BodyCountChangesRestart) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu\n", (unsigned long long)seed);
  auto bp = make_broadphase(GetParam());
  uint64_t frame = 0;
  int k = 0;
  for (uint32_t n : {50u, 80u, 0u, 1u, 50u, 49u}) {
    SceneOptions o;
    o.n = n;
    o.world = 40;
    TestScene scene(o, seed + 77 + k++);
    EXPECT_EQ(run_against_brute_force(*bp, scene, 10, frame, "n " + std::to_string(n)), 0) << "seed " << seed;
    frame += 10;
  }
}

TEST_P(EachBroadphase, SameInputsSameOutputsAndStats) {
  const uint64_t seed = test::seed();
  SceneOptions o;
  o.n = 300;
  TestScene s1(o, seed), s2(o, seed);
  auto a = make_broadphase(GetParam()), b = make_broadphase(GetParam());
  for (uint64_t f = 0; f < 30; ++f) {
    if (f) s1.step(), s2.step();
    a->update(s1.bounds(), f);
    b->update(s2.bounds(), f);
    ASSERT_EQ(a->pairs(), b->pairs()) << "frame " << f << " seed " << seed;
    ASSERT_EQ(a->stats().overlap_tests, b->stats().overlap_tests) << "frame " << f << " seed " << seed;
  }
}

TEST_P(EachBroadphase, RejectsBadBoundsNamingTheBody) {
  SceneOptions o;
  o.n = 10;
  TestScene scene(o, 1);
  auto bodies = scene.bounds();
  bodies[7].box.lo.y() = std::nan("");
  auto bp = make_broadphase(GetParam());
  try {
    bp->update(bodies, 0);
    FAIL() << "NaN accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("body 7"), std::string::npos) << e.what();
  }
  bodies = scene.bounds();
  std::swap(bodies[3].box.lo.x(), bodies[3].box.hi.x());
  bodies[3].box.lo.x() += 1;  // lo > hi even for a flat box
  EXPECT_THROW(bp->update(bodies, 1), std::invalid_argument);
}

INSTANTIATE_TEST_SUITE_P(Broadphase, EachBroadphase, ::testing::ValuesIn(broadphase_names()),
                         [](const ::testing::TestParamInfo<std::string>& p) { return p.param; });

// With threads (Broadphase::set_pool: the grid searches, sorts and places its boxes on the pool; the others ignore
// it): the pairs and stats of the grid on one thread, frame by frame (brute force's pairs, for the smaller scenes);
// a bad body's error is the first bad body's.
TEST(Broadphase, GridOnAPoolGivesThePairsStatsAndErrorsOfOneThread) {
  const uint64_t seed = test::seed();
  std::vector<SceneOptions> cases;
  for (uint32_t n : {0u, 1u, 5u, 300u, 2500u}) {
    SceneOptions o;
    o.n = n;
    o.world = n > 1000 ? 100 : 60;
    o.max_half = n > 1000 ? 2 : 5;
    cases.push_back(o);
  }
  {  // sizes over five orders of magnitude: several levels of the grid, large boxes against each level
    SceneOptions o;
    o.n = 3000;
    o.min_half = 1e-4;
    o.max_half = 3;
    cases.push_back(o);
  }
  {  // identical boxes at the same positions
    SceneOptions o;
    o.n = 1500;
    o.world = 40;
    o.clump = 0.5;
    cases.push_back(o);
  }
  const size_t dense = cases.size();
  {  // crowded: more pairs a frame than the grid sorts on one thread (16,384), so they are sorted in buckets
    SceneOptions o;
    o.n = 4000;
    o.world = 30;
    o.max_half = 3;
    cases.push_back(o);
  }
  for (unsigned threads : {2u, 3u}) {
    ThreadPool pool(threads);
    for (size_t c = 0; c < cases.size(); ++c) {
      TestScene a(cases[c], seed + c), b(cases[c], seed + c);
      auto one = make_broadphase("grid"), many = make_broadphase("grid");
      many->set_pool(&pool);
      const std::string what = "case " + std::to_string(c) + ", " + std::to_string(threads) + " threads";
      if (cases[c].n <= 300) {
        EXPECT_EQ(run_against_brute_force(*many, a, 6, 0, what), 0) << what << " seed " << seed;
        for (uint64_t f = 0; f < 6; ++f) {
          if (f) b.step();
          one->update(b.bounds(), f);
        }
        ASSERT_EQ(one->pairs(), many->pairs()) << what;
        ASSERT_EQ(one->stats().overlap_tests, many->stats().overlap_tests) << what;
        continue;
      }
      for (uint64_t f = 0; f < 6; ++f) {
        if (f) a.step();
        one->update(a.bounds(), f);
        many->update(a.bounds(), f);
        ASSERT_EQ(one->pairs(), many->pairs()) << what << " frame " << f << " seed " << seed;
        ASSERT_EQ(one->stats().overlap_tests, many->stats().overlap_tests) << what << " frame " << f;
        ASSERT_GT(many->pairs().size(), c == dense ? 16384u : 0u) << what;
      }
    }
    SceneOptions o;
    o.n = 3000;
    TestScene scene(o, seed);
    auto bodies = scene.bounds();
    bodies[2900].box.lo.y() = std::nan("");
    bodies[1700].radius = -1;
    auto bp = make_broadphase("grid");
    bp->set_pool(&pool);
    try {
      bp->update(bodies, 0);
      FAIL() << "bad bodies accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("body 1700"), std::string::npos) << e.what();
    }
  }
}

// The grid visits its first level's boxes in the order of the last frame's entries when every body was in it then
// and is now (so that its sort by cell writes nearly in sequence): the pairs and the tests counted must be those of
// a grid that has seen no frame before (which visits them in body order), frame by frame, on one thread and on a
// pool; also when the bodies' sizes spread over levels in some frames and not in others, and when the count changes.
TEST(Broadphase, GridInTheLastFramesOrderGivesAFreshGridsPairsAndTests) {
  const uint64_t seed = test::seed();
  std::printf("seed %llu (VOXCD_SEED replays)\n", (unsigned long long)seed);
  std::vector<SceneOptions> cases;
  {  // one level, crowded, with teleports and kicks (bodies change cells by far)
    SceneOptions o;
    o.n = 3000;
    o.world = 40;
    o.min_half = 0.6;
    o.max_half = 1;
    o.teleport = 0.05;
    o.kick = 0.05;
    cases.push_back(o);
  }
  {  // identical boxes at the same positions: many boxes a cell
    SceneOptions o;
    o.n = 1500;
    o.world = 30;
    o.min_half = 0.5;
    o.max_half = 0.9;
    o.clump = 0.5;
    cases.push_back(o);
  }
  {  // sizes over five orders of magnitude: several levels
    SceneOptions o;
    o.n = 2000;
    o.min_half = 1e-4;
    o.max_half = 3;
    cases.push_back(o);
  }
  ThreadPool pool(2);
  for (ThreadPool* p : {static_cast<ThreadPool*>(nullptr), &pool}) {
    for (size_t c = 0; c < cases.size(); ++c) {
      TestScene scene(cases[c], seed + c);
      auto kept = make_broadphase("grid");
      kept->set_pool(p);
      for (uint64_t f = 0; f < 8; ++f) {
        if (f) scene.step();
        std::vector<BodyBounds> bodies = scene.bounds();
        // Frames 4 and 5: one body grows past twice the others (a second level), then another instead (as many
        // boxes in the first level, but not the same ones).
        if (f == 4) bodies[1].box.hi += Vec::Constant(50);
        if (f == 5) bodies[2].box.hi += Vec::Constant(50);
        if (f == 6) bodies.pop_back();  // one body fewer: no last order to follow
        auto fresh = make_broadphase("grid");
        fresh->set_pool(p);
        kept->update(bodies, f);
        fresh->update(bodies, f);
        const std::string what = "case " + std::to_string(c) + (p ? ", pool" : ", one thread") + ", frame " +
                                 std::to_string(f) + ", seed " + std::to_string(seed);
        ASSERT_EQ(kept->pairs(), fresh->pairs()) << what;
        ASSERT_EQ(kept->stats().overlap_tests, fresh->stats().overlap_tests) << what;
        ASSERT_GT(kept->pairs().size(), 0u) << what;
      }
    }
  }
}

TEST(Broadphase, NamesAndPredicates) {
  const std::vector<std::string> want = {"all", "sphere", "sap", "coherent", "queue", "tree", "grid"};
  EXPECT_EQ(broadphase_names(), want);
  EXPECT_EQ(make_broadphase("all")->predicate(), "all");
  EXPECT_EQ(make_broadphase("sphere")->predicate(), "sphere");
  EXPECT_EQ(make_broadphase("queue")->predicate(), "sphere");
  for (const char* n : {"sap", "coherent", "tree", "grid"}) EXPECT_EQ(make_broadphase(n)->predicate(), "box") << n;
}

// The broadphases that build on the previous frame's bodies say so (a distributed run restarts them when its slab's
// bodies change); the others rebuild every frame. Each names itself in its errors by its own name.
TEST(Broadphase, KeepsStateAndNamesItselfInErrors) {
  for (const std::string& n : broadphase_names()) {
    const auto bp = make_broadphase(n);
    EXPECT_EQ(bp->keeps_state(), n == "coherent" || n == "queue" || n == "tree") << n;
    std::vector<BodyBounds> b(2);
    b[1].box.lo.x() = 1;  // lo > hi
    try {
      bp->update(b, 7);
      ADD_FAILURE() << n << " took a box with lo > hi";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()), "broadphase " + n + ": body 1 at frame 7: box with lo > hi or NaN") << n;
    }
  }
}

TEST(Broadphase, UnknownNameListsTheNames) {
  try {
    make_broadphase("octree");
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("octree"), std::string::npos) << m;
    for (const auto& n : broadphase_names()) EXPECT_NE(m.find(n), std::string::npos) << m;
  }
}

// Degenerate and extreme inputs of the box broadphases against brute force: every body at one point, points on
// a line, tiny boxes spread over 10^9, and boxes near the largest doubles (whose sides overflow to infinity).
TEST(Broadphase, DegenerateAndExtremeScenesGiveTheExactPairs) {
  auto body = [](Vec lo, Vec hi) {
    BodyBounds b;
    b.box.lo = lo;
    b.box.hi = hi;
    b.centre = 0.5 * lo + 0.5 * hi;
    b.radius = 0;
    return b;
  };
  std::vector<std::pair<std::string, std::vector<BodyBounds>>> scenes;
  std::mt19937_64 rng(test::seed());
  auto uni = [&](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  {
    std::vector<BodyBounds> s(60, body(Vec(1, 2, 3), Vec(1, 2, 3)));
    scenes.push_back({"one point", s});
  }
  {
    std::vector<BodyBounds> s;
    for (int i = 0; i < 200; ++i) {
      const double x = std::floor(uni(0, 50));
      s.push_back(body(Vec(x, 0, 0), Vec(x, 0, 0)));
    }
    scenes.push_back({"points on a line", s});
  }
  {
    std::vector<BodyBounds> s;
    for (int i = 0; i < 300; ++i) {
      const Vec lo(uni(-1e9, 1e9), uni(-1e9, 1e9), uni(-1e-3, 1e-3));
      s.push_back(body(lo, lo + Vec::Constant(i % 3 ? 1e-9 : 1e8)));
    }
    scenes.push_back({"tiny and large boxes spread over 1e9", s});
  }
  {
    const double big = std::numeric_limits<double>::max();
    std::vector<BodyBounds> s;
    for (int i = 0; i < 100; ++i) {
      const Vec c(uni(-1, 1), uni(-1, 1), uni(-1, 1));
      if (i % 10 == 0)
        s.push_back(body(Vec::Constant(-big), Vec::Constant(big)));
      else if (i % 10 == 1)
        s.push_back(body(c * big, c * big));
      else
        s.push_back(body(c * 10, c * 10 + Vec::Constant(0.5)));
    }
    scenes.push_back({"boxes as wide as the doubles", s});
  }
  for (const auto& name : broadphase_names()) {
    auto bp = make_broadphase(name);
    if (bp->predicate() != "box") continue;
    uint64_t frame = 0;
    for (const auto& [what, bodies] : scenes) {
      bp->update(bodies, frame++);
      EXPECT_EQ(bp->pairs(), brute_force("box", bodies)) << name << ": " << what << ", seed " << test::seed();
    }
  }
}

// Directed boundary cases: boxes sharing a face, an edge or a corner overlap (closed boxes); spheres exactly
// touching overlap; a gap of one ulp separates.
TEST(Broadphase, TouchingCountsAndAnUlpSeparates) {
  auto body = [](Vec lo, Vec hi, Vec c, double r) {
    BodyBounds b;
    b.box.lo = lo;
    b.box.hi = hi;
    b.centre = c;
    b.radius = r;
    return b;
  };
  const double gap = std::nextafter(2.0, 3.0);
  const std::vector<BodyBounds> bodies = {
      body({0, 0, 0}, {1, 1, 1}, {10, 0, 0}, 1),          // 0
      body({1, 0, 0}, {2, 1, 1}, {12, 0, 0}, 1),          // 1: shares a face with 0; sphere touches 0's
      body({2, 1, 1}, {3, 2, 2}, {14, 0, 0} , 0.999),     // 2: shares a corner with 1; sphere misses 1's
      body({gap, 0, 0}, {3, 1, 1}, {30, 0, 0}, 0),        // 3: one ulp right of 1; a point sphere
      body({0, 0, 0}, {1, 1, 1}, {30, 0, 0}, 0),          // 4: box identical to 0; point sphere equal to 3's
  };
  const std::vector<BodyPair> box = {{0, 1}, {0, 4}, {1, 2}, {1, 4}, {2, 3}}, sphere = {{0, 1}, {3, 4}};
  for (const auto& name : broadphase_names()) {
    auto bp = make_broadphase(name);
    for (uint64_t f = 0; f < 3; ++f) {
      bp->update(bodies, f);
      if (bp->predicate() == "box") {
        EXPECT_EQ(bp->pairs(), box) << name;
      } else if (bp->predicate() == "sphere") {
        EXPECT_EQ(bp->pairs(), sphere) << name;
      } else {
        EXPECT_EQ(bp->pairs().size(), 10u) << name;
      }
    }
  }
}

// The queue tests few pairs when bodies are far apart and slow, and more when they are not.
TEST(Broadphase, QueuePrunesWithinItsBounds) {
  SceneOptions o;
  o.n = 400;
  o.teleport = 0;
  o.kick = 0;
  TestScene scene(o, test::seed());
  auto q = make_broadphase("queue");
  uint64_t tests = 0;
  for (uint64_t f = 0; f < 40; ++f) {
    if (f) scene.step();
    q->update(scene.bounds(), f);
    if (f) tests += q->stats().overlap_tests;
  }
  EXPECT_LT(tests, 39ull * 400 * 399 / 2 / 10) << "the queue should test under a tenth of all pairs";
}

// Controls: bodies that break their motion bounds without saying so make the queue miss pairs, so the random
// test above can fail. Two spheres approach at 5 a frame while promising 0.1.
TEST(Broadphase, QueueMissesWhenBoundsAreBrokenUnflagged) {
  std::vector<BodyBounds> b(2);
  for (int i = 0; i < 2; ++i) {
    b[i].radius = 1;
    b[i].max_speed = 0.1;
    b[i].box.lo = b[i].box.hi = Vec::Zero();
  }
  auto q = make_broadphase("queue");
  int missed = 0;
  for (uint64_t f = 0; f < 20; ++f) {
    b[0].centre = Vec(-50 + 5.0 * f, 0, 0);
    b[1].centre = Vec(50 - 5.0 * f, 0, 0);
    q->update(b, f);
    if (spheres_overlap(b[0], b[1]) && q->pairs().empty()) ++missed;
  }
  EXPECT_GT(missed, 0);
  // The same motion, flagged, is caught every frame.
  auto q2 = make_broadphase("queue");
  for (uint64_t f = 0; f < 20; ++f) {
    b[0].centre = Vec(-50 + 5.0 * f, 0, 0);
    b[1].centre = Vec(50 - 5.0 * f, 0, 0);
    b[0].moved_unexpectedly = b[1].moved_unexpectedly = f > 0;
    q2->update(b, f);
    EXPECT_EQ(q2->pairs().size(), spheres_overlap(b[0], b[1]) ? 1u : 0u) << "frame " << f;
  }
}

TEST(Broadphase, QueueMissesOnRandomScenesWithUnflaggedKicks) {
  SceneOptions o;
  o.n = 300;
  o.world = 50;
  o.kick = 0.05;
  o.flag = false;
  TestScene scene(o, test::seed());
  auto q = make_broadphase("queue");
  EXPECT_GT(run_against_brute_force(*q, scene, 60, 0, "unflagged kicks", false), 0)
      << "the generator breaks its bounds, the queue should miss; seed " << test::seed();
}

}  // namespace
}  // namespace voxcd
