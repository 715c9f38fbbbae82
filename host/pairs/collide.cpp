#include "voxcd/host/pairs/collider.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "voxcd/host/pairs/detail/cull.h"
#include "voxcd/host/pairs/detail/shell_order.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

// What the culling knows of a type's voxmap (or field) on cfg's device.
detail::EmptySpace empty_space(const DeviceConfig& cfg, const ObjectType& t) {
  if (!cfg.distance()) return t.voxmap().words().empty() ? detail::EmptySpace() : detail::EmptySpace::of_states(t.voxmap());
  return t.object.distance_sparse() ? detail::EmptySpace::of_sparse_field(t.object.sparse_distance)
                                    : detail::EmptySpace::of_field(t.object.distance);
}

}  // namespace

PairCollider::Clusters PairCollider::clusters_of(const std::vector<std::array<uint32_t, 3>>& cells,
                                                 const detail::ShellOrder& order) {
  Clusters cl;
  const std::vector<uint32_t>& slots = order.point;
  const std::vector<uint32_t>& block_first = order.block_first;
  // A sparse shell's job starts at a block's origin word: a cluster is a whole block.
  const uint64_t size = order.sparse() ? uint64_t{1} << 40 : kClusterPoints;
  for (uint32_t b = 0; b + 1 < block_first.size(); ++b)
    for (uint64_t k = block_first[b]; k < block_first[b + 1]; k += size) {
      const uint32_t end = uint32_t(std::min<uint64_t>(block_first[b + 1], k + size));
      std::array<uint32_t, 3> lo = cells[slots[k]], hi = lo;
      for (uint64_t s = k + 1; s < end; ++s)
        for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], cells[slots[s]][i]), hi[i] = std::max(hi[i], cells[slots[s]][i]);
      cl.first.push_back(uint32_t(k));
      cl.block.push_back(b);
      if (order.sparse()) cl.word.push_back(order.block_word[b]);
      for (int i = 0; i < 3; ++i) {
        // Point k is at cells[k] + 0.5 exactly (within half a cell more when PF = 0: the margin of 0.5).
        cl.centre[i].push_back(0.5 * (double(lo[i]) + double(hi[i])) + 0.5);
        cl.half[i].push_back(0.5 * (double(hi[i]) - double(lo[i])) + 0.5);
      }
    }
  cl.first.push_back(uint32_t(cells.size()));
  if (order.sparse()) cl.word.push_back(uint32_t(order.words.size()));
  return cl;
}

PairCollider::PairCollider(std::unique_ptr<Device> device, std::vector<std::shared_ptr<const ObjectType>> types,
                           std::shared_ptr<ThreadPool> pool)
    : device_(std::move(device)), parts_(part_runner(*device_)), types_(std::move(types)), pool_(std::move(pool)),
      image_(device_->config()) {
  if (!pool_ && parts_) pool_ = parts_->pool();
  if (pool_ && pool_->size() <= 1) pool_ = nullptr;
  const DeviceConfig& cfg = device_->config();
  for (const auto& t : types_) {
    detail::ShellOrder o = shell_order(cfg, *t);
    image_.add(*t, o);
    clusters_.push_back(clusters_of(t->shell().cells, o));
    order_.push_back(std::move(o.point));
    block_first_.push_back(std::move(o.block_first));
    block_word_.push_back(std::move(o.block_word));
    space_.push_back(std::make_shared<const detail::EmptySpace>(empty_space(cfg, *t)));
  }
  device_->load(image_.memory());
}

template <class Emit>
void PairCollider::runs_of(const Clusters& cl, const std::vector<uint64_t>& bits_, bool first_mode, const Emit& emit) {
  // Runs of kept clusters, a run at a time from the bit mask (ctz of the word, then of its complement: the keep
  // pattern is hard to predict, so a branch per cluster costs more than the whole cull); runs closer than kMergeGap
  // points apart are one job (a job costs more on the host than a few extra lookups), which also joins the two
  // halves of a run split by a word boundary.
  size_t run_first = 0, run_end = 0;  // clusters
  bool open = false;
  if (first_mode) {
    // FIRST: runs within one block, whose slots are in ascending point order (a sparse shell's: brick by brick), so
    // that each job's first hit is the lowest point among its hits (the pair keeps the lowest over its jobs).
    uint32_t block = 0;
    for (size_t w = 0; w < bits_.size(); ++w)
      for (uint64_t x = bits_[w]; x; x &= x - 1) {
        const size_t c = w * 64 + size_t(__builtin_ctzll(x));
        if (open && cl.block[c] == block && c == run_end) {
          run_end = c + 1;
          continue;
        }
        if (open) emit(run_first, run_end);
        run_first = c, run_end = c + 1, block = cl.block[c], open = true;
      }
    if (open) emit(run_first, run_end);
    return;
  }
  for (size_t w = 0; w < bits_.size(); ++w) {
    for (uint64_t x = bits_[w]; x;) {
      const unsigned s = unsigned(__builtin_ctzll(x));
      const uint64_t zeros = ~(x >> s);  // 0 only when the run fills the word from bit 0 up
      const unsigned len = zeros ? unsigned(__builtin_ctzll(zeros)) : 64u;
      x = s + len >= 64 ? 0 : x & (~uint64_t(0) << (s + len));
      const size_t first = w * 64 + s, end = first + len;
      if (open && cl.first[first] - cl.first[run_end] <= kMergeGap) {
        run_end = end;
      } else {
        if (open) emit(run_first, run_end);
        run_first = first;
        run_end = end;
        open = true;
      }
    }
  }
  if (open) emit(run_first, run_end);
}

