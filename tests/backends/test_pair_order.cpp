// The pair tests' inside against the device contract taken plainly: PairCollider holds shells in blocks, culls
// clusters against a pyramid of each voxmap's empty space, ranks the hits back into point order and runs large
// batches in groups; whatever it does, every contact, hit and completion must be those of one job per direction over
// the shell in its own order on the reference device. Also the pyramid itself against brute force, and the block
// order and the ranks. Seed: printed; VOXCD_SEED replays.
#include <gtest/gtest.h>

#include <random>

#include "voxcd/host/device/device.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/pairs/detail/empty_space.h"
#include "voxcd/host/pairs/detail/shell_order.h"
#include "voxcd/ref/pipeline.h"
#include "tests/host/test_util.h"

namespace voxcd {
namespace {

std::shared_ptr<const ObjectType> type_of(const Mesh& mesh, double voxel, int bits = 0) {
  ObjectOptions o;
  o.voxel = voxel;
  o.distance_bits = bits;
  return std::make_shared<ObjectType>(make_object_type(make_object(mesh, mesh.name, 0, o), mesh.name));
}

uint64_t seed() {
  const uint64_t s = test::seed();
  return s;
}

Eigen::Quaterniond random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0, 1);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

// What one pair gives with one job per direction over the shell in its own order, on ref/: the contacts as (a_in_b,
// point, voxel, state, dist) and the hits.
struct Plain {
  std::vector<std::array<int64_t, 7>> contacts;
  uint32_t hits = 0;
};

Plain plain_pair(const DeviceConfig& cfg, const std::vector<std::shared_ptr<const ObjectType>>& types,
                 const PairRequest& r, const PairOptions& opt) {
  DeviceImage image(cfg);
  for (const auto& t : types) image.add(*t);
  Plain out;
  for (int dir = 0; dir < (opt.both_directions ? 2 : 1); ++dir) {
    const uint32_t s = dir == 0 ? r.a : r.b, m = dir == 0 ? r.b : r.a;
    Job j;
    j.mode = opt.mode;
    j.hit_mask = opt.hit_mask;
    j.shell_base = image.placement(s).shell_base;
    j.shell_count = image.placement(s).shell_count;
    j.map_base = image.placement(m).map_base;
    j.nx = image.placement(m).dims[0], j.ny = image.placement(m).dims[1], j.nz = image.placement(m).dims[2];
    pose_job(cfg, dir == 0 ? r.pose_a : r.pose_b, types[s]->shell().frame(), dir == 0 ? r.pose_b : r.pose_a,
             types[m]->voxmap().grid().frame(), j);
    if (cfg.distance())
      j.threshold = distance_threshold(cfg, opt.margin, types[m]->voxmap().voxel(), types[m]->object.distance.step);
    for (const Record& rec : run_stream(cfg, image.memory(), {j})) {
      if (rec.kind == Record::Done) {
        out.hits += rec.hits;
        continue;
      }
      out.contacts.push_back({dir == 0, rec.point, rec.x, rec.y, rec.z, rec.state, rec.dist});
    }
  }
  return out;
}

void expect_plain(const DeviceConfig& cfg, const std::vector<std::shared_ptr<const ObjectType>>& types,
                  const std::vector<PairRequest>& reqs, uint64_t& touching) {
  for (unsigned threads : {1u, 2u}) {
    DeviceOptions dopt;
    dopt.threads = threads;
    PairCollider col(make_device("cpu", cfg, dopt), types);
    for (Mode mode : {Mode::All, Mode::First, Mode::Count})
      for (bool cull : {true, false}) {
        PairOptions opt;
        opt.mode = mode;
        opt.both_directions = true;
        opt.cull = cull;
        opt.margin = cfg.distance() ? 0.02 : 0.0;
        ContactArrays arrays;
        const std::vector<PairResult> got = col.collide(reqs, opt);
        col.collide(reqs, opt, arrays);
        ASSERT_EQ(arrays.pairs(), reqs.size());
        for (size_t i = 0; i < reqs.size(); ++i) {
          SCOPED_TRACE("pair " + std::to_string(i) + " mode " + mode_name(mode) + " cull " + std::to_string(cull) +
                       " threads " + std::to_string(threads));
          const Plain want = plain_pair(cfg, types, reqs[i], opt);
          ASSERT_EQ(got[i].hits, want.hits);
          ASSERT_EQ(got[i].contacts.size(), want.contacts.size());
          ASSERT_EQ(arrays.first[i + 1] - arrays.first[i], want.contacts.size());
          EXPECT_EQ(arrays.hits[i], got[i].hits);
          EXPECT_EQ(arrays.lookups[i], got[i].lookups);
          EXPECT_EQ(arrays.device_cycles[i], got[i].device_cycles);
          for (size_t k = 0; k < want.contacts.size(); ++k) {
            const Contact& c = got[i].contacts[k];
            const auto& w = want.contacts[k];
            ASSERT_EQ(c.a_in_b, w[0] != 0) << "contact " << k;
            ASSERT_EQ(c.point, uint32_t(w[1])) << "contact " << k;
            ASSERT_EQ(c.voxel, (std::array<uint32_t, 3>{uint32_t(w[2]), uint32_t(w[3]), uint32_t(w[4])}));
            ASSERT_EQ(c.state, uint8_t(w[5]));
            const Contact a = arrays.contact(size_t(arrays.first[i]) + k);
            EXPECT_EQ(a.point, c.point);
            EXPECT_EQ(a.position, c.position);
            EXPECT_EQ(a.normal, c.normal);
            EXPECT_EQ(a.depth, c.depth);
            EXPECT_EQ(a.pair, uint32_t(i));
          }
          touching += want.hits > 0;
        }
      }
  }
}

TEST(PairOrder, ContactsAreThoseOfOneJobPerDirectionInShellOrder) {
  const uint64_t s = seed();
  std::mt19937_64 rng(s);
  std::uniform_real_distribution<double> u(-1, 1), dist(0, 2.5);
  Mesh plate = make_shape("plate");
  plate.name = "plate";
  for (int bits : {0, 8}) {
    const std::vector<std::shared_ptr<const ObjectType>> types = {
        type_of(make_shape("torus"), 0.11, bits), type_of(make_shape("stellated"), 0.09, bits), type_of(plate, 0.1, bits)};
    DeviceConfig cfg;
    if (bits) cfg.SB = bits;
    cfg = fit_memory(cfg, {types[0].get(), types[1].get(), types[2].get()});
    std::vector<PairRequest> reqs;
    for (int k = 0; k < 24; ++k) {
      PairRequest r;
      r.a = uint32_t(k % 3), r.b = uint32_t((k / 3) % 3);
      r.pose_a.rotation = random_rotation(rng);
      r.pose_b.rotation = random_rotation(rng);
      r.pose_b.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * dist(rng);
      reqs.push_back(r);
    }
    uint64_t touching = 0;
    expect_plain(cfg, types, reqs, touching);
    EXPECT_GT(touching, 40u) << "bits " << bits << ": the poses must touch for the comparison to mean something";
  }
}

TEST(PairOrder, ALargeBatchRunsInGroupsWithTheSameResultsAndCycles) {
  // More points than PairCollider::kGroupPoints: the batch runs in groups, each group's first job timed after the
  // previous group's last; the results must be those of the same poses one at a time, with the cycles of one stream.
  const uint64_t s = seed();
  std::mt19937_64 rng(s + 1);
  const auto a = type_of(make_torus(1.0, 0.35, 60, 30), 0.03), b = type_of(make_torus(0.8, 0.3, 60, 30), 0.03);
  std::vector<PairRequest> reqs;
  uint64_t points = 0;
  while (points < 3 * PairCollider::kGroupPoints) {
    PairRequest r;
    r.a = 0, r.b = 1;
    r.pose_b.rotation = random_rotation(rng);
    r.pose_b.translation = Eigen::Vector3d(0.3, -0.2, 0.1) * double(reqs.size() % 4);
    reqs.push_back(r);
    points += a->shell().size() + b->shell().size();
  }
  const DeviceConfig cfg = fit_memory(DeviceConfig{}, {a.get(), b.get()});
  PairCollider col(make_device("cpu", cfg), {a, b});
  PairOptions opt;
  opt.both_directions = true;
  const std::vector<PairResult> batch = col.collide(reqs, opt);
  // The cycles of the whole batch as one stream on ref/, from the same jobs in the collider's memory image.
  std::vector<Job> jobs;
  std::vector<JobSource> sources;
  col.jobs(reqs, opt, jobs, sources);
  auto ref = make_device("ref", cfg);
  ref->load(col.image().memory());
  std::vector<uint64_t> cycles(reqs.size(), 0);
  size_t j = 0;
  for (const Record& r : ref->run(jobs))
    if (r.kind == Record::Done) cycles[sources[j++].pair] += r.cycles.value_or(0);
  ASSERT_EQ(j, jobs.size());
  uint64_t hits = 0;
  std::vector<PairResult> one;
  for (size_t i = 0; i < reqs.size(); ++i) {
    SCOPED_TRACE("pair " + std::to_string(i));
    EXPECT_EQ(batch[i].device_cycles, cycles[i]);
    col.collide({reqs[i]}, opt, one);
    ASSERT_EQ(one[0].hits, batch[i].hits);
    EXPECT_EQ(one[0].lookups, batch[i].lookups);
    ASSERT_EQ(one[0].contacts.size(), batch[i].contacts.size());
    for (size_t k = 0; k < one[0].contacts.size(); ++k) {
      EXPECT_EQ(one[0].contacts[k].point, batch[i].contacts[k].point);
      EXPECT_EQ(one[0].contacts[k].position, batch[i].contacts[k].position);
    }
    hits += batch[i].hits;
  }
  EXPECT_GT(hits, 1000u);
}

// Every field of every contact, and each pair's hits, lookups and cycles, the same bit for bit.
void expect_same_results(const std::vector<PairResult>& got, const std::vector<PairResult>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    SCOPED_TRACE("pair " + std::to_string(i));
    ASSERT_EQ(got[i].hits, want[i].hits);
    EXPECT_EQ(got[i].lookups, want[i].lookups);
    EXPECT_EQ(got[i].device_cycles, want[i].device_cycles);
    ASSERT_EQ(got[i].contacts.size(), want[i].contacts.size());
    for (size_t k = 0; k < want[i].contacts.size(); ++k) {
      const Contact &c = got[i].contacts[k], &w = want[i].contacts[k];
      ASSERT_EQ(c.pair, w.pair) << "contact " << k;
      ASSERT_EQ(c.a_in_b, w.a_in_b) << "contact " << k;
      ASSERT_EQ(c.point, w.point) << "contact " << k;
      ASSERT_EQ(c.voxel, w.voxel) << "contact " << k;
      ASSERT_EQ(c.state, w.state) << "contact " << k;
      ASSERT_EQ(c.position, w.position) << "contact " << k;
      ASSERT_EQ(c.normal, w.normal) << "contact " << k;
      ASSERT_EQ(c.depth, w.depth) << "contact " << k;
    }
  }
}

