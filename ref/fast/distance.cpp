// FastRunner on a distance voxmap (SB > 2): transform, floor and bounds in 64-bit integers (the double and int64
// paths' accumulators fit 63 bits; the wide path takes ref/'s transform), the 8 node values from their parity banks,
// and the trilinear interpolation as three exact linear interpolations (docs/contract.md, "Distance voxmaps"):
// a * 2^WB + (b - a) * f, x then y then z, in 64-bit integers and in 128 bits for the last step when IW > 62.
#include <cstdint>

#include "voxcd/ref/fast/fast.h"
#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

// Exact a * 2^wb + (b - a) * f = a * (2^wb - f) + b * f.
template <class T>
inline T lerp(T a, T b, int64_t f, int wb) {
  return a * (T{1} << wb) + (b - a) * T(f);
}

}  // namespace

void FastRunner::run_distance_chunk(const Job& j, uint32_t begin, uint32_t end, std::vector<Record>& hits,
                                    uint32_t& hit_count) const {
  const int tf = cfg_.TF(), wb = cfg_.WB, sb = cfg_.SB;
  const int64_t fmask = (int64_t{1} << wb) - 1;
  const uint64_t vmask = (uint64_t{1} << sb) - 1, sign = uint64_t{1} << (sb - 1);
  int npw_bits = 0;
  while ((1 << npw_bits) < cfg_.nodes_per_word()) ++npw_bits;
  const uint64_t slot_mask = (uint64_t{1} << npw_bits) - 1;
  const int64_t n[3] = {int64_t(j.nx), int64_t(j.ny), int64_t(j.nz)};
  const uint64_t hx = (uint64_t{j.nx} >> 1) + 1, hy = (uint64_t{j.ny} >> 1) + 1;
  const uint64_t* map = map_.data() + j.map_base;
  const bool wide_d = cfg_.IW() > 62;
  for (uint32_t k = begin; k < end; ++k) {
    const ShellWord& p = shell_[size_t(j.shell_base) + k];
    int64_t idx[3], f[3];
    bool inside = true;
    if (path_ == Path::Wide) {
      const Transformed t = transform(cfg_, j, p);
      for (int i = 0; i < 3; ++i) {
        const Acc a = t.acc[i] >> tf;
        inside &= a >= 0 && a < Acc(n[i]);
        idx[i] = inside ? int64_t(a) : 0;
        f[i] = int64_t((t.acc[i] >> (tf - wb)) & Acc(fmask));
      }
    } else {
      for (int i = 0; i < 3; ++i) {
        const int64_t a = j.t[i] + j.M[i][0] * p.x + j.M[i][1] * p.y + j.M[i][2] * p.z;  // fits 63 bits
        idx[i] = a >> tf;
        inside &= idx[i] >= 0 && idx[i] < n[i];
        f[i] = (a >> (tf - wb)) & fmask;
      }
    }
    if (!inside) continue;
    // q[dx | dy << 1 | dz << 2] for node (x + dx, y + dy, z + dz).
    int64_t q[8];
    for (int c = 0; c < 8; ++c) {
      const uint64_t X = uint64_t(idx[0]) + (c & 1), Y = uint64_t(idx[1]) + (c >> 1 & 1),
                     Z = uint64_t(idx[2]) + (c >> 2 & 1);
      const uint64_t h = (X >> 1) + hx * ((Y >> 1) + hy * (Z >> 1));
      const uint64_t bank = (X & 1) | (Y & 1) << 1 | (Z & 1) << 2;
      const uint64_t raw = (map[8 * (h >> npw_bits) + bank] >> (uint64_t(sb) * (h & slot_mask))) & vmask;
      q[c] = int64_t(raw ^ sign) - int64_t(sign);
    }
    const int64_t a0 = lerp<int64_t>(q[0], q[1], f[0], wb), a1 = lerp<int64_t>(q[2], q[3], f[0], wb);
    const int64_t a2 = lerp<int64_t>(q[4], q[5], f[0], wb), a3 = lerp<int64_t>(q[6], q[7], f[0], wb);
    const int64_t b0 = lerp<int64_t>(a0, a1, f[1], wb), b1 = lerp<int64_t>(a2, a3, f[1], wb);
    const int64_t d = wide_d ? int64_t(lerp<__int128>(b0, b1, f[2], wb)) : lerp<int64_t>(b0, b1, f[2], wb);
    if (d > j.threshold) continue;
    ++hit_count;
    if (j.mode == Mode::Count) continue;
    Record& r = hits.emplace_back();
    r.kind = Record::Hit;
    r.tag = j.tag;
    r.point = k;
    r.x = uint32_t(idx[0]);
    r.y = uint32_t(idx[1]);
    r.z = uint32_t(idx[2]);
    r.dist = d;
    if (j.mode == Mode::First) return;
  }
}

}  // namespace voxcd