void PairCollider::add_runs(const Job& whole, uint32_t shell_type, uint32_t map_type, const JobSource& src,
                            std::vector<Job>& out, std::vector<JobSource>& sources,
                            std::vector<uint64_t>& bits_) const {
  const DeviceConfig& cfg = device_->config();
  const Clusters& cl = clusters_[shell_type];
  auto emit = [&](size_t c0, size_t c1) {
    const uint32_t first = cl.first[c0], end = cl.first[c1];
    Job& j = out.emplace_back(whole);
    // A sparse shell's run is the words of its clusters (each a block, from its origin word).
    const bool words = !cl.word.empty();
    j.shell_base = whole.shell_base + (words ? cl.word[c0] : first);
    j.shell_count = words ? cl.word[c1] - cl.word[c0] : end - first;
    j.tag = uint32_t((out.size() - 1) & cfg.max_tag());
    sources.push_back({src.pair, src.a_in_b, first, end - first});
  };
  // A cluster's box (centre c, half-extent h, in the shell's grid) lands in the voxmap grid inside the box of
  // centre Mq c + tq and half-extent |Mq| h, exactly; the cluster is kept when that box meets [0, n) on every
  // axis (with a slack for the double arithmetic far below the spacing of the fixed-point values).
  const double mscale = detail::pow2(-cfg.MF), tscale = detail::pow2(-cfg.TF());
  double M[3][3], aM[3][3], t[3];
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k) M[i][k] = double(whole.M[i][k]) * mscale, aM[i][k] = std::abs(M[i][k]);
    t[i] = double(whole.t[i]) * tscale;
  }
  const double n[3] = {double(whole.nx), double(whole.ny), double(whole.nz)};
  const size_t nc = cl.first.size() - 1;
  bits_.resize((nc + 63) / 64);
  const detail::ClusterBoxes boxes{{cl.centre[0].data(), cl.centre[1].data(), cl.centre[2].data()},
                                   {cl.half[0].data(), cl.half[1].data(), cl.half[2].data()},
                                   nc};
  // Then the clusters inside the grid whose voxels are all empty air (or, on a distance device, all farther than
  // the threshold) are left out too: their lookups could not hit.
  detail::HitTest test;
  test.space = space_[map_type].get();
  test.field = cfg.distance();
  test.mask = whole.hit_mask;
  test.threshold = whole.threshold;
  test.wb = cfg.WB;
  for (int i = 0; i < 3; ++i) test.n[i] = n[i];
  if (pool_ && nc >= kParallelClusters) {
    // A large shell (a query of one pair of fine objects): word-aligned ranges of its clusters on the pool (a call
    // from inside a task of the pool runs them in turn).
    const size_t words = bits_.size();
    const Ranges parts = Ranges::of(words, kParallelClusters / 64, pool_->size());
    pool_->parallel_for(parts.parts, [&](size_t p) {
      const size_t w0 = parts.begin(p), w1 = parts.end(p);
      const size_t k0 = w0 * 64, k1 = std::min(nc, w1 * 64);
      const detail::ClusterBoxes part{{boxes.centre[0] + k0, boxes.centre[1] + k0, boxes.centre[2] + k0},
                                      {boxes.half[0] + k0, boxes.half[1] + k0, boxes.half[2] + k0},
                                      k1 - k0};
      detail::cull_clusters(part, M, aM, t, n, bits_.data() + w0);
      detail::cull_empty(part, M, aM, t, test, bits_.data() + w0);
    });
  } else {
    detail::cull_clusters(boxes, M, aM, t, n, bits_.data());
    detail::cull_empty(boxes, M, aM, t, test, bits_.data());
  }
  runs_of(cl, bits_, whole.mode == Mode::First, emit);
}

double PairCollider::speculative_reach(uint32_t s, uint32_t m, const PairOptions& opt) const {
  if (!opt.speculative || !device_->config().distance() || !(image_.placement(m).sparse & kSparseMap)) return 0;
  return std::sqrt(3.0) * types_[s]->shell().grid.voxel + 0.25 * types_[m]->voxmap().voxel();
}

std::vector<Job> PairCollider::jobs(const std::vector<PairRequest>& pairs, const PairOptions& opt) const {
  std::vector<Job> out;
  std::vector<JobSource> sources;
  jobs(pairs, opt, out, sources);
  return out;
}