TEST(PairOrder, HitColumnsGiveTheContactsAndCyclesOfTheRecordStream) {
  // The cpu backend hands the collider its hits in columns with each job's cycles (Device::run_part, on one thread,
  // and run_piece on the pool for groups of many points); the ref backend gives a stream of records, which the
  // collider turns into the same columns. Both must give the same contacts (position, normal, depth, order), hits,
  // lookups and cycles, in every mode, on 2-bit, distance and banked devices, for random poses and poses that put
  // the shell across the edges of the other's grid.
  const uint64_t s = seed();
  std::mt19937_64 rng(s + 5);
  std::uniform_real_distribution<double> u(-1, 1), dist(0, 2.5);
  for (int variant = 0; variant < 3; ++variant) {
    const int bits = variant == 1 ? 8 : 0;
    const std::vector<std::shared_ptr<const ObjectType>> types = {type_of(make_torus(1.0, 0.35, 40, 20), 0.04, bits),
                                                                  type_of(make_shape("stellated"), 0.06, bits)};
    DeviceConfig cfg;
    if (bits) cfg.SB = bits;
    if (variant == 2) cfg.BANKS = 2, cfg.LANES = 4;
    cfg = fit_memory(cfg, {types[0].get(), types[1].get()});
    std::vector<PairRequest> reqs;
    for (int k = 0; k < 16; ++k) {
      PairRequest r;
      r.a = uint32_t(k % 2), r.b = uint32_t((k / 2) % 2);
      r.pose_a.rotation = random_rotation(rng);
      r.pose_b.rotation = random_rotation(rng);
      // Every fourth pose at the edge of A's reach: the shells straddle the other's grid bounds.
      r.pose_b.translation = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * (k % 4 == 3 ? 1.6 : dist(rng));
      reqs.push_back(r);
    }
    PairCollider want_col(make_device("ref", cfg), types);
    for (unsigned threads : {1u, 2u}) {
      DeviceOptions dopt;
      dopt.threads = threads;
      PairCollider col(make_device("cpu", cfg, dopt), types);
      for (Mode mode : {Mode::All, Mode::First, Mode::Count}) {
        SCOPED_TRACE("variant " + std::to_string(variant) + " threads " + std::to_string(threads) + " mode " +
                     mode_name(mode));
        PairOptions opt;
        opt.mode = mode;
        opt.both_directions = true;
        opt.margin = bits ? 0.02 : 0.0;
        const std::vector<PairResult> want = want_col.collide(reqs, opt);
        expect_same_results(col.collide(reqs, opt), want);
        ContactArrays arrays;
        col.collide(reqs, opt, arrays);
        ASSERT_EQ(arrays.size(), [&] {
          size_t n = 0;
          for (const PairResult& r : want) n += r.contacts.size();
          return n;
        }());
        for (size_t i = 0; i < want.size(); ++i)
          for (size_t k = 0; k < want[i].contacts.size(); ++k) {
            const Contact a = arrays.contact(size_t(arrays.first[i]) + k), &w = want[i].contacts[k];
            ASSERT_TRUE(a.point == w.point && a.a_in_b == w.a_in_b && a.voxel == w.voxel && a.state == w.state &&
                        a.position == w.position && a.normal == w.normal && a.depth == w.depth)
                << "pair " << i << " row " << k;
          }
        if (mode == Mode::All) {
          uint64_t contacts = 0;
          for (const PairResult& r : want) contacts += r.contacts.size();
          EXPECT_GT(contacts, 1000u) << "the poses must touch for the comparison to mean something";
        }
      }
    }
  }
}

