#include "voxcd/host/pairs/collide.h"

#include <algorithm>
#include <cmath>

#include "voxcd/host/pairs/detail/cull.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/fast/thread_pool.h"
#include "voxcd/ref/fixed.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

void check_distance(const DeviceConfig& cfg, const ObjectType& t) {
  if (!cfg.distance()) return;
  const DistanceField& f = t.object.distance;
  if (f.empty())
    throw CapacityError("object '" + t.name + "' has no distance field, and the device holds distance voxmaps (SB = " +
                        std::to_string(cfg.SB) + "): voxelise it with --distance-bits " + std::to_string(cfg.SB));
  if (f.bits > cfg.SB)
    throw CapacityError("object '" + t.name + "' has a distance field of " + std::to_string(f.bits) +
                        " bits, wider than the device's SB = " + std::to_string(cfg.SB));
}

void check_dims(const DeviceConfig& cfg, const ObjectType& t) {
  const auto& d = t.voxmap().dims();
  for (int i = 0; i < 3; ++i)
    if (d[i] > cfg.max_dim())
      throw CapacityError("object '" + t.name + "': its voxmap is " + std::to_string(d[0]) + "x" +
                          std::to_string(d[1]) + "x" + std::to_string(d[2]) + " voxels, above the device's 2^DW = " +
                          std::to_string(cfg.max_dim()) + " per axis");
}

}  // namespace

uint64_t type_map_words(const DeviceConfig& cfg, const ObjectType& t) {
  Job j;
  j.nx = t.voxmap().dims()[0];
  j.ny = t.voxmap().dims()[1];
  j.nz = t.voxmap().dims()[2];
  return map_words(cfg, j);  // ref/: states, or the distance field's parity banks
}

uint32_t DeviceImage::add(const ObjectType& t) {
  check_dims(cfg_, t);
  check_distance(cfg_, t);
  // A distance map starts on a bank boundary: the words before it up to one are padding.
  const uint64_t pad = cfg_.distance() ? (8 - mem_.map.size() % 8) % 8 : 0;
  const uint64_t shell = t.shell().size(), words = type_map_words(cfg_, t) + pad;
  const uint64_t shell_free = cfg_.shell_depth() - mem_.shell.size(), map_free = cfg_.map_depth() - mem_.map.size();
  if (shell > shell_free || words > map_free)
    throw CapacityError("object '" + t.name + "' needs " + std::to_string(shell) + " shell words and " +
                        std::to_string(words) + " voxmap words; the device has " + std::to_string(shell_free) +
                        " of 2^SAW = " + std::to_string(cfg_.shell_depth()) + " shell words and " +
                        std::to_string(map_free) + " of 2^MAW = " + std::to_string(cfg_.map_depth()) +
                        " voxmap words free");
  std::vector<ShellWord> sw = t.shell().words(cfg_);
  std::vector<uint64_t> mw = cfg_.distance() ? t.object.distance.device_words(cfg_) : t.voxmap().device_words(cfg_.MEMW);
  mem_.map.resize(mem_.map.size() + pad, 0);
  Placement p;
  p.shell_base = uint32_t(mem_.shell.size());
  p.shell_count = uint32_t(shell);
  p.map_base = uint32_t(mem_.map.size());
  p.map_words = uint32_t(words - pad);
  p.dims = t.voxmap().dims();
  mem_.shell.insert(mem_.shell.end(), sw.begin(), sw.end());
  mem_.map.insert(mem_.map.end(), mw.begin(), mw.end());
  placements_.push_back(p);
  return uint32_t(placements_.size() - 1);
}

DeviceConfig fit_memory(DeviceConfig cfg, const std::vector<const ObjectType*>& types) {
  uint64_t shell = 0, words = 0;
  for (const ObjectType* t : types) {
    check_dims(cfg, *t);
    check_distance(cfg, *t);
    shell += t->shell().size();
    words += type_map_words(cfg, *t) + (cfg.distance() ? 7 : 0);  // at most 7 words of padding before a map
  }
  while (cfg.shell_depth() < shell && cfg.SAW < 24) ++cfg.SAW;
  while (cfg.map_depth() < words && cfg.MAW < 28) ++cfg.MAW;
  if (cfg.shell_depth() < shell || cfg.map_depth() < words)
    throw CapacityError("the object types need " + std::to_string(shell) + " shell words and " +
                        std::to_string(words) + " voxmap words; the largest device memories hold 2^24 and 2^28");
  return cfg;
}

