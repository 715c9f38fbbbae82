#include "voxcd/ref/types.h"

#include <sstream>

namespace voxcd {

const char* mode_name(Mode m) {
  switch (m) {
    case Mode::All: return "ALL";
    case Mode::First: return "FIRST";
    case Mode::Count: return "COUNT";
  }
  return "?";
}

std::optional<Mode> parse_mode(const std::string& s) {
  if (s == "ALL") return Mode::All;
  if (s == "FIRST") return Mode::First;
  if (s == "COUNT") return Mode::Count;
  return std::nullopt;
}

Record Record::hit(uint32_t tag, uint32_t point, uint32_t x, uint32_t y, uint32_t z, uint8_t state, int64_t dist) {
  Record r;
  r.kind = Hit;
  r.tag = tag;
  r.point = point;
  r.x = x;
  r.y = y;
  r.z = z;
  r.state = state;
  r.dist = dist;
  return r;
}

Record Record::done(uint32_t tag, uint32_t hits, std::optional<uint64_t> cycles) {
  Record r;
  r.kind = Done;
  r.tag = tag;
  r.hits = hits;
  r.cycles = cycles;
  return r;
}

bool Record::same_as(const Record& o, bool compare_cycles) const {
  if (kind != o.kind || tag != o.tag) return false;
  if (kind == Hit) return point == o.point && x == o.x && y == o.y && z == o.z && state == o.state && dist == o.dist;
  if (hits != o.hits) return false;
  if (compare_cycles && cycles && o.cycles && *cycles != *o.cycles) return false;
  return true;
}

std::string Record::to_string(bool with_dist) const {
  std::ostringstream s;
  if (kind == Hit) {
    s << "hit " << tag << ' ' << point << ' ' << x << ' ' << y << ' ' << z << ' ' << unsigned(state);
    if (with_dist) s << ' ' << dist;
  } else {
    s << "done " << tag << ' ' << hits;
    if (cycles) s << ' ' << *cycles;
  }
  return s.str();
}

}  // namespace voxcd