TEST(PairOrder, EmptySpaceNeverHidesAHitAndFindsTheEmptyBoxes) {
  // Random sparse voxmaps (and the distance field of a shape) against brute force over random boxes: a box the
  // pyramid calls empty holds no voxel of the mask's states (no cell whose nodes reach the threshold), and at the
  // finest level of a small map most empty boxes are found empty.
  const uint64_t s = seed();
  std::mt19937_64 rng(s + 2);
  std::uniform_int_distribution<int> coord(-4, 40), size(0, 12), state(0, 99);
  GridPlacement g;
  g.dims = {37, 23, 29};
  g.voxel = 1;
  Voxmap vm(g);
  for (uint64_t i = 0; i < vm.size(); ++i) {
    const int r = state(rng);
    vm.set(i, r < 3 ? kSurface : r < 5 ? kInterior : kEmpty);
  }
  const detail::EmptySpace space = detail::EmptySpace::of_states(vm);
  EXPECT_EQ(space.base_block(), 1u);
  uint64_t empty = 0, found = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::array<int64_t, 3> lo, hi;
    for (size_t i = 0; i < 3; ++i) lo[i] = coord(rng), hi[i] = lo[i] + size(rng) / 3;
    for (uint32_t mask : {2u, 4u, 6u, 1u}) {
      bool any = false;
      for (int64_t z = std::max<int64_t>(lo[2], 0); z <= std::min<int64_t>(hi[2], g.dims[2] - 1); ++z)
        for (int64_t y = std::max<int64_t>(lo[1], 0); y <= std::min<int64_t>(hi[1], g.dims[1] - 1); ++y)
          for (int64_t x = std::max<int64_t>(lo[0], 0); x <= std::min<int64_t>(hi[0], g.dims[0] - 1); ++x)
            any |= ((mask >> int(vm.at(uint32_t(x), uint32_t(y), uint32_t(z)))) & 1) != 0;
      const bool may = space.may_hit_states(lo, hi, mask);
      ASSERT_TRUE(may || !any) << "trial " << trial << " mask " << mask;
      empty += !any, found += !any && !may;
    }
  }
  EXPECT_GT(empty, 1000u);
  EXPECT_GT(double(found), 0.9 * double(empty)) << "the pyramid should find most empty boxes of a small map";
  // A distance field: a cell may hit when its least node <= floor(threshold / 2^(3 wb)).
  const auto t = type_of(make_shape("torus"), 0.12, 8);
  const DistanceField& f = t->object.distance;
  const detail::EmptySpace field = detail::EmptySpace::of_field(f);
  const int wb = DeviceConfig{}.WB;
  std::uniform_int_distribution<int64_t> thr(-(int64_t(1) << 30), int64_t(1) << 30);
  uint64_t far = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::array<int64_t, 3> lo, hi;
    for (size_t i = 0; i < 3; ++i) {
      lo[i] = std::uniform_int_distribution<int64_t>(-2, int64_t(f.dims[i]))(rng);
      hi[i] = lo[i] + std::uniform_int_distribution<int64_t>(0, 4)(rng);
    }
    const int64_t threshold = thr(rng);
    bool any = false;
    for (int64_t z = std::max<int64_t>(lo[2], 0); z <= std::min<int64_t>(hi[2], f.dims[2] - 1); ++z)
      for (int64_t y = std::max<int64_t>(lo[1], 0); y <= std::min<int64_t>(hi[1], f.dims[1] - 1); ++y)
        for (int64_t x = std::max<int64_t>(lo[0], 0); x <= std::min<int64_t>(hi[0], f.dims[0] - 1); ++x) {
          int least = f.qmax();
          for (int c = 0; c < 8; ++c) least = std::min(least, f.at(uint64_t(x + (c & 1)), uint64_t(y + (c >> 1 & 1)),
                                                                  uint64_t(z + (c >> 2 & 1))));
          any |= int64_t(least) * (int64_t{1} << (3 * wb)) <= threshold;
        }
    const bool may = field.may_hit_field(lo, hi, threshold, wb);
    ASSERT_TRUE(may || !any) << "trial " << trial;
    far += !may;
  }
  EXPECT_GT(far, 100u) << "some boxes must lie beyond the threshold";
}

