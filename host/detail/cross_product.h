// The index-th element of a cross product of lists, as the campaign's shards and the sweep's points number them.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <vector>

namespace voxcd::detail {

// index's digits in the mixed radix `sizes`, the first varying fastest: digit k is index / (sizes[0] * ... *
// sizes[k-1]) mod sizes[k]. The last digit is not reduced, so that an index past the product shows in it.
inline std::vector<uint64_t> cross_product_digits(uint64_t index, std::initializer_list<uint64_t> sizes) {
  std::vector<uint64_t> digits;
  for (const uint64_t n : sizes) {
    const bool last = digits.size() + 1 == sizes.size();
    digits.push_back(last ? index : index % n);
    if (!last) index /= n;
  }
  return digits;
}

}  // namespace voxcd::detail
