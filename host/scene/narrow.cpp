// A frame's pair tests: the mid-phase's requests on the device, in parts of near-equal weight when the device runs
// parts, and each tested pair's outcome (Simulation::narrow).
#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "voxcd/host/scene/scene.h"

namespace voxcd {

namespace {
// Tested pairs per part of the outcomes (about 100 ns a pair); and the parts of the pair tests: at least 4 tested
// pairs each (a microsecond or more each), up to 16 per thread, cut by weight (the shell points the pair looks up:
// their costs differ, and a thread that finishes early takes another's).
constexpr size_t kGrainPairs = 32, kGrainTests = 4, kPartsTests = 16;
}  // namespace

void Simulation::cut_tests(const PairOptions& po) {
  // The weight of a request: the shell points its jobs look up before culling (A's in B, and B's in A both ways).
  const size_t total = requests_.size();
  weight_.resize(total + 1);
  weight_[0] = 0;
  for (size_t q = 0; q < total; ++q) {
    const PairRequest& rq = requests_[q];
    size_t w = scene_.types[rq.a]->shell().size();
    if (po.both_directions) w += scene_.types[rq.b]->shell().size();
    weight_[q + 1] = weight_[q] + w + 1;
  }
  // Part p: the requests whose weight starts in [p W / P, (p + 1) W / P); parts left empty are dropped.
  const size_t parts = Ranges::of(total, kGrainTests, pool_->size(), kPartsTests).parts;
  const uint64_t w = weight_[total];
  test_first_.assign(1, 0);
  for (size_t p = 1; p < parts; ++p) {
    const uint64_t cut = w * p / parts;
    const size_t q = size_t(std::upper_bound(weight_.begin(), weight_.begin() + std::ptrdiff_t(total), cut) - weight_.begin()) - 1;
    if (q > test_first_.back()) test_first_.push_back(q);
  }
  test_first_.push_back(total);
}

void Simulation::narrow_parts(const PairOptions& po) {
  cut_tests(po);
  const size_t parts = test_first_.size() - 1;
  if (narrow_parts_.size() < parts) narrow_parts_.resize(parts);
  pool_->parallel_for(parts, [&](size_t part) {
    const size_t q0 = test_first_[part], q1 = test_first_[part + 1];
    collider_->collide_part(requests_.data() + q0, q1 - q0, q0, po, results_.data() + q0, narrow_parts_[part].value);
    for (size_t q = q0; q < q1; ++q) outcome(q);
  });
  part_ptrs_.clear();
  for (size_t p = 0; p < parts; ++p) part_ptrs_.push_back(&narrow_parts_[p].value);
  collider_->join_parts(part_ptrs_.data(), part_ptrs_.size());
  for (const PairCollider::Part* p : part_ptrs_)
    if (p->any) {
      const size_t q = size_t(p->first_result - results_.data());
      outcomes_[q].cycles = results_[q].device_cycles;
    }
}

void Simulation::narrow(const std::vector<BodyPair>& pairs, const PairOptions& po) {
  // The mid-phase and the requests, then the pair tests: in parts on the pool when the device runs parts, else one
  // batch on the device and the outcomes on the pool.
  const size_t total = midphase(pairs);
  if (pool_ && pool_->size() > 1 && total > 1 && collider_->runs_parts()) {
    narrow_parts(po);
    return;
  }
  collider_->collide(requests_, po, results_);
  for_ranges(pool_.get(), pool_ranges(pool_.get(), total, kGrainPairs), [&](size_t, size_t first, size_t end) {
    for (size_t q = first; q < end; ++q) outcome(q);
  });
}

void Simulation::outcome(size_t q) {
  const PairResult& r = results_[q];
  PairOutcome& o = outcomes_[q];
  o.a = requests_pairs_[q].first;
  o.b = requests_pairs_[q].second;
  o.hits = r.hits;
  o.lookups = r.lookups;
  o.contacts = r.contacts.size();
  o.cycles = r.device_cycles;
  // A's outward normals where A's shell is in B, minus B's where B's is in A, in the contacts' order.
  o.normal = Eigen::Vector3d::Zero();
  for (const Contact& c : r.contacts) o.normal += c.a_in_b ? c.normal : -c.normal;
}

}  // namespace voxcd
