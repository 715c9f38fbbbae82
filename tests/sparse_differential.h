// The differential check of tests/differential.h for sparse distance voxmaps with refined bricks, on ref's sparse
// device (tests/sparse_pairs.h): at each of PairCheck's poses (FCL's truth, the 2-bit and dense distance answers),
// the sparse device's contacts (both directions, margin 0), each against the other mesh's exact surface (the nearest
// triangle's distance; inside by the model's solid, or within the bound of voxcd's own solid, which fills a hole across
// its rim, docs/objects.md), and the sparse device's misses measured as PairCheck measures its own (the translational
// penetration depth).
#pragma once

#include "tests/differential.h"
#include "tests/exact_geometry.h"
#include "tests/sparse_pairs.h"
#include "voxcd/host/object/detail/solid.h"

namespace voxcd::test::diff {

// The goal of refined bricks (docs/pairs.md): every contact inside the other object or within this many voxels of
// its surface.
constexpr double kContactBoundSparse = 0.25;

// An L-shaped block: the outline (0,0) (3,0) (3,1) (1,1) (1,3) (0,3) extruded over z in [0, 1], a closed mesh with one
// concave crease (x = y = 1); with the built-in torus at voxel 0.25, the case of issue 40.
inline Mesh l_block() {
  const double xy[6][2] = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  Mesh m;
  for (double z : {0.0, 1.0})
    for (const auto& p : xy) m.vertices.emplace_back(p[0], p[1], z);
  // Caps: the outline as the rectangles (0,0)-(3,1) and (0,1)-(1,3); bottom faces down, top faces up.
  const uint32_t quads[2][4] = {{0, 1, 2, 3}, {0, 3, 4, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[2], q[1]});
    m.triangles.push_back({q[0], q[3], q[2]});
    m.triangles.push_back({q[0] + 6, q[1] + 6, q[2] + 6});
    m.triangles.push_back({q[0] + 6, q[2] + 6, q[3] + 6});
  }
  for (uint32_t i = 0; i < 6; ++i) {
    const uint32_t j = (i + 1) % 6;
    m.triangles.push_back({i, j, j + 6});
    m.triangles.push_back({i, j + 6, i + 6});
  }
  m.name = "an L-shaped block";
  return m;
}

// A closed mesh as a model whose solid is itself.
inline Model solid_model(const Mesh& m) {
  Model r;
  r.name = m.name;
  r.mesh = m;
  r.solid = {m};
  r.known_solid = true;
  return r;
}

// Contacts against closed meshes by brute force (tests/exact_geometry.h: every triangle's distance, ray parity).
struct ExactContacts {
  size_t poses = 0, touching = 0, contacts = 0, beyond = 0, depth_checked = 0, depth_off = 0;
  double worst = -HUGE_VAL, worst_depth_error = 0;
  // Per contact: voxels outside (0 inside); in the band, |depth - exact| (voxels), and within 1/2 voxel of the surface
  // the angle (degrees) between the contact's normal and the exact one (the exact distance's gradient, negated).
  std::vector<double> outside, depth_error, normal_error;
};

// The closed meshes a pair's contacts are measured against: the meshes, and for the normals their trees and
// pseudo-normals.
struct ExactPair {
  ExactPair(const Mesh& a, const Mesh& b)
      : mesh{a, b},
        tree{{a.vertices, a.triangles}, {b.vertices, b.triangles}},
        normals{{a.vertices, a.triangles}, {b.vertices, b.triangles}} {}
  Mesh mesh[2];
  detail::TriangleTree tree[2];
  detail::PseudoNormals normals[2];
};

