// Where PairCollider::make_contacts (host/pairs/contacts.cpp) writes contact k of a run of hits: a Contact of
// a PairResult, or row k of ContactArrays. Both are filled field by field from the same values, so the two forms of a
// batch's contacts are the same numbers. A run's contacts share their pair and direction (run(), once a run).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "voxcd/host/pairs/collider.h"

namespace voxcd::detail {

struct ToContacts {
  Contact* to;
  ToContacts shifted(size_t k) const { return {to + k}; }
  void run(size_t n, uint32_t pair, bool a_in_b) const {
    for (size_t k = 0; k < n; ++k) to[k].pair = pair, to[k].a_in_b = a_in_b;
  }
  void put(size_t k, uint32_t point, const Eigen::Vector3d& position, const Eigen::Vector3d& normal, uint32_t vx,
           uint32_t vy, uint32_t vz, uint8_t state, double depth) const {
    Contact& c = to[k];
    c.point = point;
    c.position = position;
    c.normal = normal;
    c.voxel = {vx, vy, vz};
    c.state = state;
    c.depth = depth;
  }
};

// Rows from `at` of the arrays, which hold room for them; raw pointers, so that the byte stores of a row need not
// reload the arrays' own pointers.
struct ToArrays {
  uint32_t *pair, *point, *voxel;
  uint8_t *a_in_b, *state;
  double *position, *normal, *depth;
  ToArrays(ContactArrays& a, size_t at)
      : pair(a.pair.data() + at), point(a.point.data() + at), voxel(a.voxel.data() + 3 * at),
        a_in_b(a.a_in_b.data() + at), state(a.state.data() + at), position(a.position.data() + 3 * at),
        normal(a.normal.data() + 3 * at), depth(a.depth.data() + at) {}
  ToArrays shifted(size_t k) const {
    ToArrays t = *this;
    t.pair += k, t.point += k, t.voxel += 3 * k, t.a_in_b += k, t.state += k;
    t.position += 3 * k, t.normal += 3 * k, t.depth += k;
    return t;
  }
  void run(size_t n, uint32_t p, bool in) const {
    std::fill(pair, pair + n, p);
    std::fill(a_in_b, a_in_b + n, uint8_t(in));
  }
  void put(size_t k, uint32_t pt, const Eigen::Vector3d& pos, const Eigen::Vector3d& nrm, uint32_t vx, uint32_t vy,
           uint32_t vz, uint8_t st, double d) const {
    point[k] = pt;
    double* p = position + 3 * k;
    double* n = normal + 3 * k;
    uint32_t* v = voxel + 3 * k;
    p[0] = pos.x(), p[1] = pos.y(), p[2] = pos.z();
    n[0] = nrm.x(), n[1] = nrm.y(), n[2] = nrm.z();
    v[0] = vx, v[1] = vy, v[2] = vz;
    state[k] = st;
    depth[k] = d;
  }
};

}  // namespace voxcd::detail
