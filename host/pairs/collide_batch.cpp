// PairCollider's batches: the jobs of a batch run on the device (as one stream, or in pieces on the pool), what
// they found tallied per pair, which hit records make contacts and where each goes (ascending point order per
// direction: the device holds shells in blocks, detail/shell_order.h), and the contacts written into PairResults or
// ContactArrays; the parts of a batch that a caller runs on its own threads (collide_part, join_parts).
#include <algorithm>

#include "voxcd/host/pairs/collider.h"
#include "voxcd/host/pairs/detail/contact_out.h"
#include "voxcd/host/pairs/detail/shell_order.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/util/thread_pool.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

// Per part of a tally: its directions' hit records that make contacts in contact order (`sorted`), and where each
// direction's run of them is and goes.
struct PairCollider::Scratch {
  struct Run {
    size_t off, n;  // sorted[off, off + n)
    uint32_t pair;
    bool a_in_b;
    size_t at;      // the first one's place in the pair's contacts
  };
  detail::RankBits ranks;
  std::vector<detail::HitSpan> spans;
  std::vector<detail::SortedHit> sorted;
  std::vector<Run> runs;
  void clear() { sorted.clear(), runs.clear(); }
  // One direction of `pair` (its spans in `spans`): its kept records into `sorted`, a run for them; the kept.
  size_t keep(uint32_t pair, bool a_in_b, size_t at, bool first_only, const std::vector<uint32_t>& order) {
    size_t total = 0;
    for (const detail::HitSpan& h : spans) total += h.n;
    const size_t off = sorted.size();
    sorted.resize(off + total);
    const size_t kept = detail::keep_direction(spans.data(), spans.size(), first_only, order.data(), order.size(),
                                               sorted.data() + off, ranks);
    sorted.resize(off + kept);
    if (kept) runs.push_back({off, kept, pair, a_in_b, at});
    return kept;
  }
  // Its runs (of hits held in `cols`) as ContactRuns of at most `piece` contacts each, appended to `out`.
  void runs_into(std::vector<ContactRun>& out, size_t piece, const HitColumns* cols) const {
    for (const Run& r : runs)
      for (size_t k = 0; k < r.n; k += piece)
        out.push_back({cols, sorted.data() + r.off + k, std::min(piece, r.n - k), r.pair, r.a_in_b, r.at + k});
  }
};

std::vector<PairResult> PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt) {
  std::vector<PairResult> out;
  collide(pairs, opt, out);
  return out;
}

void PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt,
                           std::vector<PairResult>& out) {
  run_groups(pairs, opt, [&](size_t p0, size_t p1) {
    // A contacts vector that holds more already only shrinks: no contact is constructed twice.
    if (p0 == 0) out.resize(pairs.size());
    for (size_t i = p0; i < p1; ++i) {
      const PairTally& t = tally_[i];
      out[i].hits = t.hits, out[i].lookups = t.lookups, out[i].device_cycles = t.cycles;
      out[i].contacts.resize(t.contacts);
    }
    write_contacts(pairs, opt, [&](uint32_t pair) { return detail::ToContacts{out[pair].contacts.data()}; });
  });
  if (pairs.empty()) out.clear();
}

void PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt, ContactArrays& out) {
  uint64_t row = 0;
  run_groups(pairs, opt, [&](size_t p0, size_t p1) {
    // Grown, never shrunk, until the last group: the rows of the last batch are overwritten, not made anew.
    if (p0 == 0 || out.size() < row + kept_total_)
      out.resize(pairs.size(), std::max<size_t>(out.size(), size_t(row + kept_total_)));
    for (size_t i = p0; i < p1; ++i) {
      const PairTally& t = tally_[i];
      out.first[i] = row;
      out.hits[i] = t.hits, out.lookups[i] = t.lookups, out.device_cycles[i] = t.cycles;
      row += t.contacts;
    }
    out.first[p1] = row;
    write_contacts(pairs, opt, [&](uint32_t pair) { return detail::ToArrays(out, size_t(out.first[pair])); });
  });
  out.resize(pairs.size(), size_t(row));
  if (pairs.empty()) out.first[0] = 0;
}