DeviceConfig device_config_for(const std::string& backend, int lanes, const std::vector<const ObjectType*>& types,
                               int distance_bits) {
  DeviceConfig cfg;
  cfg.LANES = lanes;
  if (distance_bits > 0) cfg.SB = distance_bits;
  return backend == "rtl" ? cfg : fit_memory(cfg, types);
}

PairCollider::PairCollider(std::unique_ptr<Device> device, std::vector<std::shared_ptr<const ObjectType>> types,
                           std::shared_ptr<ThreadPool> pool)
    : device_(std::move(device)), types_(std::move(types)), pool_(std::move(pool)), image_(device_->config()) {
  if (!pool_) pool_ = device_->pool();
  if (pool_ && pool_->size() <= 1) pool_ = nullptr;
  for (const auto& t : types_) {
    image_.add(*t);
    // Clusters of up to kClusterPoints consecutive points, never across a z-slice of the shell grid (cells come
    // in linear-index order, z slowest): small boxes, since consecutive points of one slice are near each other.
    const auto& cells = t->shell().cells;
    Clusters cl;
    for (uint32_t k = 0; k < cells.size();) {
      uint32_t end = k + 1;
      std::array<uint32_t, 3> lo = cells[k], hi = cells[k];
      while (end < cells.size() && end - k < kClusterPoints && cells[end][2] == cells[k][2]) {
        for (int i = 0; i < 3; ++i) lo[i] = std::min(lo[i], cells[end][i]), hi[i] = std::max(hi[i], cells[end][i]);
        ++end;
      }
      cl.first.push_back(k);
      for (int i = 0; i < 3; ++i) {
        // Point k is at cells[k] + 0.5 exactly (within half a cell more when PF = 0: the margin of 0.5).
        cl.centre[i].push_back(0.5 * (double(lo[i]) + double(hi[i])) + 0.5);
        cl.half[i].push_back(0.5 * (double(hi[i]) - double(lo[i])) + 0.5);
      }
      k = end;
    }
    cl.first.push_back(uint32_t(cells.size()));
    clusters_.push_back(std::move(cl));
  }
  device_->load(image_.memory());
}

