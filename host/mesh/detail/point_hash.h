// Internal to host/mesh (mesh.cpp's weld, repair.cpp): points as keys of a hash table, exactly equal coordinates
// (-0 and +0 the same) the same key, and the welding of exactly equal points.
#pragma once

#include <Eigen/Core>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "voxcd/ref/fnv1a.h"

namespace voxcd::detail {

struct PointHash {
  size_t operator()(const Eigen::Vector3d& p) const {
    double d[3];
    for (int i = 0; i < 3; ++i) d[i] = p[i] == 0 ? 0.0 : p[i];
    return size_t(fnv1a(d, sizeof d));
  }
};

struct PointEqual {
  bool operator()(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const { return a == b; }
};

// Points with exactly equal coordinates merged: each added point's index among those kept, numbered in the order
// they are first added.
class ExactPoints {
 public:
  explicit ExactPoints(size_t n) { index_.reserve(n); }
  uint32_t add(const Eigen::Vector3d& p) {
    auto [it, fresh] = index_.emplace(p, uint32_t(kept_.size()));
    if (fresh) kept_.push_back(p);
    return it->second;
  }
  // Kept as it is, merged with nothing (a point that is not finite, for validate() to name).
  uint32_t add_apart(const Eigen::Vector3d& p) {
    kept_.push_back(p);
    return uint32_t(kept_.size() - 1);
  }
  size_t size() const { return kept_.size(); }
  std::vector<Eigen::Vector3d> take() { return std::move(kept_); }

 private:
  std::unordered_map<Eigen::Vector3d, uint32_t, PointHash, PointEqual> index_;
  std::vector<Eigen::Vector3d> kept_;
};

}  // namespace voxcd::detail