template <class Emit>
void PairCollider::run_groups(const std::vector<PairRequest>& pairs, const PairOptions& opt, const Emit& emit) {
  // Every job first (a bad pose is refused before anything is run or written), then the batch in groups of
  // consecutive pairs of about kGroupPoints points: each group's hit records and contacts are made while they are
  // in the cache (one stream of a whole large batch would not be), and its contacts written before the next runs.
  jobs(pairs, opt, all_jobs_, all_sources_);
  tally_.resize(pairs.size());
  rot_a_.resize(pairs.size());
  rot_b_.resize(pairs.size());
  const bool cycles = device_->models_cycles();
  JobSpan last;
  bool after = false;  // a group ran before this one: its last job's span is `last`
  for (size_t p0 = 0, j0 = 0; p0 < pairs.size();) {
    size_t p1 = p0, j1 = j0, points = 0;
    while (p1 < pairs.size()) {
      size_t jk = j1, more = 0;
      for (; jk < all_jobs_.size() && all_sources_[jk].pair == p1; ++jk) more += all_sources_[jk].points;
      if (p1 > p0 && points + more > kGroupPoints) break;
      points += more, j1 = jk, ++p1;
    }
    jobs_.assign(all_jobs_.begin() + std::ptrdiff_t(j0), all_jobs_.begin() + std::ptrdiff_t(j1));
    sources_.assign(all_sources_.begin() + std::ptrdiff_t(j0), all_sources_.begin() + std::ptrdiff_t(j1));
    if (pool_ && parts_ && points >= kParallelPoints) run_pieces(pairs, p0, p1, opt);
    else run_stream(pairs, p0, p1, opt);
    if (cycles && !jobs_.empty()) {
      // The group's first job was timed as the start of a stream; it follows the previous group's last job.
      if (after) tally_[sources_[0].pair].cycles += span_cycles(device_->config(), &last, first_span_) -
                                                     span_cycles(device_->config(), nullptr, first_span_);
      last = last_span_, after = true;
    }
    emit(p0, p1);
    p0 = p1, j0 = j1;
  }
}

template <class Out>
void PairCollider::write_contacts(const std::vector<PairRequest>& pairs, const PairOptions& opt, const Out& out) {
  auto write = [&](const ContactRun& r) {
    make_contacts(pairs[r.pair], r.pair, r.a_in_b, *r.cols, r.hits, r.n, rot_a_[r.pair], rot_b_[r.pair], opt,
                  out(r.pair).shifted(r.at));
  };
  if (!pool_ || kept_total_ < kParallelContacts) {
    for (const ContactRun& r : runs_) write(r);
    return;
  }
  pool_->parallel_for(runs_.size(), [&](size_t i) { write(runs_[i]); });
}

PairCollider::Scratch& PairCollider::scratch(std::shared_ptr<Scratch>& s) {
  if (!s) s = std::make_shared<Scratch>();
  return *s;
}

void PairCollider::run_records(const std::vector<Job>& js) {
  // The stream is checked whole before the caller's results are touched, so a misbehaving device leaves them as
  // they were: a completion record per job, the last record one of them.
  device_->run_into(js, records_);
  const DeviceConfig& cfg = device_->config();
  const bool cycles = device_->models_cycles();
  hits_.clear();
  outcomes_.resize(js.size());
  size_t job = 0, first = 0;
  for (size_t r = 0; r < records_.size(); ++r) {
    const Record& rec = records_[r];
    if (rec.kind != Record::Done) {
      hits_.append(rec);
      continue;
    }
    if (job == js.size())
      throw DeviceError("the device returned records after the completions of all " + std::to_string(js.size()) +
                        " jobs");
    JobOutcome& o = outcomes_[job];
    o.first = hits_.size() - (r - first);
    o.records = r - first;
    o.hits = rec.hits;
    o.cycles = rec.cycles.value_or(0);
    if (cycles) {
      const JobSlots slots = slots_of(js[job]);
      const JobHits h = job_hits(slots, js[job], job, records_.data() + first, r - first, first);
      // A banked device's conflicts from the shell the device holds (the image's), as ref/banks.h counts them.
      o.span = job_span(cfg, js[job], slots, job, h, rec.hits,
                        cfg.banked() ? job_bank_cycles(cfg, image_.memory().shell, image_.memory().map, js[job], h, rec.hits)
                                     : BankCycles{});
    }
    ++job, first = r + 1;
  }
  if (job != js.size() || first != records_.size())
    throw DeviceError(job != js.size() ? "the device returned fewer completions than the " + std::to_string(js.size()) +
                                             " jobs it was given"
                                       : "the device returned records after the completions of all " +
                                             std::to_string(js.size()) + " jobs");
}

