#include "voxcd/host/scene/exchange.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <stdexcept>

namespace voxcd {

std::vector<PairOutcome> merge_outcomes(const std::vector<std::vector<PairOutcome>>& per_rank) {
  std::vector<PairOutcome> all;
  for (const auto& v : per_rank) all.insert(all.end(), v.begin(), v.end());
  std::sort(all.begin(), all.end(),
            [](const PairOutcome& x, const PairOutcome& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  return all;
}

std::string slab_text(const Slabs& s, int rank) {
  std::ostringstream o;
  o.precision(6);
  o << "slab " << rank << " of " << s.ranks() << " (" << "xyz"[s.axis] << " in [";
  if (rank == 0) o << "-inf"; else o << s.cuts[size_t(rank - 1)];
  o << ", ";
  if (rank + 1 >= s.ranks()) o << "inf"; else o << s.cuts[size_t(rank)];
  o << "))";
  return o.str();
}

namespace {
constexpr uint64_t kMagic = 0x766f7863646f7574ull;  // "voxcdout"
constexpr size_t kOutcomeBytes = 2 * 4 + 4 * 8 + 3 * 8;

template <typename T>
void put(std::string& s, T v) {
  s.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <typename T>
T take(const std::string& s, size_t& at) {
  if (at + sizeof(T) > s.size()) throw std::runtime_error("an outcome message ends early");
  T v;
  std::memcpy(&v, s.data() + at, sizeof v);
  at += sizeof v;
  return v;
}
}  // namespace

std::string encode_outcomes(uint64_t frame, const RankCounts& c, const std::vector<PairOutcome>& outcomes) {
  std::string s;
  s.reserve(6 * 8 + outcomes.size() * kOutcomeBytes);
  put(s, kMagic), put(s, frame), put(s, c.pairs), put(s, c.tested), put(s, c.cycles), put(s, uint64_t(outcomes.size()));
  for (const PairOutcome& o : outcomes) {
    put(s, o.a), put(s, o.b), put(s, o.hits), put(s, o.lookups), put(s, o.contacts), put(s, o.cycles);
    put(s, o.normal.x()), put(s, o.normal.y()), put(s, o.normal.z());
  }
  return s;
}

void decode_outcomes(const std::string& s, uint64_t& frame, RankCounts& c, std::vector<PairOutcome>& outcomes) {
  size_t at = 0;
  if (take<uint64_t>(s, at) != kMagic) throw std::runtime_error("a message that is not a rank's outcomes");
  frame = take<uint64_t>(s, at);
  c.pairs = take<uint64_t>(s, at), c.tested = take<uint64_t>(s, at), c.cycles = take<uint64_t>(s, at);
  const uint64_t n = take<uint64_t>(s, at);
  if (n > (s.size() - at) / kOutcomeBytes) throw std::runtime_error("an outcome message ends early");
  outcomes.resize(size_t(n));
  for (PairOutcome& o : outcomes) {
    o.a = take<uint32_t>(s, at), o.b = take<uint32_t>(s, at);
    o.hits = take<uint64_t>(s, at), o.lookups = take<uint64_t>(s, at), o.contacts = take<uint64_t>(s, at);
    o.cycles = take<uint64_t>(s, at);
    const double x = take<double>(s, at), y = take<double>(s, at), z = take<double>(s, at);
    o.normal = Eigen::Vector3d(x, y, z);
  }
  if (at != s.size()) throw std::runtime_error("an outcome message has trailing bytes");
}

}  // namespace voxcd
