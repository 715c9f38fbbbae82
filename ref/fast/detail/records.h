// Internal to FastRunner: records emitted into a stream: a record appended in place, a piece's hit columns appended
// as hit records.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxcd/ref/fast/hits.h"
#include "voxcd/ref/types.h"

namespace voxcd::detail {

// A record appended in place: a Record returned by value and then copied costs a store-forwarding stall per hit.
inline Record& push_record(std::vector<Record>& out, Record::Kind kind, uint32_t tag) {
  Record& r = out.emplace_back();
  r.kind = kind;
  r.tag = tag;
  return r;
}

// Hits [from, end) of `c` appended to `out` as hit records of job `tag`.
inline void append_records(const HitColumns& c, size_t from, uint32_t tag, std::vector<Record>& out) {
  for (size_t k = from; k < c.size(); ++k) {
    Record& r = push_record(out, Record::Hit, tag);
    r.point = c.point[k], r.x = c.x[k], r.y = c.y[k], r.z = c.z[k], r.state = c.state[k], r.dist = c.dist[k];
  }
}

}  // namespace voxcd::detail