void PairCollider::run_stream(const std::vector<PairRequest>& pairs, size_t p0, size_t p1, const PairOptions& opt) {
  // A device that runs parts hands its hits over in columns, each job's cycles with them; another gives a stream of
  // records.
  const std::vector<Job>& js = jobs_;
  if (parts_) parts_->run_part(js.data(), js.size(), hits_, outcomes_);
  else run_records(js);
  // Pair by pair (on the pool in ranges of pairs when they are many; a pair's jobs are consecutive): which hits make
  // contacts and where they go, the pair's hits, lookups, cycles and contacts and, for a pair with contacts, the
  // pose of its objects as matrices.
  first_job_.resize(pairs.size() + 1);  // pair i's jobs: [first_job_[i], first_job_[i + 1])
  for (size_t i = p0, j = 0; i <= p1; ++i) {
    while (j < js.size() && sources_[j].pair < i) ++j;
    first_job_[i] = j;
  }
  const Ranges parts = pool_ranges(pool_.get(), p1 - p0, kParallelPairs);
  if (kept_parts_.size() < parts.parts) kept_parts_.resize(parts.parts);
  if (scratch_.size() < parts.parts) scratch_.resize(parts.parts);
  for_ranges(pool_.get(), parts, [&](size_t part, size_t q0, size_t q1) {
    kept_parts_[part].value = tally(pairs.data(), p0 + q0, p0 + q1, opt, sources_.data(),
                                    first_job_.data(), outcomes_.data(), hits_, tally_.data(), rot_a_.data(),
                                    rot_b_.data(), scratch(scratch_[part]));
  });
  kept_total_ = 0;
  for (size_t p = 0; p < parts.parts; ++p) kept_total_ += kept_parts_[p].value;
  // The runs of hits that make contacts, in pieces of up to kContactPiece hits for the pool.
  runs_.clear();
  for (size_t p = 0; p < parts.parts; ++p) scratch_[p]->runs_into(runs_, kContactPiece, &hits_);
  if (device_->models_cycles() && !js.empty()) first_span_ = outcomes_.front().span, last_span_ = outcomes_.back().span;
}

JobSlots PairCollider::slots_of(const Job& j) const {
  return job_slots(device_->config(), image_.memory().shell, j);
}

void PairCollider::plan_pieces() {
  // Pieces of at most kPiecePoints points; tasks: runs of consecutive pieces of at least kTaskPoints points.
  const std::vector<Job>& js = jobs_;
  pieces_.clear();
  job_first_piece_.resize(js.size() + 1);
  for (size_t j = 0; j < js.size(); ++j) {
    job_first_piece_[j] = pieces_.size();
    const uint32_t points = sources_[j].points;
    for (uint32_t b = 0; b < points; b += uint32_t(kPiecePoints)) {
      Piece& p = pieces_.emplace_back();
      p.job = j;
      p.begin = b;
      p.end = uint32_t(std::min<size_t>(points, b + kPiecePoints));
    }
  }
  job_first_piece_[js.size()] = pieces_.size();
  task_first_piece_.clear();
  for (size_t i = 0, acc = kTaskPoints; i < pieces_.size(); ++i) {
    if (acc >= kTaskPoints) task_first_piece_.push_back(i), acc = 0;
    acc += pieces_[i].end - pieces_[i].begin;
  }
  task_first_piece_.push_back(pieces_.size());
}

