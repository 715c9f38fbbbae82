// Where PairCollider::make_contacts (host/pairs/contacts.cpp) writes contact k of a run of hits: a Contact of
// a PairResult, or row k of ContactArrays. Both are filled field by field from the same values, so the two forms of a
// batch's contacts are the same numbers.
#pragma once

#include <cstddef>
#include <cstdint>

#include "voxcd/host/pairs/collider.h"

namespace voxcd::detail {

struct ToContacts {
  Contact* to;
  ToContacts shifted(size_t k) const { return {to + k}; }
  void put(size_t k, uint32_t pair, bool a_in_b, uint32_t point, const Eigen::Vector3d& position,
           const Eigen::Vector3d& normal, const HitColumns& h, size_t hit, double depth) const {
    Contact& c = to[k];
    c.pair = pair;
    c.a_in_b = a_in_b;
    c.point = point;
    c.position = position;
    c.normal = normal;
    c.voxel = {h.x[hit], h.y[hit], h.z[hit]};
    c.state = h.state[hit];
    c.depth = depth;
  }
};

// Row `at + k` of the arrays, which hold room for it.
struct ToArrays {
  ContactArrays* a;
  size_t at;
  ToArrays shifted(size_t k) const { return {a, at + k}; }
  void put(size_t k, uint32_t pair, bool a_in_b, uint32_t point, const Eigen::Vector3d& position,
           const Eigen::Vector3d& normal, const HitColumns& h, size_t hit, double depth) const {
    const size_t i = at + k;
    a->pair[i] = pair;
    a->a_in_b[i] = a_in_b;
    a->point[i] = point;
    double* p = a->position.data() + 3 * i;
    double* n = a->normal.data() + 3 * i;
    uint32_t* v = a->voxel.data() + 3 * i;
    p[0] = position.x(), p[1] = position.y(), p[2] = position.z();
    n[0] = normal.x(), n[1] = normal.y(), n[2] = normal.z();
    v[0] = h.x[hit], v[1] = h.y[hit], v[2] = h.z[hit];
    a->state[i] = h.state[hit];
    a->depth[i] = depth;
  }
};

}  // namespace voxcd::detail
