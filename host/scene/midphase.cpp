// The mid-phase: of the broadphase's pairs, those whose enclosing spheres and then oriented boxes meet, as pair
// requests in pair order (Simulation::midphase, make_requests).
#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "voxcd/host/scene/detail/placed.h"
#include "voxcd/host/scene/scene.h"

namespace voxcd {

namespace {

using detail::placed;
using detail::Placed;

// Do the two bodies' oriented boxes meet? Each box is its type's contact bounds (lo..hi in the type's frame:
// every non-empty voxel and shell point) grown by one of its voxels, which covers the fixed-point error of a job
// (a small fraction of a voxel) and rounding here. Gottschalk's separating-axis test: 3 + 3 face axes and 9 edge
// cross products, with a relative slack on the near-parallel cross products.
// Ra, ca: A's rotation and the centre of its box in the world (placed()).
bool boxes_overlap(const ObjectType& ta, const Eigen::Matrix3d& Ra, const Eigen::Vector3d& ca, const ObjectType& tb,
                   const Eigen::Matrix3d& Rb, const Eigen::Vector3d& cb) {
  const double ga = ta.voxmap().voxel(), gb = tb.voxmap().voxel();
  const Eigen::Vector3d ea = 0.5 * (ta.hi - ta.lo) + Eigen::Vector3d::Constant(ga);
  const Eigen::Vector3d eb = 0.5 * (tb.hi - tb.lo) + Eigen::Vector3d::Constant(gb);
  // B's axes and centre in A's frame.
  const Eigen::Matrix3d R = Ra.transpose() * Rb;
  const Eigen::Vector3d t = Ra.transpose() * (cb - ca);
  Eigen::Matrix3d AbsR;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) AbsR(i, j) = std::abs(R(i, j)) + 1e-9;
  for (int i = 0; i < 3; ++i)
    if (std::abs(t[i]) > ea[i] + eb.dot(AbsR.row(i))) return false;
  for (int j = 0; j < 3; ++j)
    if (std::abs(t.dot(R.col(j))) > ea.dot(AbsR.col(j)) + eb[j]) return false;
  for (int i = 0; i < 3; ++i) {
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ea[i1] * AbsR(i2, j) + ea[i2] * AbsR(i1, j);
      const double rb = eb[j1] * AbsR(i, j2) + eb[j2] * AbsR(i, j1);
      if (std::abs(t[i2] * R(i1, j) - t[i1] * R(i2, j)) > ra + rb) return false;
    }
  }
  return true;
}


// Broadphase pairs per part of the mid-phase (about 20 ns a pair: below two parts' worth it runs on the calling
// thread, where the bodies' bounds already are).
constexpr size_t kGrainMidphase = 1024;
constexpr size_t kAheadMidphase = 16;  // pairs ahead whose second sphere is fetched

}  // namespace

size_t Simulation::midphase(const std::vector<BodyPair>& pairs) {
  const Ranges r = pool_ranges(pool_.get(), pairs.size(), kGrainMidphase);
  keep_.resize(pairs.size());
  if (part_counts_.size() < r.parts) part_counts_.resize(r.parts);
  // A range with no pairs is never visited: its count must not be a previous frame's (or uninitialised).
  for (size_t p = 0; p < r.parts; ++p) part_counts_[p].value = 0;
  // Most pairs fail the spheres' test, which reads only the compact spheres; the few that pass are listed, and their
  // bodies' rotations and box centres worked out (as compute_bounds did) for the boxes' test, their bodies fetched a
  // few pairs ahead (they are anywhere in memory).
  if (passing_.size() < r.parts) passing_.resize(r.parts);
  for_ranges(pool_.get(), r, [&](size_t part, size_t first, size_t end) {
    std::vector<uint32_t>& passing = passing_[part].value;
    passing.clear();
    uint64_t kept_first = 0;  // the pairs the first test keeps (without the mid-phase, every one kept)
    for (size_t k = first; k < end; ++k) {
      const uint32_t ia = pairs[k].first, ib = pairs[k].second;
      // Pairs come by first body; the second is anywhere: its sphere is fetched a few pairs ahead.
      if (k + kAheadMidphase < end) __builtin_prefetch(&sphere_[pairs[k + kAheadMidphase].second]);
      // (A pair of which neither body is dynamic is not tested: the response could push neither.)
      const bool keep = (!opt_.midphase || sphere_[ia].overlaps(sphere_[ib])) &&
                        !(any_fixed_ && fixed_[ia] && fixed_[ib]);
      keep_[k] = keep;
      if (keep && opt_.midphase) passing.push_back(uint32_t(k - first));
      kept_first += keep;
    }
    uint64_t kept = opt_.midphase ? 0 : kept_first;
    for (size_t j = 0; j < passing.size(); ++j) {
      if (j + kAheadMidphase < passing.size()) {
        const BodyPair& ahead = pairs[first + passing[j + kAheadMidphase]];
        for (const uint32_t i : {ahead.first, ahead.second}) {
          __builtin_prefetch(&scene_.bodies[i]);
          __builtin_prefetch(reinterpret_cast<const char*>(&scene_.bodies[i] + 1) - 1);
        }
      }
      const size_t k = first + passing[j];
      const Body &a = scene_.bodies[pairs[k].first], &b = scene_.bodies[pairs[k].second];
      const ObjectType &ta = *scene_.types[a.type], &tb = *scene_.types[b.type];
      const Placed pa = placed(ta, a), pb = placed(tb, b);
      keep_[k] = boxes_overlap(ta, pa.R, pa.c, tb, pb.R, pb.c);
      kept += keep_[k];
    }
    part_counts_[part].value = kept;
  });
  // The requests in pair order: each range's from where the ranges before it end.
  size_t total = 0;
  part_first_.resize(r.parts + 1);
  for (size_t p = 0; p < r.parts; ++p) part_first_[p] = total, total += part_counts_[p].value;
  part_first_[r.parts] = total;
  requests_.resize(total);
  requests_pairs_.resize(total);
  results_.resize(total);
  outcomes_.resize(total);
  for_ranges(pool_.get(), r, [&](size_t part, size_t first, size_t end) { make_requests(pairs, first, end, part_first_[part]); });
  return total;
}

void Simulation::make_requests(const std::vector<BodyPair>& pairs, size_t first, size_t end, size_t q) {
  for (size_t k = first; k < end; ++k) {
    if (!keep_[k]) continue;
    const Body &a = scene_.bodies[pairs[k].first], &b = scene_.bodies[pairs[k].second];
    PairRequest& rq = requests_[q];
    rq.a = a.type;
    rq.b = b.type;
    rq.pose_a = a.pose;
    rq.pose_b = b.pose;
    requests_pairs_[q++] = pairs[k];
  }
}

}  // namespace voxcd
