// A batch's contacts in flat arrays (internal to host): what PairCollider::collide writes for callers that hand
// contacts on as arrays or query every frame.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxcd/host/pairs/contact.h"

namespace voxcd {

// Every contact of a batch in flat arrays, one row per contact (the fields of Contact), pair i's rows at
// [first[i], first[i + 1]) in the order PairResult::contacts has them: for callers that hand contacts on as arrays
// (the Python module's numpy arrays) or query every frame. The arrays keep their capacity from batch to batch, so a
// query allocates nothing once they have grown.
struct ContactArrays {
  std::vector<uint64_t> first;              // per pair its first row, then one past the last row
  std::vector<uint32_t> hits;               // per pair, PairResult::hits
  std::vector<uint64_t> lookups, device_cycles;  // per pair, PairResult::lookups and device_cycles
  std::vector<uint32_t> pair, point;        // per row
  std::vector<uint8_t> a_in_b, state;       // per row
  std::vector<double> position, normal;     // per row x, y, z (3 values a row)
  std::vector<uint32_t> voxel;              // per row x, y, z
  std::vector<double> depth;                // per row

  size_t size() const { return point.size(); }  // rows
  size_t pairs() const { return hits.size(); }
  // Row k as a Contact.
  Contact contact(size_t k) const;
  // Sizes every array for `pairs` pairs and `rows` rows (what a batch writes; the values are left to it).
  void resize(size_t pairs, size_t rows);
};

}  // namespace voxcd
