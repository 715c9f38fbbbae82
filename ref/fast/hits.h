// Hit records in columns: what FastRunner hands a host that turns hits into contacts (PairCollider), with no
// Record (88 bytes, its optional fields) per hit; and what one job of such a run gave.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxcd/ref/timing.h"
#include "voxcd/ref/types.h"

namespace voxcd {

// Hit k (k < size()) is point[k] (relative to its job's shell_base), in voxel (x[k], y[k], z[k]) of state state[k]
// (0 on a distance voxmap) and, on a distance voxmap, interpolated distance dist[k] (else 0): the fields of a hit
// Record. The columns keep their capacity: clear() and a run of as many hits again allocate nothing.
struct HitColumns {
  std::vector<uint32_t> point, x, y, z;
  std::vector<uint8_t> state;
  std::vector<int64_t> dist;

  size_t size() const { return n_; }
  void clear() { n_ = 0; }
  // Room for `more` hits after those held, so that put() need not check.
  void reserve_more(size_t more) {
    if (n_ + more <= point.size()) return;
    const size_t cap = std::max(n_ + more, 2 * point.size() + 64);
    point.resize(cap), x.resize(cap), y.resize(cap), z.resize(cap), state.resize(cap), dist.resize(cap);
  }
  // Appends a hit (reserve_more first).
  void put(uint32_t p, uint32_t vx, uint32_t vy, uint32_t vz, uint8_t st, int64_t d) {
    point[n_] = p, x[n_] = vx, y[n_] = vy, z[n_] = vz, state[n_] = st, dist[n_] = d;
    ++n_;
  }
  // Raw pointers to the columns from the first free row (reserve_more first), for a writer's tight loop; commit(n)
  // then takes the n rows written as hits. (Stores through one column's pointer cannot move the others, as the
  // vectors' own pointers could be reloaded after every byte store of put().)
  struct Rows {
    uint32_t *point, *x, *y, *z;
    uint8_t* state;
    int64_t* dist;
  };
  Rows rows() {
    return {point.data() + n_, x.data() + n_, y.data() + n_, z.data() + n_, state.data() + n_, dist.data() + n_};
  }
  void commit(size_t n) { n_ += n; }
  // Appends hits [from, from + n) of `o`.
  void append(const HitColumns& o, size_t from, size_t n) {
    reserve_more(n);
    const auto at = std::ptrdiff_t(n_), b = std::ptrdiff_t(from), e = std::ptrdiff_t(from + n);
    std::copy(o.point.begin() + b, o.point.begin() + e, point.begin() + at);
    std::copy(o.x.begin() + b, o.x.begin() + e, x.begin() + at);
    std::copy(o.y.begin() + b, o.y.begin() + e, y.begin() + at);
    std::copy(o.z.begin() + b, o.z.begin() + e, z.begin() + at);
    std::copy(o.state.begin() + b, o.state.begin() + e, state.begin() + at);
    std::copy(o.dist.begin() + b, o.dist.begin() + e, dist.begin() + at);
    n_ += n;
  }
  // Appends the hit record `r`.
  void append(const Record& r) {
    reserve_more(1);
    put(r.point, r.x, r.y, r.z, r.state, r.dist);
  }
  // Hit k as a Record of job `tag`.
  Record record(size_t k, uint32_t tag) const { return Record::hit(tag, point[k], x[k], y[k], z[k], state[k], dist[k]); }

 private:
  size_t n_ = 0;
};

// What one job of a run gave: its hits [first, first + records) in the run's columns, its completion record's hits
// (FIRST: 0 or 1; COUNT: the count, with no hit held) and, where the device models time, its cycles and its span on
// the stream's clock (ref/timing.h), the run timed as a stream of its own.
struct JobOutcome {
  size_t first = 0, records = 0;
  uint32_t hits = 0;
  uint64_t cycles = 0;
  JobSpan span;
};

}  // namespace voxcd
