// The broadphase factory, the shared helpers, and the two all-pairs broadphases ("all" and "sphere").
#include "voxcd/host/broadphase/broadphase.h"

#include <algorithm>
#include <sstream>

#include "voxcd/host/broadphase/detail/common.h"

namespace voxcd {
namespace detail {

void throw_bad_body(const char* who, size_t i, uint64_t frame, const char* what) {
  std::ostringstream s;
  s << "broadphase " << who << ": body " << i << " at frame " << frame << ": " << what;
  throw std::invalid_argument(s.str());
}

// LSD radix sort on the pair packed into 2 * bits(n - 1) bits, in as few passes of at most 11 bits as cover them
// (two of 8 bits for 256 bodies, whose counts clear and sum in a blink): O(k) for any pair count.
const uint64_t* sort_keys(uint64_t* keys, uint64_t* scratch, size_t k, uint32_t n) {
  if (k < 256) {
    std::sort(keys, keys + k);
    return keys;
  }
  int b = 1;
  while (b < 32 && (uint64_t(1) << b) < n) ++b;
  for (size_t i = 0; i < k; ++i) keys[i] = (keys[i] >> 32) << b | (keys[i] & 0xffffffffu);
  constexpr int kMaxDigit = 11;
  const int passes = (2 * b + kMaxDigit - 1) / kMaxDigit;
  const int digit = (2 * b + passes - 1) / passes;
  const uint64_t dmask = (uint64_t(1) << digit) - 1;
  uint32_t count[1 << kMaxDigit];
  for (int shift = 0; shift < 2 * b; shift += digit) {
    std::fill(count, count + (size_t(1) << digit), 0u);
    for (size_t i = 0; i < k; ++i) ++count[(keys[i] >> shift) & dmask];
    uint32_t sum = 0;
    for (size_t d = 0; d < (size_t(1) << digit); ++d) {
      const uint32_t t = count[d];
      count[d] = sum;
      sum += t;
    }
    for (size_t i = 0; i < k; ++i) scratch[count[(keys[i] >> shift) & dmask]++] = keys[i];
    std::swap(keys, scratch);
  }
  const uint64_t mask = (uint64_t(1) << b) - 1;
  for (size_t i = 0; i < k; ++i) keys[i] = (keys[i] >> b) << 32 | (keys[i] & mask);
  return keys;
}

void sort_keys(std::vector<uint64_t>& keys, std::vector<uint64_t>& scratch, uint32_t n) {
  scratch.resize(keys.size());
  if (sort_keys(keys.data(), scratch.data(), keys.size(), n) != keys.data()) keys.swap(scratch);
}

void sort_pairs(std::vector<uint64_t>& keys, std::vector<uint64_t>& scratch, uint32_t n,
                std::vector<BodyPair>& out) {
  sort_keys(keys, scratch, n);
  out.resize(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) out[i] = {uint32_t(keys[i] >> 32), uint32_t(keys[i])};
}

namespace {

// Every pair, no test: the paper's baseline. The list is rebuilt only when the body count changes.
class AllPairs final : public BroadphaseBase {
 public:
  AllPairs() : BroadphaseBase("all", "all") {}
  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    for (size_t i = 0; i < bodies.size(); ++i) check_body(bodies[i], name_, i, frame);
    const size_t n = bodies.size();
    if (n != n_ || pairs_.size() != n * (n ? n - 1 : 0) / 2) {
      n_ = n;
      pairs_.clear();
      pairs_.reserve(n * (n ? n - 1 : 0) / 2);
      for (uint32_t i = 0; i < n; ++i)
        for (uint32_t j = i + 1; j < n; ++j) pairs_.push_back({i, j});
    }
    stats_ = {0, pairs_.size()};
  }

 private:
  size_t n_ = 0;
};

// Bounding spheres, every pair tested: O(n^2). A loose test over flat arrays (which the compiler vectorises)
// picks candidates; spheres_overlap() decides, so the result is exactly the predicate's.
class SpherePairs final : public BroadphaseBase {
 public:
  SpherePairs() : BroadphaseBase("sphere", "sphere") {}
  void update(const std::vector<BodyBounds>& bodies, uint64_t frame) override {
    const size_t n = bodies.size();
    x_.resize(n);
    y_.resize(n);
    z_.resize(n);
    r_.resize(n);
    for (size_t i = 0; i < n; ++i) {
      check_body(bodies[i], name_, i, frame);
      x_[i] = bodies[i].centre.x();
      y_[i] = bodies[i].centre.y();
      z_[i] = bodies[i].centre.z();
      r_[i] = bodies[i].radius;
    }
    pairs_.clear();
    // Rounding differs from spheres_overlap() by a few ulps at most: the candidate test is looser by 1e-9.
    constexpr double kLoose = 1 + 1e-9;
    uint64_t tests = 0;
    for (uint32_t i = 0; i < n; ++i) {
      const double xi = x_[i], yi = y_[i], zi = z_[i], ri = r_[i];
      for (uint32_t j = i + 1; j < n; ++j) {
        const double dx = x_[j] - xi, dy = y_[j] - yi, dz = z_[j] - zi, s = r_[j] + ri;
        if (dx * dx + dy * dy + dz * dz <= s * s * kLoose && spheres_overlap(bodies[i], bodies[j]))
          pairs_.push_back({i, j});
      }
      tests += n - 1 - i;
    }
    stats_ = {tests, pairs_.size()};
  }

 private:
  std::vector<double> x_, y_, z_, r_;
};

}  // namespace
}  // namespace detail

std::vector<std::string> broadphase_names() { return {"all", "sphere", "sap", "coherent", "queue", "tree", "grid"}; }

std::unique_ptr<Broadphase> make_broadphase(const std::string& name) {
  if (name == "all") return std::make_unique<detail::AllPairs>();
  if (name == "sphere") return std::make_unique<detail::SpherePairs>();
  if (name == "sap") return detail::make_sap();
  if (name == "coherent") return detail::make_coherent();
  if (name == "queue") return detail::make_queue();
  if (name == "tree") return detail::make_tree();
  if (name == "grid") return detail::make_grid();
  std::string known;
  for (const auto& n : broadphase_names()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown broadphase '" + name + "' (known: " + known + ")");
}

}  // namespace voxcd