// Each contact's signed distance to the other closed mesh (A at the origin, B at pb) by brute force, in voxels; with
// band > 0, where the contact's cell lies within the band (the point 2 voxels inside its edge), its depth against
// that distance (counted off beyond depth_bound) and its normal against the exact one.
inline void measure_contacts(const std::vector<Contact>& cs, const ExactPair& x, const RigidPose& pb, double voxel,
                             ExactContacts& e, double band = 0, double depth_bound = 0.5) {
  ++e.poses;
  e.touching += !cs.empty();
  e.contacts += cs.size();
  for (const Contact& c : cs) {
    const int k = c.a_in_b ? 1 : 0;
    const RigidPose po = k ? pb : RigidPose();
    const Eigen::Vector3d local = po.rotation.conjugate() * (c.position - po.translation);
    const double u = test::mesh_distance(x.mesh[k], local) / voxel;
    const double d = test::inside_reference(x.mesh[k], local) ? -u : u;
    e.worst = std::max(e.worst, d);
    e.beyond += d > kContactBoundSparse;
    e.outside.push_back(std::max(0.0, d));
    // A speculative contact (depth below 0 at margin 0) lies on the other surface and carries the separation at its
    // shell point: its position is measured, its depth not.
    if (band > 0 && -d <= band - 2 && c.depth >= 0) {
      const double err = std::abs(c.depth / voxel + d);
      e.depth_error.push_back(err);
      e.worst_depth_error = std::max(e.worst_depth_error, err);
      ++e.depth_checked;
      e.depth_off += err > depth_bound;
      if (std::abs(d) > 0.5) continue;  // deeper, near a medial surface the exact gradient turns at once
      // The exact field's gradient: away from the closest point (towards it inside), or on the surface the
      // pseudo-normal there; negated, as the contact's normal is.
      const detail::Closest cl = x.tree[k].closest(local);
      const Eigen::Vector3d away = local - cl.point;
      const Eigen::Vector3d grad =
          away.norm() > 1e-9 * voxel ? Eigen::Vector3d(away.normalized() * (d < 0 ? -1 : 1)) : x.normals[k].at(cl);
      const Eigen::Vector3d exact = -(po.rotation * grad);
      const double cosine = std::clamp(exact.dot(c.normal), -1.0, 1.0);
      e.normal_error.push_back(std::acos(cosine) * 180 / M_PI);
    }
  }
}

// The q-quantile of v (0 for none).
inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5))];
}

struct SparseOutcome {
  Outcome o;                                          // PairCheck's: truth, 2-bit, dense distance
  bool sparse = false;                                // the sparse device found a contact
  double depth = 0;                                   // a sparse miss: the translational penetration depth, voxels
  size_t contacts = 0, beyond = 0, conservative = 0;  // contacts; beyond kContactBoundSparse; by conservative cells
  size_t filled = 0;         // contacts beyond the bound from the mesh, inside voxcd's solid only or within the bound
                             // of it (a hole's filling, whose boundary no triangle bounds)
  double worst = -HUGE_VAL;  // the farthest contact outside the other surface, voxels (negative: all inside)
};

class SparseCheck {
 public:
  SparseCheck(const Model& a, const Model& b, uint32_t resolution) : check_(a, b, resolution) {
    const Model* m[2] = {&a, &b};
    for (int k = 0; k < 2; ++k) {
      mesh_[k] = m[k]->mesh;
      MeshReport rep = repair(mesh_[k]);
      obj_[k] = sparse::make_sparse_object(mesh_[k], m[k]->name, check_.voxel(), 3, &rep);
      tree_[k] = std::make_unique<detail::TriangleTree>(mesh_[k].vertices, mesh_[k].triangles);
      inside_[k] = std::make_unique<Inside>(*m[k]);
    }
    device_ = std::make_unique<sparse::SparseDevice>(std::vector<const sparse::SparseObject*>{&obj_[0], &obj_[1]});
  }

  PairCheck& pair_check() { return check_; }
  // The sparse device's contacts at the last pose checked.
  const std::vector<Contact>& contacts() const { return contacts_; }
  const sparse::SparseObject& object(int k) const { return obj_[k]; }

