#include "voxcd/host/scene/partition.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace voxcd {

int Slabs::slab_of(double v) const { return int(std::upper_bound(cuts.begin(), cuts.end(), v) - cuts.begin()); }

Slabs split_slabs(const std::vector<BodyBounds>& bodies, int ranks) {
  if (ranks < 1) throw std::invalid_argument("split_slabs: " + std::to_string(ranks) + " ranks");
  Slabs s;
  if (bodies.empty()) {
    s.cuts.assign(size_t(ranks - 1), 0.0);
    return s;
  }
  Eigen::Vector3d lo = bodies[0].centre, hi = bodies[0].centre;
  for (const BodyBounds& b : bodies) lo = lo.cwiseMin(b.centre), hi = hi.cwiseMax(b.centre);
  (hi - lo).maxCoeff(&s.axis);
  std::vector<double> c;
  c.reserve(bodies.size());
  for (const BodyBounds& b : bodies) c.push_back(b.centre[s.axis]);
  // The cuts' order statistics by selection, cut after cut on what lies above the last (a sort costs more than the
  // rest of the partition): c[k] is then the k-th smallest, and the largest of c[begin, k) the (k-1)-th.
  const size_t n = c.size();
  size_t begin = 0;
  for (int r = 1; r < ranks; ++r) {
    const size_t k = n * size_t(r) / size_t(ranks);  // bodies below the cut
    if (k == 0) {
      s.cuts.push_back(*std::min_element(c.begin(), c.end()));
      continue;
    }
    if (k == begin) {  // fewer bodies than ranks: the same cut again
      s.cuts.push_back(s.cuts.back());
      continue;
    }
    std::nth_element(c.begin() + std::ptrdiff_t(begin), c.begin() + std::ptrdiff_t(k), c.end());
    const double below = *std::max_element(c.begin() + std::ptrdiff_t(begin), c.begin() + std::ptrdiff_t(k));
    s.cuts.push_back(0.5 * (below + c[k]));
    begin = k;
  }
  return s;
}

namespace {
// The body's extent along the axis: of its sphere and its box together, so that both predicates' pairs overlap.
double extent_lo(const BodyBounds& b, int axis) { return std::min(b.centre[axis] - b.radius, b.box.lo[axis]); }
double extent_hi(const BodyBounds& b, int axis) { return std::max(b.centre[axis] + b.radius, b.box.hi[axis]); }
}  // namespace

std::vector<uint32_t> slab_bodies(const Slabs& s, int r, const std::vector<BodyBounds>& bodies) {
  std::vector<uint32_t> out;
  for (uint32_t i = 0; i < bodies.size(); ++i)
    if (s.slab_of(extent_lo(bodies[i], s.axis)) <= r && s.slab_of(extent_hi(bodies[i], s.axis)) >= r)
      out.push_back(i);
  return out;
}

int pair_owner(const Slabs& s, const BodyBounds& a, const BodyBounds& b) {
  return s.slab_of(std::max(extent_lo(a, s.axis), extent_lo(b, s.axis)));
}

}  // namespace voxcd
