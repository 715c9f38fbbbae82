// Contacts from hit records: a shell point's world position and normal, the voxel and its state, the depth (the
// voxel's penetration estimate, or on a distance device the interpolated distance and the field's gradient), written
// into a PairResult's Contacts or into ContactArrays (host/pairs/detail/contact_out.h).
#include "voxcd/host/pairs/contacts.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "voxcd/host/pairs/collider.h"
#include "voxcd/host/pairs/detail/contact_out.h"
#include "voxcd/host/pairs/detail/shell_order.h"

namespace voxcd {

Contact ContactArrays::contact(size_t k) const {
  Contact c;
  c.pair = pair.at(k);
  c.a_in_b = a_in_b[k] != 0;
  c.point = point[k];
  c.position = Eigen::Vector3d(position[3 * k], position[3 * k + 1], position[3 * k + 2]);
  c.normal = Eigen::Vector3d(normal[3 * k], normal[3 * k + 1], normal[3 * k + 2]);
  c.voxel = {voxel[3 * k], voxel[3 * k + 1], voxel[3 * k + 2]};
  c.state = state[k];
  c.depth = depth[k];
  return c;
}

void ContactArrays::resize(size_t pairs, size_t rows) {
  first.resize(pairs + 1);
  hits.resize(pairs);
  lookups.resize(pairs);
  device_cycles.resize(pairs);
  pair.resize(rows);
  point.resize(rows);
  a_in_b.resize(rows);
  state.resize(rows);
  position.resize(3 * rows);
  normal.resize(3 * rows);
  voxel.resize(3 * rows);
  depth.resize(rows);
}

namespace {

// The field's slope at g over a span of h voxels (central differences): a direction where the interpolant is flat
// (a plateau between two surfaces, whose nodes are equal).
Eigen::Vector3d wide_gradient(const ObjectFile& f, const Eigen::Vector3d& g, double h) {
  Eigen::Vector3d s;
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(i) * h;
    s[i] = (f.distance_at(g + e) - f.distance_at(g - e)) / (2 * h);
  }
  return s;
}

// Where a speculative contact is placed: where the field reads 1/16 voxel inside the other object. The field's zero
// lies within 1/4 voxel of the surface where the resolution test samples a sub-cell (docs/objects.md), up to 0.27 voxel
// between those samples on the corpus; 1/16 inside keeps every placed contact within 1/4 voxel of the surface.
constexpr double kSpeculativeLevel = -1.0 / 16;

// A grid point g (voxels) moved onto the field's `level` by steps of the distance along the gradient's direction
// (sphere tracing: the field is about 1-Lipschitz, so a step from outside does not pass the level), at most 16, until
// within 1/256 voxel; where the interpolant is flat, along its slope over the step's span; where that vanishes too it
// stays. The result's gradient in *grad.
Eigen::Vector3d onto_level(const ObjectFile& f, Eigen::Vector3d g, double level, Eigen::Vector3d* grad) {
  for (int k = 0; k < 16; ++k) {
    const double d = f.distance_at(g, grad) - level;
    if (std::abs(d) < 1.0 / 256) break;
    Eigen::Vector3d dir = *grad;
    if (dir.norm() < 1e-6) dir = wide_gradient(f, g, std::max(std::abs(d), 0.25));
    const double len = dir.norm();
    if (len < 1e-6) break;
    g -= (d / std::max(len, 1.0)) * (dir / len);
  }
  f.distance_at(g, grad);
  return g;
}

// The voxel of grid point g, within the grid of dims n.
std::array<uint32_t, 3> voxel_of(const Eigen::Vector3d& g, const std::array<uint32_t, 3>& n) {
  std::array<uint32_t, 3> v;
  for (int i = 0; i < 3; ++i) v[i] = uint32_t(std::clamp(std::floor(g[i]), 0.0, double(n[i] - 1)));
  return v;
}

// A speculative contact moved onto the other object's surface: its grid point g (voxels) to where the field reads
// kSpeculativeLevel, its world position (the map's grid at rotation Rm, translation tm) and its voxel with it; the
// field's gradient there in *grad.
void place_on_surface(const ObjectFile& f, const Voxmap& vm, const Eigen::Matrix3d& Rm, const Eigen::Vector3d& tm,
                      Eigen::Vector3d& g, Eigen::Vector3d& position, std::array<uint32_t, 3>& v, Eigen::Vector3d* grad) {
  g = onto_level(f, g, kSpeculativeLevel, grad);
  position = Rm * (vm.origin() + g * vm.voxel()) + tm;
  v = voxel_of(g, vm.dims());
}

}  // namespace

