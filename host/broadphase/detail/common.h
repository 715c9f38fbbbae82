// Internal to the broadphases (host/broadphase*.cpp): input checks, pair sorting, the shared base class and
// the factories of each implementation.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/broadphase/broadphase.h"

namespace voxcd::detail {

inline uint64_t pair_key(uint32_t a, uint32_t b) { return a < b ? uint64_t(a) << 32 | b : uint64_t(b) << 32 | a; }

[[noreturn]] void throw_bad_body(const char* who, size_t i, uint64_t frame, const char* what);

// Checked in the one pass each broadphase makes over its input anyway: a box must be finite with lo <= hi
// (which NaN fails), a sphere finite with radius >= 0, the motion bounds finite and >= 0.
inline void check_body(const BodyBounds& b, const char* who, size_t i, uint64_t frame) {
  const auto& lo = b.box.lo;
  const auto& hi = b.box.hi;
  if (!(lo.x() <= hi.x() && lo.y() <= hi.y() && lo.z() <= hi.z()))
    throw_bad_body(who, i, frame, "box with lo > hi or NaN");
  if (!(std::isfinite(lo.x()) && std::isfinite(lo.y()) && std::isfinite(lo.z()) && std::isfinite(hi.x()) &&
        std::isfinite(hi.y()) && std::isfinite(hi.z())))
    throw_bad_body(who, i, frame, "box not finite");
  if (!(std::isfinite(b.centre.x()) && std::isfinite(b.centre.y()) && std::isfinite(b.centre.z()) &&
        b.radius >= 0 && std::isfinite(b.radius)))
    throw_bad_body(who, i, frame, "sphere not finite or negative radius");
  if (!(b.max_speed >= 0 && std::isfinite(b.max_speed) && b.max_accel >= 0 && std::isfinite(b.max_accel)))
    throw_bad_body(who, i, frame, "motion bound not finite or negative");
}

// keys: pair_key()s of bodies below n, sorted ascending in place (O(k) radix sort for large k).
void sort_keys(std::vector<uint64_t>& keys, std::vector<uint64_t>& scratch, uint32_t n);
// The same on keys[0, k) with scratch[0, k): returns where the sorted keys are (keys or scratch).
const uint64_t* sort_keys(uint64_t* keys, uint64_t* scratch, size_t k, uint32_t n);
// keys: distinct pair_key()s of bodies below n, in any order (reordered here). out: the pairs ascending.
void sort_pairs(std::vector<uint64_t>& keys, std::vector<uint64_t>& scratch, uint32_t n,
                std::vector<BodyPair>& out);

// Exact box overlap on flat boxes (lo xyz, hi xyz), the same comparisons as Aabb::overlaps.
struct FlatBox {
  double lo[3], hi[3];
};
inline bool overlaps(const FlatBox& a, const FlatBox& b) {
  return (a.lo[0] <= b.hi[0]) & (b.lo[0] <= a.hi[0]) & (a.lo[1] <= b.hi[1]) & (b.lo[1] <= a.hi[1]) &
         (a.lo[2] <= b.hi[2]) & (b.lo[2] <= a.hi[2]);
}
inline FlatBox flat(const Aabb& b) {
  return {{b.lo.x(), b.lo.y(), b.lo.z()}, {b.hi.x(), b.hi.y(), b.hi.z()}};
}

// What every broadphase shares: its name, predicate and whether it keeps state (given once, at construction),
// its pairs and statistics, and the input pass that checks and flattens the boxes.
class BroadphaseBase : public Broadphase {
 public:
  BroadphaseBase(const char* name, const char* predicate, bool keeps_state = false)
      : name_(name), predicate_(predicate), keeps_state_(keeps_state) {}
  std::string name() const final { return name_; }
  std::string predicate() const final { return predicate_; }
  bool keeps_state() const final { return keeps_state_; }
  const std::vector<BodyPair>& pairs() const final { return pairs_; }
  BroadphaseStats stats() const final { return stats_; }

 protected:
  // Every body checked (check_body, under this broadphase's name) and its box flattened into `box`, in order.
  // Returns the body count.
  uint32_t check_flatten(const std::vector<BodyBounds>& bodies, uint64_t frame, std::vector<FlatBox>& box) const {
    const uint32_t n = uint32_t(bodies.size());
    box.resize(n);
    for (uint32_t i = 0; i < n; ++i) {
      check_body(bodies[i], name_, i, frame);
      box[i] = flat(bodies[i].box);
    }
    return n;
  }

  const char* const name_;
  std::vector<BodyPair> pairs_;
  BroadphaseStats stats_;

 private:
  const char* const predicate_;
  const bool keeps_state_;
};

std::unique_ptr<Broadphase> make_sap();
std::unique_ptr<Broadphase> make_coherent();
std::unique_ptr<Broadphase> make_queue();
std::unique_ptr<Broadphase> make_tree();
std::unique_ptr<Broadphase> make_grid();

}  // namespace voxcd::detail
