// Priority queue of pair wake-up frames after Lin and Manocha, on bounding spheres: a pair is tested exactly
// only at its wake-up frame, a lower bound on the first frame its spheres can touch given both bodies' motion
// bounds; overlapping pairs are tested every frame. It never misses a pair while the bounds hold.
#include <algorithm>
#include <limits>

#include "voxcd/host/broadphase/detail/common.h"

namespace voxcd::detail {
namespace {

constexpr uint64_t kNever = std::numeric_limits<uint64_t>::max();
// n(n-1)/2 pairs are kept (the paper's memory demand): 8192 bodies already take about 800 MB.
constexpr uint32_t kMaxBodies = 8192;

class PriorityQueue final : public BroadphaseBase {
 public:
  PriorityQueue() : BroadphaseBase("queue", "sphere", /*keeps_state=*/true) {}

  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    const uint32_t n = uint32_t(bodies.size());
    if (bodies.size() > kMaxBodies)
      throw std::invalid_argument("broadphase queue: " + std::to_string(bodies.size()) +
                                  " bodies; it keeps every pair and takes at most " + std::to_string(kMaxBodies));
    bool restart = n != n_ || !started_ || frame <= frame_;
    resched_.clear();
    for (uint32_t i = 0; i < n; ++i) {
      check_body(bodies[i], name_, i, frame);
      // A new radius breaks the bound as surely as an unexpected move.
      if (!restart && (bodies[i].moved_unexpectedly || bodies[i].radius != radius_[i])) resched_.push_back(i);
    }
    radius_.resize(n);
    for (uint32_t i = 0; i < n; ++i) radius_[i] = bodies[i].radius;
    found_.clear();
    if (restart)
      schedule_all(bodies, frame);
    else
      reschedule(bodies, frame);
    frame_ = frame;
    const uint64_t tests = test_due(bodies, frame);
    if (heap_.size() > 2 * wake_.size() + 1024) compact();
    sort_pairs(found_, scratch_, n, pairs_);
    stats_ = {tests, pairs_.size()};
  }

 private:
  struct Entry {
    uint64_t wake;
    uint32_t i, j;
  };

  // Every pair scheduled afresh.
  void schedule_all(const std::vector<BodyBounds>& bodies, uint64_t frame) {
    const uint32_t n = uint32_t(bodies.size());
    n_ = n;
    started_ = true;
    wake_.assign(size_t(n) * (n ? n - 1 : 0) / 2, kNever);
    heap_.clear();
    for (uint32_t i = 0; i < n; ++i)
      for (uint32_t j = i + 1; j < n; ++j) {
        const uint64_t w = wake_at(bodies[i], bodies[j], frame);
        wake_[index(i, j)] = w;
        if (w != kNever) heap_.push_back({w, i, j});
      }
    std::make_heap(heap_.begin(), heap_.end(), later);
  }

  // The pairs of the bodies in resched_ scheduled again (each pair once).
  void reschedule(const std::vector<BodyBounds>& bodies, uint64_t frame) {
    const uint32_t n = uint32_t(bodies.size());
    flagged_.assign(n, 0);
    for (uint32_t i : resched_) flagged_[i] = 1;
    for (uint32_t i : resched_)
      for (uint32_t j = 0; j < n; ++j) {
        if (j == i || (flagged_[j] && j < i)) continue;
        const uint32_t a = std::min(i, j), b = std::max(i, j);
        const uint64_t w = wake_at(bodies[a], bodies[b], frame);
        uint64_t& cur = wake_[index(a, b)];
        if (w != cur) {
          cur = w;
          if (w != kNever) push({w, a, b});
        }
      }
  }

  // Every pair whose time has come: test it, report it if its spheres overlap (and test it again next frame),
  // otherwise schedule it by its new separation. Entries whose pair was rescheduled since are stale. Returns the tests.
  uint64_t test_due(const std::vector<BodyBounds>& bodies, uint64_t frame) {
    uint64_t tests = 0;
    while (!heap_.empty() && heap_.front().wake <= frame) {
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const Entry e = heap_.back();
      heap_.pop_back();
      uint64_t& cur = wake_[index(e.i, e.j)];
      if (cur != e.wake) continue;
      ++tests;
      if (spheres_overlap(bodies[e.i], bodies[e.j])) {
        found_.push_back(uint64_t(e.i) << 32 | e.j);
        cur = frame + 1;
      } else {
        cur = wake_at(bodies[e.i], bodies[e.j], frame);
      }
      if (cur != kNever) push({cur, e.i, e.j});
    }
    return tests;
  }

  // Min-heap on the wake-up frame, ties by pair so that the order is fixed.
  static bool later(const Entry& x, const Entry& y) {
    return x.wake > y.wake || (x.wake == y.wake && (x.i > y.i || (x.i == y.i && x.j > y.j)));
  }
  size_t index(uint32_t i, uint32_t j) const {  // i < j
    return size_t(i) * (2 * size_t(n_) - i - 1) / 2 + (j - i - 1);
  }
  void push(const Entry& e) {
    heap_.push_back(e);
    std::push_heap(heap_.begin(), heap_.end(), later);
  }
  void compact() {
    size_t m = 0;
    for (const Entry& e : heap_)
      if (wake_[index(e.i, e.j)] == e.wake) heap_[m++] = e;
    heap_.resize(m);
    std::make_heap(heap_.begin(), heap_.end(), later);
  }

  // The first frame from `frame` on at which the spheres of a and b could touch: `frame` if they do now. In t
  // frames a body's sphere moves at most v t + a t (t + 1) / 2 (speed at most v + a k during the k-th frame,
  // k = 1..t), which bounds both continuous and stepwise (Euler) motion. The gap is shrunk by a relative 1e-9
  // so that rounding can only make the wake-up early.
  static uint64_t wake_at(const BodyBounds& a, const BodyBounds& b, uint64_t frame) {
    if (spheres_overlap(a, b)) return frame;
    const double d = (a.centre - b.centre).norm(), rs = a.radius + b.radius;
    const double gap = d - rs - 1e-9 * (d + rs);
    if (gap <= 0) return frame + 1;
    const double v = a.max_speed + b.max_speed, acc = a.max_accel + b.max_accel;
    if (v == 0 && acc == 0) return kNever;
    // Smallest t >= 1 with (acc/2) t^2 + (v + acc/2) t >= gap.
    const double p = v + 0.5 * acc;
    double t = acc > 0 ? (2 * gap) / (p + std::sqrt(p * p + 2 * acc * gap)) : gap / v;
    t = std::ceil(t);
    if (!(t < 1e15)) return frame + uint64_t(1e15);  // as good as never, but not never
    uint64_t steps = std::max<uint64_t>(1, uint64_t(t));
    auto reach = [&](uint64_t s) { return v * double(s) + 0.5 * acc * double(s) * double(s + 1); };
    while (steps > 1 && reach(steps - 1) >= gap) --steps;
    while (reach(steps) < gap) ++steps;
    return frame + steps;
  }

  uint32_t n_ = 0;
  bool started_ = false;
  uint64_t frame_ = 0;
  std::vector<uint64_t> wake_;
  std::vector<Entry> heap_;
  std::vector<double> radius_;
  std::vector<uint32_t> resched_;
  std::vector<uint8_t> flagged_;
  std::vector<uint64_t> found_, scratch_;
};

}  // namespace

std::unique_ptr<Broadphase> make_queue() { return std::make_unique<PriorityQueue>(); }

}  // namespace voxcd::detail
