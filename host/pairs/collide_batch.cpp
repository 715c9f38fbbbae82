// PairCollider's batches: the jobs of a batch run on the device (as one stream, or in pieces on the pool), what
// they found tallied per pair, and their contacts written into PairResults or ContactArrays; the parts of a batch
// that a caller runs on its own threads (collide_part, join_parts).
#include <algorithm>

#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/pairs/detail/contact_out.h"
#include "voxcd/ref/banks.h"
#include "voxcd/ref/fast/thread_pool.h"
#include "voxcd/ref/timing.h"

namespace voxcd {

std::vector<PairResult> PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt) {
  std::vector<PairResult> out;
  collide(pairs, opt, out);
  return out;
}

void PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt,
                           std::vector<PairResult>& out) {
  run_batch(pairs, opt);
  // A contacts vector that holds more already only shrinks: no contact is constructed twice.
  out.resize(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    const PairTally& t = tally_[i];
    out[i].hits = t.hits, out[i].lookups = t.lookups, out[i].cycles = t.cycles;
    out[i].contacts.resize(t.contacts);
  }
  write_contacts(pairs, [&](uint32_t pair) { return detail::ToContacts{out[pair].contacts.data()}; });
}

void PairCollider::collide(const std::vector<PairRequest>& pairs, const PairOptions& opt, ContactArrays& out) {
  run_batch(pairs, opt);
  out.resize(pairs.size(), kept_total_);
  uint64_t row = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    const PairTally& t = tally_[i];
    out.first[i] = row;
    out.hits[i] = t.hits, out.lookups[i] = t.lookups, out.cycles[i] = t.cycles;
    row += t.contacts;
  }
  out.first[pairs.size()] = row;
  write_contacts(pairs, [&](uint32_t pair) { return detail::ToArrays{&out, size_t(out.first[pair])}; });
}

template <class Out>
void PairCollider::write_contacts(const std::vector<PairRequest>& pairs, const Out& out) {
  auto write = [&](const ContactRun& r) {
    const JobSource& src = sources_[r.job];
    make_contacts(pairs[src.pair], src.pair, src, r.recs, r.n, rot_a_[src.pair], rot_b_[src.pair],
                  out(src.pair).shifted(r.at));
  };
  if (!pool_ || kept_total_ < kParallelContacts) {
    for (const ContactRun& r : runs_) write(r);
    return;
  }
  pool_->parallel_for(runs_.size(), [&](size_t i) { write(runs_[i]); });
}

void PairCollider::run_batch(const std::vector<PairRequest>& pairs, const PairOptions& opt) {
  jobs(pairs, opt, jobs_, sources_);
  if (pool_ && device_->runs_parts()) {
    size_t points = 0;
    for (const Job& j : jobs_) points += j.shell_count;
    if (points >= kParallelPoints) return run_pieces(pairs, opt);
  }
  run_stream(pairs, opt);
}

void PairCollider::run_stream(const std::vector<PairRequest>& pairs, const PairOptions& opt) {
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
  // records make contacts (FIRST: only the first hit of a direction, over its jobs), the pair's hits, lookups,
  // cycles and contacts and, for a pair with contacts, the pose of its objects as matrices.
  tally_.resize(pairs.size());
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
                                    job_records_.data(), records_.data(), nrec, tally_.data(), rot_a_.data(),
                                    rot_b_.data());
  });
  kept_total_ = 0;
  for (size_t p = 0; p < parts.parts; ++p) kept_total_ += kept_parts_[p].value;
  // The runs of records that make contacts, in pieces of up to kContactPiece records for the pool.
  runs_.clear();
  for (size_t j = 0; j < js.size(); ++j) {
    const Part::JobRecords& jr = job_records_[j];
    for (size_t k = 0; k < jr.kept; k += kContactPiece)
      runs_.push_back({records_.data() + jr.first + k, std::min(kContactPiece, jr.kept - k), j, jr.at + k});
  }
}

void PairCollider::run_pieces(const std::vector<PairRequest>& pairs, const PairOptions& opt) {
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
  tally_.assign(pairs.size(), PairTally());
  JobSpan prev;
  bool found = false;  // FIRST: the current direction has its hit
  size_t kept_total = 0;
  for (size_t j = 0; j < js.size(); ++j) {
    const JobSource& src = sources_[j];
    if (j == 0 || src.pair != sources_[j - 1].pair || src.a_in_b != sources_[j - 1].a_in_b) found = false;
    PairTally& res = tally_[src.pair];
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
      p.at = res.contacts;
      res.contacts += p.kept;
      kept_total += p.kept;
    }
    if (first_only) {
      if (!found && hits) ++res.hits, found = true;
    } else {
      res.hits += hits;
    }
    res.lookups += js[j].shell_count;
    if (cycles) {
      const uint64_t conflicts =
          cfg.banked() ? device_->bank_conflicts(js[j], read_groups(cfg, js[j], sum, hits)) : 0;
      const JobSpan span = job_span(cfg, js[j], j, sum, hits, conflicts);
      res.cycles += span_cycles(cfg, j ? &prev : nullptr, span);
      prev = span;
    }
  }
  rot_a_.resize(pairs.size());
  rot_b_.resize(pairs.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (tally_[i].contacts == 0) continue;
    rot_a_[i] = pairs[i].pose_a.rotation.toRotationMatrix();
    rot_b_[i] = pairs[i].pose_b.rotation.toRotationMatrix();
  }
  kept_total_ = kept_total;
  // The runs of records that make contacts: each piece's, where its task put them.
  runs_.clear();
  for (const Piece& p : pieces_)
    if (p.kept) runs_.push_back({piece_hits_[p.task].value.data() + p.first, p.kept, p.job, p.at});
}

size_t PairCollider::tally(const PairRequest* pairs, size_t p0, size_t p1, const PairOptions& opt, const Job* js,
                           const JobSource* sources, size_t njobs, const size_t* first_job,
                           Part::JobRecords* job_records, const Record* records, size_t nrec, PairTally* out,
                           Eigen::Matrix3d* rot_a, Eigen::Matrix3d* rot_b) const {
  const bool first_only = opt.mode == Mode::First;
  size_t kept_total = 0;
  for (size_t i = p0; i < p1; ++i) {
    PairTally& res = out[i];
    res = PairTally();
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
    res.contacts = count;
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
      const uint64_t conflicts =
          cfg.banked() ? device_->bank_conflicts(js[j], read_groups(cfg, js[j], h, done.hits)) : 0;
      const JobSpan span = job_span(cfg, js[j], j, h, done.hits, conflicts);
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
  part.tally.resize(n);
  tally(pairs, 0, n, opt, js.data(), part.sources.data(), js.size(), part.first_job.data(), part.job_records.data(),
        part.records.data(), nrec, part.tally.data(), part.rot_a.data(), part.rot_b.data());
  for (size_t i = 0; i < n; ++i) {
    const PairTally& t = part.tally[i];
    out[i].hits = t.hits, out[i].lookups = t.lookups, out[i].cycles = t.cycles;
    out[i].contacts.resize(t.contacts);
  }
  for (size_t j = 0; j < js.size(); ++j) {
    const Part::JobRecords& jr = part.job_records[j];
    if (!jr.kept) continue;
    const size_t i = part.sources[j].pair;
    JobSource src = part.sources[j];
    src.pair = uint32_t(base + i);
    make_contacts(pairs[i], uint32_t(base + i), src, part.records.data() + jr.first, jr.kept, part.rot_a[i],
                  part.rot_b[i], detail::ToContacts{out[i].contacts.data() + jr.at});
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

}  // namespace voxcd