  SparseOutcome check(const RigidPose& pb) {
    SparseOutcome s;
    s.o = check_.check(pb);
    contacts_ = device_->collide(0, RigidPose(), 1, pb, true);
    const std::vector<Contact>& cs = contacts_;
    s.sparse = !cs.empty();
    s.contacts = cs.size();
    for (const Contact& c : cs) {
      const int k = c.a_in_b ? 1 : 0;  // the object whose field the contact read
      const RigidPose po = k == 1 ? pb : RigidPose();
      const Eigen::Vector3d local = po.rotation.conjugate() * (c.position - po.translation);
      double d = std::sqrt(tree_[k]->closest(local).d2) / check_.voxel();
      if (inside_[k]->depth(local) > 0) d = -d;
      // Beyond the bound from every triangle, a hole's filling (voxcd's solid) may still hold the contact.
      if (d > kContactBoundSparse && near_filling(k, local, kContactBoundSparse * check_.voxel())) d = -d, ++s.filled;
      s.worst = std::max(s.worst, d);
      s.beyond += d > kContactBoundSparse;
      s.conservative += obj_[k].field.near_conservative(sparse::grid_of(obj_[k], po, c.position));
    }
    if (s.o.truth && !s.sparse) s.depth = check_.penetration_depth(pb) / check_.voxel();
    return s;
  }

 private:
  // A level-3 node of object k's grid (where refined bricks take their signs) within r of p (object k's frame) that
  // lies in voxcd's own solid (the voxeliser's, detail/solid.h: the winding number with its caps): a contact by the
  // boundary of a hole's filling, which no triangle bounds.
  bool near_filling(int k, const Eigen::Vector3d& p, double r) const {
    const GridPlacement& vm = obj_[k].type->voxmap().grid();
    const double h = vm.voxel / 8;
    const Eigen::Vector3d first = ((p - vm.origin) / h).array().floor().matrix() - Eigen::Vector3d::Constant(2);
    GridPlacement g;
    g.voxel = h;
    g.origin = vm.origin + (first - Eigen::Vector3d::Constant(0.5)) * h;  // voxel centres on the nodes
    g.dims = {6, 6, 6};
    const std::vector<uint64_t> in = detail::solid_bits(mesh_[k], g, 1);
    for (uint64_t i = 0; i < 216; ++i) {
      const Eigen::Vector3d node =
          vm.origin + (first + Eigen::Vector3d(double(i % 6), double(i / 6 % 6), double(i / 36))) * h;
      if ((in[i >> 6] >> (i & 63) & 1) && (node - p).norm() <= r) return true;
    }
    return false;
  }

  PairCheck check_;
  Mesh mesh_[2];
  sparse::SparseObject obj_[2];
  std::unique_ptr<detail::TriangleTree> tree_[2];
  std::unique_ptr<Inside> inside_[2];
  std::unique_ptr<sparse::SparseDevice> device_;
  std::vector<Contact> contacts_;
};

// What a run of poses found in sparse mode.
struct SparseTally {
  uint64_t tp = 0, fn = 0, fp = 0, tn = 0;
  uint64_t missed_beyond = 0;      // misses deeper than kMissDepthDistance
  uint64_t missed_found_2bit = 0;  // misses the 2-bit voxmap found
  uint64_t contacts = 0, beyond = 0, conservative = 0, filled = 0;
  double worst_missed_depth = 0, worst_found_2bit_depth = 0, worst_contact = -HUGE_VAL;
  std::string worst_missed, worst_contact_at;
};

inline void tally(SparseTally& t, const SparseOutcome& s, const std::string& where) {
  if (s.o.truth && s.sparse) ++t.tp;
  if (!s.o.truth && !s.sparse) ++t.tn;
  if (!s.o.truth && s.sparse) ++t.fp;
  if (s.o.truth && !s.sparse) {
    ++t.fn;
    t.missed_beyond += s.depth > kMissDepthDistance;
    t.missed_found_2bit += s.o.voxcd[0];
    if (s.o.voxcd[0]) t.worst_found_2bit_depth = std::max(t.worst_found_2bit_depth, s.depth);
    if (s.depth > t.worst_missed_depth) t.worst_missed_depth = s.depth, t.worst_missed = where;
  }
  t.contacts += s.contacts;
  t.beyond += s.beyond;
  t.conservative += s.conservative;
  t.filled += s.filled;
  if (s.contacts && s.worst > t.worst_contact) t.worst_contact = s.worst, t.worst_contact_at = where;
}

}  // namespace voxcd::test::diff
