#include "voxcd/host/scene/distance_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "voxcd/host/pairs/pose.h"

namespace voxcd {

namespace {
const double kSqrt3 = std::sqrt(3.0);
}  // namespace

DistanceBound::DistanceBound(const std::vector<std::shared_ptr<const ObjectType>>& types, const DeviceConfig& cfg) {
  if (!cfg.distance())
    throw std::invalid_argument("continuous collision bounds distances with a distance device (SB 4, 8 or 16)");
  const double wb = std::ldexp(1.0, -cfg.WB), scale = std::ldexp(1.0, 3 * cfg.WB);
  margin_ = std::numeric_limits<double>::infinity();
  for (const auto& tp : types) {
    const ObjectType& t = *tp;
    const ObjectFile& f = t.object;  // its distance field, dense or sparse
    if (!f.has_distance() || f.distance_bits() > cfg.SB)
      throw std::invalid_argument("continuous collision: object '" + t.name + "' has no distance field of at most " +
                                  std::to_string(cfg.SB) + " bits");
    const double s = f.distance_step();
    // A field that is clamped within the interpolation's error of the surface cannot tell a far point from a near one.
    if (!(f.distance_band() > s + kSqrt3 + kTolerance))
      throw std::invalid_argument("continuous collision: object '" + t.name + "' has a distance band of " +
                                  std::to_string(f.distance_band()) + " voxels; at least " +
                                  std::to_string(s + kSqrt3 + kTolerance) + " are needed");
    margin_ = std::min(margin_, double(f.distance_qmax()) * s * t.voxmap().voxel());
  }
  // Per axis, in voxels of the map, per unit of the shell's largest coordinate (the matrix term) and the translation's.
  fixed_unit_ = 3 * std::ldexp(1.0, -(cfg.MF + 1));
  const double t_err = std::ldexp(1.0, -(cfg.TF() + 1));
  for (const auto& tp : types) {
    const ObjectType& t = *tp;
    const ObjectFile& f = t.object;
    const Voxmap& vm = t.voxmap();
    Type y;
    y.voxel = vm.voxel();
    y.field_error = y.voxel * (f.distance_step() / 2 + kSqrt3 / 2 + kSqrt3 * wb);
    y.fixed_error = kSqrt3 * t_err * y.voxel;
    // Every surface point lies in a surface voxel of the shell grid (spacing h), within sqrt(3)/2 h of its centre;
    // a shell on the surface moves that centre to its closest surface point (no farther than the surface point)
    // and rounds it to 2^-kShellFrac h per axis.
    const PointShell& sh = t.shell();
    const double h = sh.grid.voxel;
    y.shell_gap = sh.on_surface ? kSqrt3 * h + kSqrt3 / 2 * std::ldexp(h, -kShellFrac) : kSqrt3 / 2 * h;
    // Shell words are exact at PF >= kShellFrac (and voxel centres at PF >= 1); otherwise each coordinate is off by
    // up to 2^-(PF+1) spacings.
    const bool exact = cfg.PF >= kShellFrac || (!sh.on_surface && cfg.PF >= 1);
    y.point_error = exact ? 0.0 : kSqrt3 * std::ldexp(h, -(cfg.PF + 1));
    const Eigen::Vector3d lo = vm.origin();
    const Eigen::Vector3d hi = lo + y.voxel * Eigen::Vector3d(vm.dims()[0], vm.dims()[1], vm.dims()[2]);
    y.pad = std::min((t.lo - lo).minCoeff(), (hi - t.hi).minCoeff());
    const int64_t thr = distance_threshold(cfg, margin_, y.voxel, f.distance_step());
    y.none = y.voxel * f.distance_step() * double(thr + 1) / scale - y.field_error;
    for (size_t k = 0; k < sh.size(); ++k) y.pmax = std::max(y.pmax, sh.grid_point(k).cwiseAbs().maxCoeff());
    y.half = 0.5 * (t.hi - t.lo);
    y.mid = 0.5 * (t.hi + t.lo);
    y.radius = t.radius;
    y.centre = t.centre;
    types_.push_back(y);
  }
}

double DistanceBound::direction(const Type& shell, const Type& map, double min_distance, bool any) const {
  // The fixed-point path puts the point within this of its exact place (Euclidean, world units).
  const double fix = kSqrt3 * fixed_unit_ * shell.pmax * map.voxel + map.fixed_error + shell.point_error;
  // A point that reports nothing is outside the map's grid (at least the pad from its solid) or inside with a
  // distance above the threshold.
  double lb = std::min(map.pad, map.none) - fix;
  if (any) lb = std::min(lb, min_distance - map.field_error - fix);
  return lb - shell.shell_gap;
}

double DistanceBound::device(uint32_t ta, uint32_t tb, const PairResult& r) const {
  double dab = std::numeric_limits<double>::infinity(), dba = dab;
  bool ab = false, ba = false;
  for (const Contact& c : r.contacts) {
    if (c.a_in_b) dab = std::min(dab, -c.depth), ab = true;
    else dba = std::min(dba, -c.depth), ba = true;
  }
  const Type &a = types_.at(ta), &b = types_.at(tb);
  return std::min(direction(a, b, dab, ab), direction(b, a, dba, ba));
}

double DistanceBound::geometric(uint32_t ta, const Eigen::Matrix3d& Ra, const Eigen::Vector3d& Ta, uint32_t tb,
                                const Eigen::Matrix3d& Rb, const Eigen::Vector3d& Tb) const {
  const Type &a = types_.at(ta), &b = types_.at(tb);
  // The enclosing spheres.
  double lb = (Ra * a.centre + Ta - Rb * b.centre - Tb).norm() - a.radius - b.radius;
  // The contact boxes, on each box's face axes: a projected gap never exceeds the distance.
  const Eigen::Vector3d d = (Rb * b.mid + Tb) - (Ra * a.mid + Ta);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d u = Ra.col(i);
    const double ga = std::abs(d.dot(u)) - a.half[i] - (Rb.transpose() * u).cwiseAbs().dot(b.half);
    const Eigen::Vector3d w = Rb.col(i);
    const double gb = std::abs(d.dot(w)) - b.half[i] - (Ra.transpose() * w).cwiseAbs().dot(a.half);
    lb = std::max(lb, std::max(ga, gb));
  }
  return lb;
}

}  // namespace voxcd