void PairCollider::run_pieces(const std::vector<PairRequest>& pairs, size_t p0, size_t p1, const PairOptions& opt) {
  const std::vector<Job>& js = jobs_;
  const DeviceConfig& cfg = device_->config();
  const bool cycles = device_->models_cycles();
  plan_pieces();
  if (cycles) {
    piece_slots_.resize(js.size());
    for (size_t j = 0; j < js.size(); ++j) piece_slots_[j] = slots_of(js[j]);
  }
  const size_t tasks = task_first_piece_.size() - 1;
  if (piece_hits_.size() < tasks) piece_hits_.resize(tasks);
  // The lookups. A task validates a job before its first piece of it, so the lowest task that throws names the first
  // invalid job (the error run_into gives); nothing of the caller's is touched before every task has finished.
  pool_->parallel_for(tasks, [&](size_t t) {
    HitColumns& hits = piece_hits_[t].value;
    hits.clear();
    size_t validated = SIZE_MAX;
    for (size_t i = task_first_piece_[t]; i < task_first_piece_[t + 1]; ++i) {
      Piece& p = pieces_[i];
      const Job& j = js[p.job];
      p.task = t;
      p.first = hits.size();
      p.count = 0;
      parts_->run_piece(j, p.begin, p.end, validated != p.job, hits, p.count);
      validated = p.job;
      p.records = hits.size() - p.first;
      if (cycles) p.sum = job_hits(piece_slots_[p.job], hits.point.data() + p.first, p.records);
    }
  });
  // Job by job, in order: its hits and summary as the device's stream would have them (FIRST: the first piece with a
  // hit holds the job's record), its cycles after the previous job's.
  std::fill(tally_.begin() + std::ptrdiff_t(p0), tally_.begin() + std::ptrdiff_t(p1), PairTally());
  JobSpan prev;
  for (size_t j = 0; j < js.size(); ++j) {
    PairTally& res = tally_[sources_[j].pair];
    uint32_t hits = 0;
    JobHits sum;
    sum.first_group = sum.last_group = cycles ? piece_slots_[j].groups : 0;
    for (size_t i = job_first_piece_[j]; i < job_first_piece_[j + 1]; ++i) {
      const Piece& p = pieces_[i];
      if (opt.mode != Mode::First) {
        hits += p.count;
        if (cycles) sum = join_job_hits(sum, p.sum);
      } else if (hits == 0 && p.records) {
        hits = 1, sum = p.sum;
      }
    }
    res.hits += hits;  // FIRST: made 0 or 1 per direction below
    res.lookups += sources_[j].points;
    if (cycles) {
      const BankCycles bank = cfg.banked() ? parts_->bank_cycles(js[j], sum, hits) : BankCycles{};
      const JobSpan span = job_span(cfg, js[j], piece_slots_[j], j, sum, hits, bank);
      res.cycles += span_cycles(cfg, j ? &prev : nullptr, span);
      if (j == 0) first_span_ = span;
      prev = span;
    }
  }
  last_span_ = prev;
  keep_pieces(pairs, p0, p1, opt);
}

void PairCollider::keep_pieces(const std::vector<PairRequest>& pairs, size_t p0, size_t p1,
                               const PairOptions& opt) {
  // The pieces' hits into hits_ in stream order (FIRST: each job's first piece with a hit only); direction by
  // direction, which of them make contacts, in contact order; then the runs of those hits.
  const bool first_only = opt.mode == Mode::First;
  hits_.clear();
  for (size_t j = 0; j < jobs_.size(); ++j) {
    bool found = false;
    for (size_t i = job_first_piece_[j]; i < job_first_piece_[j + 1]; ++i) {
      Piece& p = pieces_[i];
      if (first_only && (found || p.records == 0)) p.records = 0;
      else found = p.records > 0;
      p.at = hits_.size();
      hits_.append(piece_hits_[p.task].value, p.first, p.records);
    }
  }
  if (scratch_.empty()) scratch_.resize(1);
  Scratch& sc = scratch(scratch_[0]);
  sc.clear();
  kept_total_ = 0;
  for (size_t j0 = 0, j1 = 0; j0 < jobs_.size(); j0 = j1) {
    const JobSource& src = sources_[j0];
    while (j1 < jobs_.size() && sources_[j1].pair == src.pair && sources_[j1].a_in_b == src.a_in_b) ++j1;
    sc.spans.clear();
    for (size_t i = job_first_piece_[j0]; i < job_first_piece_[j1]; ++i) {
      const Piece& p = pieces_[i];
      sc.spans.push_back({hits_.point.data() + p.at, p.records, sources_[p.job].first, p.at});
    }
    PairTally& res = tally_[src.pair];
    const uint32_t shell_type = src.a_in_b ? pairs[src.pair].a : pairs[src.pair].b;
    const size_t kept = sc.keep(src.pair, src.a_in_b, res.contacts, first_only, order_[shell_type]);
    res.contacts += kept;
    kept_total_ += kept;
  }
  if (first_only) {
    // FIRST: a direction counts one hit when any of its jobs had one.
    for (size_t i = p0; i < p1; ++i) tally_[i].hits = 0;
    for (size_t j0 = 0, j1 = 0; j0 < jobs_.size(); j0 = j1) {
      const JobSource& src = sources_[j0];
      bool any = false;
      for (; j1 < jobs_.size() && sources_[j1].pair == src.pair && sources_[j1].a_in_b == src.a_in_b; ++j1)
        for (size_t i = job_first_piece_[j1]; i < job_first_piece_[j1 + 1]; ++i) any |= pieces_[i].records > 0;
      tally_[src.pair].hits += any;
    }
  }
  for (size_t i = p0; i < p1; ++i) {
    if (tally_[i].contacts == 0) continue;
    rot_a_[i] = pairs[i].pose_a.rotation.toRotationMatrix();
    rot_b_[i] = pairs[i].pose_b.rotation.toRotationMatrix();
  }
  runs_.clear();
  sc.runs_into(runs_, kContactPiece, &hits_);
}

