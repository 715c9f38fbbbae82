// Sweep and prune on axis-aligned boxes: "sap" sorts from scratch every frame and sweeps one axis (the paper's
// fast AABB); "coherent" keeps three sorted endpoint lists from frame to frame, restores their order by
// insertion sort, and updates the overlapping pairs from the swaps (the paper's coherent AABB).
#include <algorithm>
#include <cmath>
#include <cstring>

#include "voxcd/host/broadphase/detail/common.h"

namespace voxcd::detail {
namespace {

// A float at most x / at least x, so that sorting and sweeping on floats never drops a pair the exact double
// test would keep (rounding is monotonic, so the order of the rounded-down floats is the order of the doubles, up to ties).
inline float step_float(float f, bool up) {  // the next float up or down (as std::nextafter, without libm)
  uint32_t b;
  std::memcpy(&b, &f, 4);
  if (f == 0) b = up ? 1u : 0x80000001u;
  else if ((f > 0) == up) ++b;
  else --b;
  std::memcpy(&f, &b, 4);
  return f;
}
inline float float_down(double x) {
  const float f = float(x);
  return double(f) > x ? step_float(f, false) : f;
}
inline float float_up(double x) {
  const float f = float(x);
  return double(f) < x ? step_float(f, true) : f;
}
// Sort and sweep from scratch every frame: a sort of the lower bounds on the axis of largest variance of the box
// centres, then a sweep testing each box against those that start before it ends on that axis. A sweep over all n boxes would test every pair whose projections overlap on
// that one axis, which in a crowded 3-D scene grows like n^(5/3); so the sweep is cut into a grid of columns
// across the two other axes (cells about four mean box extents wide, at most 64 a side and one per 16 boxes), a
// box sweeps in every column it touches, and a pair is reported only in the column holding the lower corner of
// its overlap. O(n + s + k), s the projections overlapping within columns: near O(n log(n / cells) + k).
class SortAndSweep final : public BroadphaseBase {
 public:
  SortAndSweep() : BroadphaseBase("sap", "box") {}

  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    const uint32_t n = check_flatten(bodies, frame, box_);
    const Columns cols = columns();
    scatter(cols);
    found_.clear();
    const uint64_t tests = sweep(cols);
    sort_pairs(found_, tmp_, n, pairs_);
    stats_ = {tests, pairs_.size()};
  }

 private:
  // The sweep axis (the one the box centres vary most along) and the grid of columns across the other two.
  struct Columns {
    int axis = 0, u = 1, v = 2;
    int cells[2] = {1, 1};
    double inv[2] = {0, 0}, lo_min[3] = {0, 0, 0};
    uint16_t cell(double x, int k) const {
      const int a = k ? v : u;
      return uint16_t(std::min(int((x - lo_min[a]) * inv[k]), cells[k] - 1));
    }
  };

  Columns columns() const {
    const uint32_t n = uint32_t(box_.size());
    Columns c;
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, ext[3] = {0, 0, 0}, hi_max[3] = {0, 0, 0};
    if (n)
      for (int a = 0; a < 3; ++a) c.lo_min[a] = box_[0].lo[a], hi_max[a] = box_[0].hi[a];
    for (const FlatBox& b : box_)
      for (int a = 0; a < 3; ++a) {
        const double m = 0.5 * (b.lo[a] + b.hi[a]);
        sum[a] += m;
        sum2[a] += m * m;
        ext[a] += b.hi[a] - b.lo[a];
        c.lo_min[a] = std::min(c.lo_min[a], b.lo[a]);
        hi_max[a] = std::max(hi_max[a], b.hi[a]);
      }
    double best = -1;
    for (int a = 0; a < 3; ++a) {
      const double var = sum2[a] - (n ? sum[a] * sum[a] / n : 0);
      if (var > best) best = var, c.axis = a;
    }
    c.u = (c.axis + 1) % 3;
    c.v = (c.axis + 2) % 3;
    const int limit = std::max(1, int(std::sqrt(n / 16.0)));
    for (int k = 0; k < 2; ++k) {
      const int a = k ? c.v : c.u;
      const double range = hi_max[a] - c.lo_min[a], mean = n ? ext[a] / n : 0;
      const double want = mean > 0 ? range / (4 * mean) : 64;
      c.cells[k] = range > 0 ? int(std::min<double>({want, 64.0, double(limit)})) : 1;
      c.cells[k] = std::max(c.cells[k], 1);
      c.inv[k] = range > 0 ? c.cells[k] / range : 0;
    }
    return c;
  }