template <class Out>
void PairCollider::make_contacts(const PairRequest& req, uint32_t pair, bool a_in_b, const HitColumns& cols,
                                 const detail::SortedHit* hits, size_t n, const Eigen::Matrix3d& Ra,
                                 const Eigen::Matrix3d& Rb, const PairOptions& opt, const Out& to) const {
  // The depth lookups land all over B's depth field (4 bytes per voxel, often larger than the cache), so the loop
  // prefetches the depth of the hit a few hits ahead.
  constexpr size_t kAhead = 16;
  const ObjectType& shell_t = *types_[a_in_b ? req.a : req.b];
  const ObjectType& map_t = *types_[a_in_b ? req.b : req.a];
  const RigidPose& pose = a_in_b ? req.pose_a : req.pose_b;
  const Eigen::Matrix3d R = a_in_b ? Ra : Rb;
  const Eigen::Vector3d t = pose.translation;
  const Eigen::Vector3d* points = shell_t.shell().points.data();
  const Eigen::Vector3d* normals = shell_t.shell().normals.data();
  const Voxmap& vm = map_t.voxmap();
  const float* depth = map_t.depth.data();
  const size_t nvox = map_t.depth.size();
  const double voxel = vm.voxel();
  const uint64_t nx = vm.dims()[0], nxy = nx * vm.dims()[1];
  const uint32_t *cx = cols.x.data(), *cy = cols.y.data(), *cz = cols.z.data();
  to.run(n, pair, a_in_b);
  if (!device_->config().distance()) {
    const uint8_t* st = cols.state.data();
    for (size_t k = 0; k < n; ++k) {
      if (k + kAhead < n) {
        const uint32_t a = hits[k + kAhead].hit;
        const uint64_t i = cx[a] + nx * cy[a] + nxy * cz[a];
        if (i < nvox) __builtin_prefetch(depth + i);
      }
      const uint32_t h = hits[k].hit, point = hits[k].point;
      const uint32_t x = cx[h], y = cy[h], z = cz[h];
      to.put(k, point, R * points[point] + t, R * normals[point], x, y, z, st[h],
             double(depth[x + nx * y + nxy * z]) * voxel);
    }
    return;
  }
  const ObjectFile& field = map_t.object;  // its distance field, dense or sparse
  const double dist_unit = voxel * field.distance_step() / std::ldexp(1.0, 3 * device_->config().WB);
  const RigidPose& map_pose = a_in_b ? req.pose_b : req.pose_a;
  const Eigen::Matrix3d& Rm = a_in_b ? Rb : Ra;
  // Hits beyond the margin (speculative: PairOptions::speculative) are placed on the other surface.
  const bool speculative = speculative_reach(a_in_b ? req.a : req.b, a_in_b ? req.b : req.a, opt) > 0;
  for (size_t k = 0; k < n; ++k) {
    const uint32_t h = hits[k].hit, point = hits[k].point;
    Eigen::Vector3d position = R * points[point] + t;
    Eigen::Vector3d normal = R * normals[point];
    const double d = -double(cols.dist[h]) * dist_unit;
    // The field's gradient at the point, in the map's grid, to the world; negated, it points the way the shell
    // object's outward normal does at a contact.
    Eigen::Vector3d g = (Rm.transpose() * (position - map_pose.translation) - vm.origin()) / voxel;
    Eigen::Vector3d grad;
    std::array<uint32_t, 3> v = {cx[h], cy[h], cz[h]};
    if (speculative && -d > opt.margin)
      place_on_surface(field, vm, Rm, map_pose.translation, g, position, v, &grad);
    else
      field.distance_at(g, &grad);
    const Eigen::Vector3d nrm = -(Rm * grad);
    if (nrm.squaredNorm() > 1e-24) normal = nrm.normalized();
    to.put(k, point, position, normal, v[0], v[1], v[2], cols.state[h], d);
  }
}

template void PairCollider::make_contacts<detail::ToContacts>(const PairRequest&, uint32_t, bool,
                                                              const HitColumns&, const detail::SortedHit*, size_t,
                                                              const Eigen::Matrix3d&, const Eigen::Matrix3d&,
                                                              const PairOptions&, const detail::ToContacts&) const;
template void PairCollider::make_contacts<detail::ToArrays>(const PairRequest&, uint32_t, bool, const HitColumns&,
                                                            const detail::SortedHit*, size_t, const Eigen::Matrix3d&,
                                                            const Eigen::Matrix3d&, const PairOptions&,
                                                            const detail::ToArrays&) const;

}  // namespace voxcd
