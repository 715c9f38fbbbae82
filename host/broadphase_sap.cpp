// Sweep and prune on axis-aligned boxes: "sap" sorts from scratch every frame and sweeps one axis (the paper's
// fast AABB); "coherent" keeps three sorted endpoint lists from frame to frame, restores their order by
// insertion sort, and updates the overlapping pairs from the swaps (the paper's coherent AABB).
#include <algorithm>
#include <cstring>
#include <limits>

#include "host/broadphase_detail.h"

namespace voxcd::detail {
namespace {

// A float at most x / at least x, so that sorting and sweeping on floats never drops a pair the exact double
// test would keep (the order of floats rounded down is the order of the doubles, up to ties).
inline float float_down(double x) {
  float f = float(x);
  if (double(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
inline float float_up(double x) {
  float f = float(x);
  if (double(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}
// The float's bits as an unsigned integer in the float's order.
inline uint32_t ordered_bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, 4);
  return u & 0x80000000u ? ~u : u | 0x80000000u;
}

// Sort and sweep from scratch: O(n) radix sort of the lower bounds on the axis of largest variance of the box
// centres (O(n log n) below 256 bodies), then a sweep that tests each box against those that start before it
// ends on that axis. O(n + s) where s is the number of overlaps of the projections on that axis.
class SortAndSweep final : public BroadphaseBase {
 public:
  std::string name() const override { return "sap"; }
  std::string predicate() const override { return "box"; }

  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    const uint32_t n = uint32_t(bodies.size());
    box_.resize(n);
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (uint32_t i = 0; i < n; ++i) {
      check_body(bodies[i], "sap", i, frame);
      box_[i] = flat(bodies[i].box);
      for (int a = 0; a < 3; ++a) {
        const double c = 0.5 * (box_[i].lo[a] + box_[i].hi[a]);
        sum[a] += c;
        sum2[a] += c * c;
      }
    }
    int axis = 0;
    double best = -1;
    for (int a = 0; a < 3; ++a) {
      const double var = sum2[a] - (n ? sum[a] * sum[a] / n : 0);
      if (var > best) best = var, axis = a;
    }
    // Keys: ordered float bits of the lower bound above, body index below; sorted by the upper 32 bits only.
    keys_.resize(n);
    for (uint32_t i = 0; i < n; ++i) keys_[i] = uint64_t(ordered_bits(float_down(box_[i].lo[axis]))) << 32 | i;
    if (n < 256) {
      std::sort(keys_.begin(), keys_.end());
    } else {
      tmp_.resize(n);
      static constexpr int kShift[3] = {32, 43, 54}, kBits[3] = {11, 11, 10};
      for (int pass = 0; pass < 3; ++pass) {
        uint32_t count[1 << 11] = {};
        const uint32_t mask = (1u << kBits[pass]) - 1;
        for (uint64_t k : keys_) ++count[(k >> kShift[pass]) & mask];
        uint32_t s = 0;
        for (uint32_t d = 0; d <= mask; ++d) {
          const uint32_t c = count[d];
          count[d] = s;
          s += c;
        }
        for (uint64_t k : keys_) tmp_[count[(k >> kShift[pass]) & mask]++] = k;
        keys_.swap(tmp_);
      }
    }
    // Sorted copies: the float bounds the sweep runs on, and the exact boxes it tests.
    lo_.resize(n);
    hi_.resize(n);
    sorted_.resize(n);
    id_.resize(n);
    for (uint32_t s = 0; s < n; ++s) {
      const uint32_t i = uint32_t(keys_[s]);
      id_[s] = i;
      sorted_[s] = box_[i];
      lo_[s] = float_down(box_[i].lo[axis]);
      hi_[s] = float_up(box_[i].hi[axis]);
    }
    found_.clear();
    uint64_t tests = 0;
    for (uint32_t s = 0; s < n; ++s) {
      const float h = hi_[s];
      const FlatBox& a = sorted_[s];
      uint32_t t = s + 1;
      for (; t < n && lo_[t] <= h; ++t)
        if (overlaps(a, sorted_[t])) found_.push_back(pair_key(id_[s], id_[t]));
      tests += t - s - 1;
    }
    sort_pairs(found_, tmp_, n, pairs_);
    stats_ = {tests, pairs_.size()};
  }

 private:
  std::vector<FlatBox> box_, sorted_;
  std::vector<uint64_t> keys_, tmp_, found_;
  std::vector<float> lo_, hi_;
  std::vector<uint32_t> id_;
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
  std::string name() const override { return "coherent"; }
  std::string predicate() const override { return "box"; }

  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    const uint32_t n = uint32_t(bodies.size());
    box_.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      check_body(bodies[i], "coherent", i, frame);
      box_[i] = flat(bodies[i].box);
    }
    uint64_t tests = 0;
    if (n != n_ || !started_) {
      restart(n, tests);
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

  // Sorts the endpoints from scratch and finds the pairs by one sweep along x.
  void restart(uint32_t n, uint64_t& tests) {
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
    open_.clear();
    for (const End& p : ends_[0]) {
      const uint32_t b = p.id >> 1;
      if (p.id & 1) {
        open_.erase(std::find(open_.begin(), open_.end(), b));
      } else {
        for (uint32_t o : open_) {
          ++tests;
          if (overlaps(box_[b], box_[o])) set_.insert(pair_key(b, o));
        }
        open_.push_back(b);
      }
    }
  }

  uint32_t n_ = 0;
  bool started_ = false;
  std::vector<FlatBox> box_;
  std::vector<End> ends_[3];
  std::vector<uint32_t> open_;
  PairSet set_;
  std::vector<uint64_t> found_, tmp_;
};

}  // namespace

std::unique_ptr<Broadphase> make_sap() { return std::make_unique<SortAndSweep>(); }
std::unique_ptr<Broadphase> make_coherent() { return std::make_unique<CoherentSweep>(); }

}  // namespace voxcd::detail