  // Each box into every column it touches (a counting scatter in body order, which reads the input in order), then
  // each column sorted on its own: small sorts in cache instead of a gather over all boxes.
  void scatter(const Columns& c) {
    const uint32_t n = uint32_t(box_.size());
    const int ncell = c.cells[0] * c.cells[1], axis = c.axis, u = c.u, v = c.v;
    start_.assign(ncell + 1, 0);
    span_.resize(n);
    entry_.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      const FlatBox& b = box_[i];
      Span& sp = span_[i];
      sp = {c.cell(b.lo[u], 0), c.cell(b.hi[u], 0), c.cell(b.lo[v], 1), c.cell(b.hi[v], 1)};
      entry_[i] = {float_down(b.lo[axis]), float_up(b.hi[axis]), float_down(b.lo[u]), float_up(b.hi[u]),
                   float_down(b.lo[v]),    float_up(b.hi[v]),    i,                   sp.u0, sp.v0};
      for (int cu = sp.u0; cu <= sp.u1; ++cu)
        for (int cv = sp.v0; cv <= sp.v1; ++cv) ++start_[cu * c.cells[1] + cv + 1];
    }
    for (int k = 0; k < ncell; ++k) start_[k + 1] += start_[k];
    fill_.assign(start_.begin(), start_.end() - 1);
    entries_.resize(start_[ncell]);
    for (uint32_t i = 0; i < n; ++i) {
      const Span& sp = span_[i];
      for (int cu = sp.u0; cu <= sp.u1; ++cu)
        for (int cv = sp.v0; cv <= sp.v1; ++cv) entries_[fill_[cu * c.cells[1] + cv]++] = entry_[i];
    }
    for (int k = 0; k < ncell; ++k)
      std::sort(entries_.begin() + start_[k], entries_.begin() + start_[k + 1],
                [](const Entry& x, const Entry& y) { return x.lo < y.lo || (x.lo == y.lo && x.id < y.id); });
  }

  // Sweeps every column; a pair is found only in the column of the lower corner of its overlap. Returns the tests.
  uint64_t sweep(const Columns& cols) {
    uint64_t tests = 0;
    const int ncell = cols.cells[0] * cols.cells[1];
    for (int c = 0; c < ncell; ++c) {
      const uint16_t cu = uint16_t(c / cols.cells[1]), cv = uint16_t(c % cols.cells[1]);
      const Entry* e = entries_.data() + start_[c];
      const uint32_t m = start_[c + 1] - start_[c];
      for (uint32_t s = 0; s < m; ++s) {
        const Entry& a = e[s];
        uint32_t t = s + 1;
        for (; t < m && e[t].lo <= a.hi; ++t) {
          const Entry& b = e[t];
          // Conservative float test on the other axes, this column only, then the exact test.
          if ((a.lo_u <= b.hi_u) & (b.lo_u <= a.hi_u) & (a.lo_v <= b.hi_v) & (b.lo_v <= a.hi_v) &
              (std::max(a.u0, b.u0) == cu) & (std::max(a.v0, b.v0) == cv) && overlaps(box_[a.id], box_[b.id]))
            found_.push_back(pair_key(a.id, b.id));
        }
        tests += t - s - 1;
      }
    }
    return tests;
  }

  struct Span {
    uint16_t u0, u1, v0, v1;  // the columns a box touches
  };
  struct Entry {
    float lo, hi, lo_u, hi_u, lo_v, hi_v;  // rounded outwards
    uint32_t id;
    uint16_t u0, v0;
  };
  std::vector<FlatBox> box_;
  std::vector<uint64_t> tmp_, found_;
  std::vector<Span> span_;
  std::vector<uint32_t> start_, fill_;
  std::vector<Entry> entries_, entry_;
};

// Open-addressing set of pair keys (linear probing, backward-shift deletion): no tombstones, no allocation
// once grown.
class PairSet {
 public:
  static constexpr uint64_t kEmpty = ~uint64_t(0);
  void clear() {
    std::fill(slots_.begin(), slots_.end(), kEmpty);
    size_ = 0;
  }
  void insert(uint64_t key) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    size_t i = slot(key);
    while (slots_[i] != kEmpty) {
      if (slots_[i] == key) return;
      i = (i + 1) & mask_;
    }
    slots_[i] = key;
    ++size_;
  }
  void erase(uint64_t key) {
    if (slots_.empty()) return;
    size_t i = slot(key);
    while (slots_[i] != key) {
      if (slots_[i] == kEmpty) return;
      i = (i + 1) & mask_;
    }
    // Shift later members of the cluster back into the hole when their home slot allows it.
    size_t hole = i;
    for (size_t j = (i + 1) & mask_; slots_[j] != kEmpty; j = (j + 1) & mask_) {
      const size_t home = slot(slots_[j]);
      if (((j - home) & mask_) >= ((j - hole) & mask_)) {
        slots_[hole] = slots_[j];
        hole = j;
      }
    }
    slots_[hole] = kEmpty;
    --size_;
  }
  template <class Fn>
  void for_each(Fn&& fn) const {
    for (uint64_t k : slots_)
      if (k != kEmpty) fn(k);
  }
  size_t size() const { return size_; }

 private:
  size_t slot(uint64_t key) const { return size_t((key * 0x9E3779B97F4A7C15ull) >> 20) & mask_; }
  void grow() {
    std::vector<uint64_t> old;
    old.swap(slots_);
    slots_.assign(old.empty() ? 1024 : 2 * old.size(), kEmpty);
    mask_ = slots_.size() - 1;
    size_ = 0;
    for (uint64_t k : old)
      if (k != kEmpty) insert(k);
  }
  std::vector<uint64_t> slots_;
  size_t mask_ = 0, size_ = 0;
};

