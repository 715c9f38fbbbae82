#include "voxcd/host/scene/exchange.h"

#include <algorithm>

namespace voxcd {

std::vector<PairOutcome> merge_outcomes(const std::vector<std::vector<PairOutcome>>& per_rank) {
  std::vector<PairOutcome> all;
  for (const auto& v : per_rank) all.insert(all.end(), v.begin(), v.end());
  std::sort(all.begin(), all.end(),
            [](const PairOutcome& x, const PairOutcome& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  return all;
}

}  // namespace voxcd