size_t PairCollider::tally(const PairRequest* pairs, size_t p0, size_t p1, const PairOptions& opt,
                           const JobSource* sources, const size_t* first_job, const JobOutcome* outs,
                           const HitColumns& hits, PairTally* out, Eigen::Matrix3d* rot_a, Eigen::Matrix3d* rot_b,
                           Scratch& sc) const {
  const bool first_only = opt.mode == Mode::First;
  size_t kept_total = 0;
  sc.clear();
  for (size_t i = p0; i < p1; ++i) {
    PairTally& res = out[i];
    res = PairTally();
    // Direction by direction (its jobs [j0, j1)): every job's hits one span.
    for (size_t j0 = first_job[i], j1 = j0; j0 < first_job[i + 1]; j0 = j1) {
      sc.spans.clear();
      bool any = false;
      for (; j1 < first_job[i + 1] && sources[j1].a_in_b == sources[j0].a_in_b; ++j1) {
        const JobOutcome& o = outs[j1];
        sc.spans.push_back({hits.point.data() + o.first, o.records, sources[j1].first, o.first});
        any |= o.hits > 0;
        if (!first_only) res.hits += o.hits;
        res.lookups += sources[j1].points;
        res.cycles += o.cycles;
      }
      if (first_only) res.hits += any;
      const uint32_t shell_type = sources[j0].a_in_b ? pairs[i].a : pairs[i].b;
      res.contacts += sc.keep(uint32_t(i), sources[j0].a_in_b, res.contacts, first_only, order_[shell_type]);
    }
    kept_total += res.contacts;
    if (res.contacts == 0) continue;
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
  if (!parts_) throw DeviceError("the " + device_->name() + " backend runs whole batches only (no parts)");
  parts_->run_part(js.data(), js.size(), part.hits, part.outcomes);
  part.any = !js.empty() && device_->models_cycles();
  if (part.any) part.first = part.outcomes.front().span, part.last = part.outcomes.back().span;
  part.first_job.resize(n + 1);
  for (size_t i = 0, j = 0; i <= n; ++i) {
    while (j < js.size() && part.sources[j].pair < i) ++j;
    part.first_job[i] = j;
  }
  part.rot_a.resize(n);
  part.rot_b.resize(n);
  part.tally.resize(n);
  Scratch& sc = scratch(part.scratch);
  tally(pairs, 0, n, opt, part.sources.data(), part.first_job.data(), part.outcomes.data(), part.hits,
        part.tally.data(), part.rot_a.data(), part.rot_b.data(), sc);
  for (size_t i = 0; i < n; ++i) {
    const PairTally& t = part.tally[i];
    out[i].hits = t.hits, out[i].lookups = t.lookups, out[i].device_cycles = t.cycles;
    out[i].contacts.resize(t.contacts);
  }
  for (const Scratch::Run& r : sc.runs)
    make_contacts(pairs[r.pair], uint32_t(base + r.pair), r.a_in_b, part.hits, sc.sorted.data() + r.off, r.n,
                  part.rot_a[r.pair], part.rot_b[r.pair], opt, detail::ToContacts{out[r.pair].contacts.data() + r.at});
  if (part.any) part.first_result = out + part.sources[0].pair;
}

void PairCollider::join_parts(Part* const* parts, size_t n) const {
  const DeviceConfig& cfg = device_->config();
  const Part* prev = nullptr;
  for (size_t p = 0; p < n; ++p) {
    const Part& part = *parts[p];
    if (!part.any) continue;
    // Its first job's cycles: after the previous part's last job, not after the stream's start.
    if (prev)
      part.first_result->device_cycles +=
          span_cycles(cfg, &prev->last, part.first) - span_cycles(cfg, nullptr, part.first);
    prev = &part;
  }
}

}  // namespace voxcd
