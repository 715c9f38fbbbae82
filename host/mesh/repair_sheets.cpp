// repair()'s sheets (detail/repair_steps.h): the parts that enclose nothing, grouped across cracks.
#include "voxcd/host/mesh/detail/repair_steps.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <map>
#include <unordered_map>

#include "voxcd/host/mesh/detail/cells.h"
#include "voxcd/host/mesh/detail/edge_uses.h"
#include "voxcd/host/mesh/detail/point_hash.h"
#include "voxcd/host/mesh/ray_crossing.h"
#include "voxcd/host/mesh/detail/union_find.h"


namespace voxcd::detail::mesh_repair {

using detail::EdgeUse;
using detail::UnionFind;
using detail::edge_uses;

namespace {

// A hole whose fill has more than this fraction of its part's area makes the part a sheet (docs/objects.md).
constexpr double kSheetRatio = 0.4;
// Open parts whose boundaries come this close (relative to the model's size) close each other (cracks).
constexpr double kCrackRelative = 1e-2;

// The patches grouped with the open patches whose boundary vertices come within `gap` of theirs (parts split by
// cracks close each other); resolved parts' fins (resolved 2) are left alone.
UnionFind group_by_cracks(const Mesh& m, const Patches& p, const std::vector<EdgeUse>& after, double gap) {
  UnionFind group{p.list.size()};
  std::unordered_map<std::array<int64_t, 3>, std::vector<std::pair<uint32_t, uint32_t>>, CellKeyHash> cells;
  auto key_of = [&](const Eigen::Vector3d& x) {
    std::array<int64_t, 3> k{};
    for (int a = 0; a < 3; ++a) k[a] = int64_t(std::floor(x[a] / gap));
    return k;
  };
  for (size_t i = 0; i < after.size();) {
    size_t j = i;
    while (j < after.size() && after[j].key == after[i].key) ++j;
    const uint32_t q = p.of[after[i].tri];
    if (j - i == 1 && p.resolved[q] != 2) {
      for (uint32_t v : {uint32_t(after[i].key >> 32), uint32_t(after[i].key)}) {
        const auto k = key_of(m.vertices[v]);
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              const auto it = cells.find({k[0] + dx, k[1] + dy, k[2] + dz});
              if (it == cells.end()) continue;
              for (const auto& [w, o] : it->second)
                if (o != q && (m.vertices[w] - m.vertices[v]).norm() <= gap) group.unite(q, o);
            }
        cells[k].push_back({v, q});
      }
    }
    i = j;
  }
  return group;
}

}  // namespace

// Sheets: patches grouped with the open patches whose boundary vertices come within kCrackRelative of the model's size
// of theirs (parts split by cracks close each other); a group whose boundary encloses more than kSheetRatio of
// its area (the vector area of its boundary loops, origin-independent for closed loops) encloses nothing. A
// resolved part's fins are sheets whatever their boundary.
void mark_sheets(Mesh& m, const Patches& p, const std::vector<EdgeUse>& after, const std::vector<char>& closed,
                 const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, MeshReport& r) {
  const size_t n = m.size(), np = p.list.size();
  UnionFind group = group_by_cracks(m, p, after, kCrackRelative * (hi - lo).norm());
  std::vector<Eigen::Vector3d> loop_area(np, Eigen::Vector3d::Zero());
  std::vector<double> area(np, 0);
  const Eigen::Vector3d centre = (lo + hi) / 2;
  for (size_t t = 0; t < n; ++t) {
    const uint32_t g = group.find(p.of[t]);
    const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    area[g] += (b - a).cross(c - a).norm() / 2;
    // The vector area of the triangle's edges as part of the boundary chain: the boundary's is the sum over every
    // triangle of its own (inner edges cancel).
    loop_area[g] += ((a - centre).cross(b - centre) + (b - centre).cross(c - centre) + (c - centre).cross(a - centre)) / 2;
  }
  std::vector<char> sheet_group(np, 0);
  for (size_t q = 0; q < np; ++q) {
    const uint32_t g = group.find(uint32_t(q));
    if (g != q) continue;
    // The triangles' own vector areas sum to the boundary's: for a closed group it is zero up to rounding.
    sheet_group[g] = loop_area[g].norm() > kSheetRatio * area[g];
  }
  auto is_sheet = [&](uint32_t q) { return p.resolved[q] == 2 || sheet_group[group.find(q)]; };
  m.sheet.assign(n, 0);
  bool any_solid = false;
  for (size_t t = 0; t < n; ++t) {
    m.sheet[t] = is_sheet(p.of[t]);
    any_solid |= !m.sheet[t];
  }
  for (uint32_t q = 0; q < np; ++q) {
    if (closed[q]) ++r.closed_components;
    if (is_sheet(q)) ++r.sheet_components;
  }
  if (!any_solid) r.surface_only = true;
  if (std::none_of(m.sheet.begin(), m.sheet.end(), [](uint8_t s) { return s != 0; })) m.sheet.clear();
}


}  // namespace voxcd::detail::mesh_repair