void PairCollider::add_runs(const Job& whole, uint32_t shell_type, const JobSource& src, std::vector<Job>& out,
                            std::vector<JobSource>& sources, std::vector<uint64_t>& bits_) const {
  const DeviceConfig& cfg = device_->config();
  auto emit = [&](uint32_t first, uint32_t end) {
    Job& j = out.emplace_back(whole);
    j.shell_base = whole.shell_base + first;
    j.shell_count = end - first;
    j.tag = uint32_t((out.size() - 1) & cfg.max_tag());
    sources.push_back({src.pair, src.a_in_b, first});
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
  const Clusters& cl = clusters_[shell_type];
  const size_t nc = cl.first.size() - 1;
  bits_.resize((nc + 63) / 64);
  const detail::ClusterBoxes boxes{{cl.centre[0].data(), cl.centre[1].data(), cl.centre[2].data()},
                                   {cl.half[0].data(), cl.half[1].data(), cl.half[2].data()},
                                   nc};
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
    });
  } else {
    detail::cull_clusters(boxes, M, aM, t, n, bits_.data());
  }
  // Runs of kept clusters, a run at a time from the bit mask (ctz of the word, then of its complement: the keep
  // pattern is hard to predict, so a branch per cluster costs more than the whole cull); runs closer than kMergeGap
  // points apart are one job (a job costs more on the host than a few extra lookups), which also joins the two
  // halves of a run split by a word boundary.
  uint32_t run_first = 0, run_end = 0;
  bool open = false;
  for (size_t w = 0; w < bits_.size(); ++w) {
    for (uint64_t x = bits_[w]; x;) {
      const unsigned s = unsigned(__builtin_ctzll(x));
      const uint64_t zeros = ~(x >> s);  // 0 only when the run fills the word from bit 0 up
      const unsigned len = zeros ? unsigned(__builtin_ctzll(zeros)) : 64u;
      x = s + len >= 64 ? 0 : x & (~uint64_t(0) << (s + len));
      const uint32_t first = cl.first[w * 64 + s], end = cl.first[w * 64 + s + len];
      if (open && first - run_end <= kMergeGap) {
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
    j.map_base = mp.map_base;
    j.nx = mp.dims[0];
    j.ny = mp.dims[1];
    j.nz = mp.dims[2];
    try {
      pose_job(cfg, ps, types_[s]->shell().frame(), pm, types_[m]->voxmap().grid().frame(), j);
      if (cfg.distance())
        j.threshold = distance_threshold(cfg, opt.margin, types_[m]->voxmap().voxel(), types_[m]->object.distance.step);
    } catch (const RangeError& e) {
      throw RangeError("pair " + std::to_string(i) + " (" + types_[r.a]->name + ", " + types_[r.b]->name +
                       "): " + e.what());
    }
    const JobSource src{uint32_t(i), dir == 0, 0};
    if (opt.cull) {
      add_runs(j, s, src, out, sources, bits);
    } else {
      out.push_back(j);
      sources.push_back(src);
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

std::vector<PairResult> PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt) {
  std::vector<PairResult> out;
  collide(pairs, opt, out);
  return out;
}

void PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt,
                           std::vector<PairResult>& out) {
  jobs(pairs, opt, jobs_, sources_);
  if (pool_ && device_->runs_parts()) {
    size_t points = 0;
    for (const Job& j : jobs_) points += j.shell_count;
    if (points >= kParallelPoints) return collide_pieces(pairs, opt, out);
  }
  device_->run_into(jobs_, records_);
  const std::vector<Job>& js = jobs_;
  const size_t nrec = records_.size();
  // The stream is checked whole before `out` is touched, so a misbehaving device leaves the caller's results as
  // they were: the completion records, one per job, the last record one of them.
  job_records_.resize(js.size());
  {
    size_t job = 0, last = SIZE_MAX;
    auto done = [&](size_t r) {
      if (job == js.size())
        throw DeviceError("the device returned records after the completions of all " + std::to_string(js.size()) +
                          " jobs");
      job_records_[job++].first = last + 1;
      last = r;
    };
    if (pool_ && nrec >= kParallelScan) {
      const Ranges parts = Ranges::of(nrec, kParallelScan / 4, pool_->size());
      if (done_parts_.size() < parts.parts) done_parts_.resize(parts.parts);
      pool_->parallel_for(parts.parts, [&](size_t p) {
        std::vector<size_t>& d = done_parts_[p];
        d.clear();
        for (size_t r = parts.begin(p); r < parts.end(p); ++r)
          if (records_[r].kind == Record::Done) d.push_back(r);
      });
      for (size_t p = 0; p < parts.parts; ++p)
        for (size_t r : done_parts_[p]) done(r);
    } else {
      for (size_t r = 0; r < nrec; ++r)
        if (records_[r].kind == Record::Done) done(r);
    }
    if (job != js.size() || last + 1 != nrec)
      throw DeviceError(job != js.size() ? "the device returned fewer completions than the " + std::to_string(js.size()) +
                                               " jobs it was given"
                                         : "the device returned records after the completions of all " +
                                               std::to_string(js.size()) + " jobs");
  }
  // Pair by pair (on the pool in ranges of pairs when they are many; a pair's jobs are consecutive): which hit
  // records make contacts (FIRST: only the first hit of a direction, over its jobs), the pair's hits, lookups and
  // cycles, its contacts in place (a vector that holds more already only shrinks: no contact is constructed twice)
  // and, for a pair with contacts, the pose of its objects as matrices.
  out.resize(pairs.size());
  first_job_.resize(pairs.size() + 1);  // pair i's jobs: [first_job_[i], first_job_[i + 1])
  for (size_t i = 0, j = 0; i <= pairs.size(); ++i) {
    while (j < js.size() && sources_[j].pair < i) ++j;
    first_job_[i] = j;
  }
  rot_a_.resize(pairs.size());
  rot_b_.resize(pairs.size());
  const Ranges parts = pool_ranges(pool_.get(), pairs.size(), kParallelPairs);
  if (kept_parts_.size() < parts.parts) kept_parts_.resize(parts.parts);
  for_ranges(pool_.get(), parts, [&](size_t part, size_t p0, size_t p1) {
    kept_parts_[part].value = tally(pairs.data(), p0, p1, opt, js.data(), sources_.data(), js.size(), first_job_.data(),
                                    job_records_.data(), records_.data(), nrec, out.data(), rot_a_.data(), rot_b_.data());
  });
  size_t kept_total = 0;
  for (size_t p = 0; p < parts.parts; ++p) kept_total += kept_parts_[p].value;
  if (!pool_ || kept_total < kParallelContacts) {
    for (size_t j = 0; j < js.size(); ++j)
      if (job_records_[j].kept)
        make_contacts(pairs[sources_[j].pair], sources_[j].pair, sources_[j], records_.data() + job_records_[j].first,
                      job_records_[j].kept, rot_a_[sources_[j].pair], rot_b_[sources_[j].pair],
                      out[sources_[j].pair].contacts.data() + job_records_[j].at);
    return;
  }
  // In pieces of up to kContactPiece records on the pool, each written to its place.
  contact_pieces_.clear();
  for (size_t j = 0; j < js.size(); ++j) {
    const Part::JobRecords& jr = job_records_[j];
    Contact* to = out[sources_[j].pair].contacts.data() + jr.at;
    for (size_t k = 0; k < jr.kept; k += kContactPiece)
      contact_pieces_.push_back({j, jr.first + k, std::min(kContactPiece, jr.kept - k), to + k});
  }
  pool_->parallel_for(contact_pieces_.size(), [&](size_t p) {
    const ContactPiece& c = contact_pieces_[p];
    const JobSource& src = sources_[c.job];
    make_contacts(pairs[src.pair], src.pair, src, records_.data() + c.first, c.n, rot_a_[src.pair], rot_b_[src.pair],
                  c.to);
  });
}

void PairCollider::collide_pieces(const std::vector<PairRequest>& pairs, const PairOptions& opt,
                                  std::vector<PairResult>& out) {
  const std::vector<Job>& js = jobs_;
  const DeviceConfig& cfg = device_->config();
  const bool cycles = device_->models_cycles(), first_only = opt.mode == Mode::First;
  // Pieces of at most kPiecePoints points; tasks: runs of consecutive pieces of at least kTaskPoints points.
  pieces_.clear();
  job_first_piece_.resize(js.size() + 1);
  for (size_t j = 0; j < js.size(); ++j) {
    job_first_piece_[j] = pieces_.size();
    for (uint32_t b = 0; b < js[j].shell_count; b += uint32_t(kPiecePoints)) {
      Piece& p = pieces_.emplace_back();
      p.job = j;
      p.begin = b;
      p.end = uint32_t(std::min<size_t>(js[j].shell_count, b + kPiecePoints));
    }
  }
  job_first_piece_[js.size()] = pieces_.size();
  task_first_piece_.clear();
  for (size_t i = 0, acc = kTaskPoints; i < pieces_.size(); ++i) {
    if (acc >= kTaskPoints) task_first_piece_.push_back(i), acc = 0;
    acc += pieces_[i].end - pieces_[i].begin;
  }
  task_first_piece_.push_back(pieces_.size());
  const size_t tasks = task_first_piece_.size() - 1;
  if (piece_hits_.size() < tasks) piece_hits_.resize(tasks);
  // The lookups. A task validates a job before its first piece of it, so the lowest task that throws names the first
  // invalid job (the error run_into gives); `out` is not touched before every task has finished.
  pool_->parallel_for(tasks, [&](size_t t) {
    std::vector<Record>& hits = piece_hits_[t].value;
    hits.clear();
    size_t validated = SIZE_MAX;
    for (size_t i = task_first_piece_[t]; i < task_first_piece_[t + 1]; ++i) {
      Piece& p = pieces_[i];
      const Job& j = js[p.job];
      p.task = t;
      p.first = hits.size();
      p.count = 0;
      device_->run_piece(j, p.begin, p.end, validated != p.job, hits, p.count);
      validated = p.job;
      p.records = hits.size() - p.first;
      if (cycles) p.sum = job_hits(cfg, j, p.job, hits.data() + p.first, p.records);
    }
  });
  // Job by job, in order: its hits and summary as the device's stream would have them (FIRST: the first piece with a
  // hit holds the job's record), its cycles after the previous job's, and which records make contacts (FIRST: only
  // the first hit of a direction, over its jobs) and where they go in their pair's contacts.
  out.resize(pairs.size());
  for (PairResult& r : out) r.hits = 0, r.lookups = 0, r.cycles = 0;
  contact_count_.assign(pairs.size(), 0);
  JobSpan prev;
  bool found = false;  // FIRST: the current direction has its hit
  size_t kept_total = 0;
  for (size_t j = 0; j < js.size(); ++j) {
    const JobSource& src = sources_[j];
    if (j == 0 || src.pair != sources_[j - 1].pair || src.a_in_b != sources_[j - 1].a_in_b) found = false;
    PairResult& res = out[src.pair];
    uint32_t hits = 0;
    JobHits sum;
    sum.first_group = sum.last_group = job_groups(cfg, js[j]);
    for (size_t i = job_first_piece_[j]; i < job_first_piece_[j + 1]; ++i) {
      Piece& p = pieces_[i];
      p.kept = 0;
      if (first_only) {
        if (hits == 0 && p.records) {
          hits = 1;
          sum = p.sum;
          p.kept = found ? 0 : 1;
        }
      } else {
        hits += p.count;
        if (cycles) sum = join_job_hits(sum, p.sum);
        p.kept = p.records;
      }
      p.at = contact_count_[src.pair];
      contact_count_[src.pair] += p.kept;
      kept_total += p.kept;
    }
    if (first_only) {
      if (!found && hits) ++res.hits, found = true;
    } else {
      res.hits += hits;
    }
    res.lookups += js[j].shell_count;
    if (cycles) {
      const BankCycles bank = cfg.banked() ? device_->bank_cycles(js[j], sum, hits) : BankCycles{};
      const JobSpan span = job_span(cfg, js[j], j, sum, hits, bank);
      res.cycles += span_cycles(cfg, j ? &prev : nullptr, span);
      prev = span;
    }
  }
  rot_a_.resize(pairs.size());
  rot_b_.resize(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    out[i].contacts.resize(contact_count_[i]);
    if (contact_count_[i] == 0) continue;
    rot_a_[i] = pairs[i].pose_a.rotation.toRotationMatrix();
    rot_b_[i] = pairs[i].pose_b.rotation.toRotationMatrix();
  }
  // The contacts, each task's from the records it made (on the pool when they are many).
  auto contacts = [&](size_t t) {
    const std::vector<Record>& hits = piece_hits_[t].value;
    for (size_t i = task_first_piece_[t]; i < task_first_piece_[t + 1]; ++i) {
      const Piece& p = pieces_[i];
      if (!p.kept) continue;
      const JobSource& src = sources_[p.job];
      make_contacts(pairs[src.pair], src.pair, src, hits.data() + p.first, p.kept, rot_a_[src.pair], rot_b_[src.pair],
                    out[src.pair].contacts.data() + p.at);
    }
  };
  if (kept_total >= kParallelContacts) {
    pool_->parallel_for(tasks, contacts);
  } else {
    for (size_t t = 0; t < tasks; ++t) contacts(t);
  }
}

size_t PairCollider::tally(const PairRequest* pairs, size_t p0, size_t p1, const PairOptions& opt, const Job* js,
                           const JobSource* sources, size_t njobs, const size_t* first_job,
                           Part::JobRecords* job_records, const Record* records, size_t nrec, PairResult* out,
                           Eigen::Matrix3d* rot_a, Eigen::Matrix3d* rot_b) const {
  const bool first_only = opt.mode == Mode::First;
  size_t kept_total = 0;
  for (size_t i = p0; i < p1; ++i) {
    PairResult& res = out[i];
    res.hits = 0, res.lookups = 0, res.cycles = 0;
    size_t count = 0;
    bool found = false;  // FIRST: the current direction has its hit
    for (size_t j = first_job[i]; j < first_job[i + 1]; ++j) {
      const JobSource& src = sources[j];
      if (j == first_job[i] || src.a_in_b != sources[j - 1].a_in_b) found = false;
      Part::JobRecords& jr = job_records[j];
      const size_t end = j + 1 < njobs ? job_records[j + 1].first - 1 : nrec - 1;  // its completion record
      const Record& done = records[end];
      jr.kept = first_only && found ? 0 : end - jr.first;
      jr.at = count;
      count += jr.kept;
      if (first_only) {
        if (!found && done.hits) ++res.hits, found = true;
      } else {
        res.hits += done.hits;
      }
      res.lookups += js[j].shell_count;
      if (done.cycles) res.cycles += *done.cycles;
    }
    res.contacts.resize(count);
    kept_total += count;
    if (count == 0) continue;
    rot_a[i] = pairs[i].pose_a.rotation.toRotationMatrix();
    rot_b[i] = pairs[i].pose_b.rotation.toRotationMatrix();
  }
  return kept_total;
}

void PairCollider::collide_part(const PairRequest* pairs, size_t n, size_t base, const PairOptions& opt,
                                PairResult* out, Part& part) const {
  // The part's jobs (tags: their index in the part), run on this thread, timed as a stream of their own.
  part.jobs.clear();
  part.sources.clear();
  for (size_t i = 0; i < n; ++i) {
    const size_t first = part.jobs.size();
    pair_jobs(base + i, pairs[i], opt, part.jobs, part.sources, part.bits);
    for (size_t j = first; j < part.jobs.size(); ++j) part.sources[j].pair = uint32_t(i);
  }
  const std::vector<Job>& js = part.jobs;
  device_->run_part(js.data(), js.size(), part.records);
  const DeviceConfig& cfg = device_->config();
  const size_t nrec = part.records.size();
  part.job_records.resize(js.size());
  for (size_t r = 0, j = 0, first = 0; r < nrec; ++r)
    if (part.records[r].kind == Record::Done) part.job_records[j++].first = first, first = r + 1;
  // The cycles of the timing model (annotate_cycles' of the part as a stream of its own), and the spans of its first
  // and last jobs for join_parts.
  part.any = !js.empty() && device_->models_cycles();
  if (part.any) {
    JobSpan prev;
    for (size_t j = 0; j < js.size(); ++j) {
      const Part::JobRecords& jr = part.job_records[j];
      const size_t end = j + 1 < js.size() ? part.job_records[j + 1].first - 1 : nrec - 1;
      Record& done = part.records[end];
      const JobHits h = job_hits(cfg, js[j], j, part.records.data() + jr.first, end - jr.first, jr.first);
      const BankCycles bank = cfg.banked() ? device_->bank_cycles(js[j], h, done.hits) : BankCycles{};
      const JobSpan span = job_span(cfg, js[j], j, h, done.hits, bank);
      done.cycles = span_cycles(cfg, j ? &prev : nullptr, span);
      done.points = span.points;
      done.stalls = 0;
      if (j == 0) part.first = span;
      prev = span;
    }
    part.last = prev;
  }
  part.first_job.resize(n + 1);
  for (size_t i = 0, j = 0; i <= n; ++i) {
    while (j < js.size() && part.sources[j].pair < i) ++j;
    part.first_job[i] = j;
  }
  part.rot_a.resize(n);
  part.rot_b.resize(n);
  tally(pairs, 0, n, opt, js.data(), part.sources.data(), js.size(), part.first_job.data(), part.job_records.data(),
        part.records.data(), nrec, out, part.rot_a.data(), part.rot_b.data());
  for (size_t j = 0; j < js.size(); ++j) {
    const Part::JobRecords& jr = part.job_records[j];
    if (!jr.kept) continue;
    const size_t i = part.sources[j].pair;
    JobSource src = part.sources[j];
    src.pair = uint32_t(base + i);
    make_contacts(pairs[i], uint32_t(base + i), src, part.records.data() + jr.first, jr.kept, part.rot_a[i],
                  part.rot_b[i], out[i].contacts.data() + jr.at);
  }
  if (part.any) part.first_result = out + part.sources[0].pair;
}

void PairCollider::join_parts(Part* const* parts, size_t n) const {
  const DeviceConfig& cfg = device_->config();
  const Part* prev = nullptr;
  for (size_t p = 0; p < n; ++p) {
    const Part& part = *parts[p];
    if (!part.any) continue;
    // Its first job's cycles: after the previous part's last job, not after the stream's start.
    if (prev) part.first_result->cycles += span_cycles(cfg, &prev->last, part.first) - span_cycles(cfg, nullptr, part.first);
    prev = &part;
  }
}

void PairCollider::make_contacts(const PairRequest& req, uint32_t pair, const JobSource& src, const Record* recs,
                                 size_t n, const Eigen::Matrix3d& Ra, const Eigen::Matrix3d& Rb, Contact* to) const {
  // The depth lookups land all over B's depth field (4 bytes per voxel, often larger than the cache), so the loop
  // prefetches the depth of the hit a few records ahead.
  constexpr size_t kAhead = 16;
  const bool a_in_b = src.a_in_b;
  const ObjectType& shell_t = *types_[a_in_b ? req.a : req.b];
  const ObjectType& map_t = *types_[a_in_b ? req.b : req.a];
  const RigidPose& pose = a_in_b ? req.pose_a : req.pose_b;
  const Eigen::Matrix3d& R = a_in_b ? Ra : Rb;
  const auto& points = shell_t.shell().points;
  const auto& normals = shell_t.shell().normals;
  const Voxmap& vm = map_t.voxmap();
  const float* depth = map_t.depth.data();
  const size_t nvox = map_t.depth.size();
  const double voxel = vm.voxel();
  const bool distance = device_->config().distance();
  const DistanceField& field = map_t.object.distance;
  const double dist_unit = distance ? voxel * field.step / std::ldexp(1.0, 3 * device_->config().WB) : 0.0;
  const RigidPose& map_pose = a_in_b ? req.pose_b : req.pose_a;
  const Eigen::Matrix3d& Rm = a_in_b ? Rb : Ra;
  for (size_t k = 0; k < n; ++k) {
    if (k + kAhead < n) {
      const Record& ahead = recs[k + kAhead];
      const uint64_t i = vm.index(ahead.x, ahead.y, ahead.z);
      if (i < nvox) __builtin_prefetch(depth + i);
    }
    const Record& rec = recs[k];
    const uint32_t point = rec.point + src.first;
    Contact& c = to[k];
    c.pair = pair;
    c.a_in_b = a_in_b;
    c.point = point;
    c.position = R * points[point] + pose.translation;
    c.normal = R * normals[point];
    c.voxel = {rec.x, rec.y, rec.z};
    c.state = rec.state;
    if (distance) {
      c.depth = -double(rec.dist) * dist_unit;
      // The field's gradient at the point, in the map's grid, to the world; negated, it points the way the
      // shell object's outward normal does at a contact.
      const Eigen::Vector3d g = (Rm.transpose() * (c.position - map_pose.translation) - vm.origin()) / voxel;
      Eigen::Vector3d grad;
      field.sample(g, &grad);
      const Eigen::Vector3d nrm = -(Rm * grad);
      if (nrm.squaredNorm() > 1e-24) c.normal = nrm.normalized();
    } else {
      c.depth = double(depth[vm.index(rec.x, rec.y, rec.z)]) * voxel;
    }
  }
}

}  // namespace voxcd