void PairCollider::pair_jobs(size_t i, const PairRequest& r, const PairOptions& opt, std::vector<Job>& out,
                             std::vector<JobSource>& sources, std::vector<uint64_t>& bits) const {
  const DeviceConfig& cfg = device_->config();
  if (r.a >= types_.size() || r.b >= types_.size())
    throw std::out_of_range("pair " + std::to_string(i) + " names object type " + std::to_string(std::max(r.a, r.b)) +
                            " of " + std::to_string(types_.size()));
  for (int dir = 0; dir < (opt.both_directions ? 2 : 1); ++dir) {
    const uint32_t s = dir == 0 ? r.a : r.b, m = dir == 0 ? r.b : r.a;
    const RigidPose& ps = dir == 0 ? r.pose_a : r.pose_b;
    const RigidPose& pm = dir == 0 ? r.pose_b : r.pose_a;
    const DeviceImage::Placement& sp = image_.placement(s);
    const DeviceImage::Placement& mp = image_.placement(m);
    Job j;
    j.tag = uint32_t(out.size() & cfg.max_tag());
    j.mode = opt.mode;
    j.hit_mask = opt.hit_mask;
    j.shell_base = sp.shell_base;
    j.shell_count = sp.shell_count;
    j.sparse = uint8_t((sp.sparse & kSparseShell) | (mp.sparse & kSparseMap));
    j.map_base = mp.map_base;
    j.brick_base = mp.brick_base;
    j.brick_units = mp.brick_units;
    j.nx = mp.dims[0];
    j.ny = mp.dims[1];
    j.nz = mp.dims[2];
    try {
      pose_job(cfg, ps, types_[s]->shell().frame(), pm, types_[m]->voxmap().grid().frame(), j);
      if (cfg.distance())
        j.threshold = distance_threshold(cfg, opt.margin + speculative_reach(s, m, opt), types_[m]->voxmap().voxel(),
                                         types_[m]->object.distance_step());
    } catch (const RangeError& e) {
      const std::string pair =
          "pair " + std::to_string(i) + " (" + types_[r.a]->name + ", " + types_[r.b]->name + ")";
      throw RangeError(pair + ": " + e.what(), pair);
    }
    const JobSource src{uint32_t(i), dir == 0, 0, sp.points};
    if (opt.cull) {
      add_runs(j, s, m, src, out, sources, bits);
    } else if (opt.mode != Mode::First) {
      out.push_back(j);
      sources.push_back(src);
    } else {
      // FIRST: a job per block (see add_runs); a sparse shell's block is its words.
      const std::vector<uint32_t>& blocks = block_first_[s];
      const std::vector<uint32_t>& words = block_word_[s];
      for (size_t b = 0; b + 1 < blocks.size(); ++b) {
        Job& jb = out.emplace_back(j);
        jb.shell_base = j.shell_base + (words.empty() ? blocks[b] : words[b]);
        jb.shell_count = words.empty() ? blocks[b + 1] - blocks[b] : words[b + 1] - words[b];
        jb.tag = uint32_t((out.size() - 1) & cfg.max_tag());
        sources.push_back({src.pair, src.a_in_b, blocks[b], blocks[b + 1] - blocks[b]});
      }
    }
  }
}

void PairCollider::jobs(const std::vector<PairRequest>& pairs, const PairOptions& opt, std::vector<Job>& out,
                        std::vector<JobSource>& sources) const {
  out.clear();
  sources.clear();
  if (jobs_tasks_.empty()) jobs_tasks_.resize(1);
  if (!pool_ || pairs.size() < kParallelPairs) {
    out.reserve(pairs.size() * (opt.both_directions ? 2 : 1));
    for (size_t i = 0; i < pairs.size(); ++i) pair_jobs(i, pairs[i], opt, out, sources, jobs_tasks_[0].bits);
    return;
  }
  // Ranges of pairs on the pool, each into its own lists, joined in order (the tags renumbered by their place in
  // the stream). The lowest range that throws is the one the pool rethrows: the error of the first bad pair.
  const Ranges parts = Ranges::of(pairs.size(), kParallelPairs / 2, pool_->size());
  if (jobs_tasks_.size() < parts.parts) jobs_tasks_.resize(parts.parts);
  pool_->parallel_for(parts.parts, [&](size_t p) {
    JobsTask& t = jobs_tasks_[p];
    t.jobs.clear();
    t.sources.clear();
    for (size_t i = parts.begin(p); i < parts.end(p); ++i) pair_jobs(i, pairs[i], opt, t.jobs, t.sources, t.bits);
  });
  size_t total = 0;
  for (size_t p = 0; p < parts.parts; ++p) total += jobs_tasks_[p].jobs.size();
  out.reserve(total);
  sources.reserve(total);
  const uint32_t max_tag = device_->config().max_tag();
  for (size_t p = 0; p < parts.parts; ++p) {
    const JobsTask& t = jobs_tasks_[p];
    for (const Job& j : t.jobs) out.push_back(j), out.back().tag = uint32_t((out.size() - 1) & max_tag);
    sources.insert(sources.end(), t.sources.begin(), t.sources.end());
  }
}

}  // namespace voxcd