TEST(PairOrder, BlockOrderAndRanks) {
  // Every point once, blocks in order, ascending within a block; the ranks of any set of hits their order.
  const auto t = type_of(make_shape("torus"), 0.05);
  const auto& cells = t->shell().cells;
  const detail::ShellOrder o = detail::block_order(cells);
  ASSERT_EQ(o.point.size(), cells.size());
  std::vector<bool> seen(cells.size(), false);
  for (uint32_t p : o.point) {
    ASSERT_FALSE(seen.at(p));
    seen[p] = true;
  }
  ASSERT_EQ(o.block_first.back(), cells.size());
  for (size_t b = 0; b + 1 < o.block_first.size(); ++b) {
    ASSERT_LT(o.block_first[b], o.block_first[b + 1]) << "an empty block";
    for (uint32_t k = o.block_first[b]; k < o.block_first[b + 1]; ++k) {
      for (size_t i = 0; i < 3; ++i)
        ASSERT_EQ(cells[o.point[k]][i] / detail::ShellOrder::kBlock, cells[o.point[o.block_first[b]]][i] / detail::ShellOrder::kBlock);
      if (k > o.block_first[b]) {
        ASSERT_LT(o.point[k - 1], o.point[k]);
      }
    }
  }
  std::mt19937_64 rng(seed() + 3);
  detail::RankBits ranks;
  for (int trial = 0; trial < 50; ++trial) {
    // Hits at random slots, in two spans (two jobs), each ascending by slot.
    std::vector<uint32_t> hits;
    for (uint32_t k = 0; k < o.point.size(); ++k)
      if (rng() % 7 == 0) hits.push_back(k);
    const size_t half = hits.size() / 2;
    detail::HitSpan spans[2] = {{hits.data(), half, 0, 0}, {hits.data() + half, hits.size() - half, 0, half}};
    std::vector<detail::SortedHit> sorted(hits.size(), detail::SortedHit{UINT32_MAX, 0});
    ranks.place(spans, 2, o.point.data(), o.point.size(), sorted.data());
    std::vector<uint32_t> at(hits.size());
    for (size_t k = 0; k < hits.size(); ++k) {
      ASSERT_LT(sorted[k].hit, hits.size()) << "trial " << trial << ": no hit at " << k;
      ASSERT_EQ(sorted[k].point, o.point[hits[sorted[k].hit]]);
      at[k] = sorted[k].point;
    }
    ASSERT_TRUE(std::is_sorted(at.begin(), at.end())) << "trial " << trial;
    ASSERT_EQ(std::adjacent_find(at.begin(), at.end()), at.end());
  }
}

}  // namespace
}  // namespace voxcd