// Coherent sweep and prune. Each axis keeps its 2n endpoints sorted by (value, min before max); two boxes
// overlap on an axis exactly when each one's min precedes the other's max. Insertion sort from last frame's
// order swaps exactly the endpoint pairs whose order changed, so a min passing a max leftwards is the only way
// to start overlapping on an axis (then the full box test on this frame's boxes decides) and a max passing a
// min leftwards the only way to stop (the pair goes). O(n + swaps + k) a frame: O(n + k) in coherent scenes.
class CoherentSweep final : public BroadphaseBase {
 public:
  CoherentSweep() : BroadphaseBase("coherent", "box", /*keeps_state=*/true) {}

  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    const uint32_t n = check_flatten(bodies, frame, box_);
    uint64_t tests = 0;
    if (n != n_ || !started_) {
      restart(bodies, frame, tests);
    } else {
      for (int a = 0; a < 3; ++a) {
        auto& e = ends_[a];
        for (auto& p : e) p.v = p.id & 1 ? box_[p.id >> 1].hi[a] : box_[p.id >> 1].lo[a];
        for (size_t k = 1; k < e.size(); ++k) {
          const End x = e[k];
          size_t j = k;
          while (j > 0 && before(x, e[j - 1])) {
            const End& p = e[j - 1];
            if (!(x.id & 1) && (p.id & 1)) {  // x's min passes p's max: they may start to overlap
              ++tests;
              if (overlaps(box_[x.id >> 1], box_[p.id >> 1])) set_.insert(pair_key(x.id >> 1, p.id >> 1));
            } else if ((x.id & 1) && !(p.id & 1)) {  // x's max passes p's min: they stop overlapping
              set_.erase(pair_key(x.id >> 1, p.id >> 1));
            }
            e[j] = p;
            --j;
          }
          e[j] = x;
        }
      }
    }
    found_.clear();
    set_.for_each([&](uint64_t k) { found_.push_back(k); });
    sort_pairs(found_, tmp_, n, pairs_);
    stats_ = {tests, pairs_.size()};
  }

 private:
  struct End {
    double v;
    uint32_t id;  // body << 1 | (1 for a max)
  };
  static bool before(const End& x, const End& y) { return x.v < y.v || (x.v == y.v && (x.id & 1) < (y.id & 1)); }

  // Sorts the endpoints from scratch and finds the pairs by sort and sweep (one sweep along x with a list of open
  // boxes would be quadratic for many bodies: n times the boxes that span a point of x).
  void restart(const std::vector<BodyBounds>& bodies, uint64_t frame, uint64_t& tests) {
    const uint32_t n = uint32_t(bodies.size());
    n_ = n;
    started_ = true;
    set_.clear();
    for (int a = 0; a < 3; ++a) {
      auto& e = ends_[a];
      e.resize(2 * size_t(n));
      for (uint32_t i = 0; i < n; ++i) {
        e[2 * i] = {box_[i].lo[a], 2 * i};
        e[2 * i + 1] = {box_[i].hi[a], 2 * i + 1};
      }
      std::sort(e.begin(), e.end(), [](const End& x, const End& y) {
        return before(x, y) || (!before(y, x) && x.id < y.id);
      });
    }
    SortAndSweep sweep;
    sweep.update(bodies, frame);
    tests += sweep.stats().overlap_tests;
    for (const BodyPair& p : sweep.pairs()) set_.insert(pair_key(p.first, p.second));
  }

  uint32_t n_ = 0;
  bool started_ = false;
  std::vector<FlatBox> box_;
  std::vector<End> ends_[3];
  PairSet set_;
  std::vector<uint64_t> found_, tmp_;
};

}  // namespace

std::unique_ptr<Broadphase> make_sap() { return std::make_unique<SortAndSweep>(); }
std::unique_ptr<Broadphase> make_coherent() { return std::make_unique<CoherentSweep>(); }

}  // namespace voxcd::detail
