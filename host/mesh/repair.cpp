// repair(): a triangle soup as real exports give it, made into the best surface it allows, and reported. The
// steps, in order (docs/objects.md, "Repair"): drop triangles with a non-finite corner, weld vertices within
// kWeldRelative of the model's size, drop degenerate triangles and exact duplicates, orient each part
// consistently, orient parts outward (nested closed parts keep the orientation they were given, so cavities stay
// cavities), and mark the parts that enclose nothing as sheets.

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

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/mesh/detail/repair_steps.h"

namespace voxcd {

namespace {

using detail::EdgeUse;
using detail::UnionFind;
using detail::edge_uses;
using namespace detail::mesh_repair;

// Drops the vertices no triangle uses any more (of dropped triangles, or moved by welding).
void drop_unused_vertices(Mesh& m) {
  std::vector<uint32_t> to(m.vertices.size(), UINT32_MAX);
  for (const auto& t : m.triangles)
    for (uint32_t v : t) to[v] = 0;
  std::vector<Eigen::Vector3d> kept;
  for (size_t v = 0; v < m.vertices.size(); ++v)
    if (to[v] == 0) {
      to[v] = uint32_t(kept.size());
      kept.push_back(m.vertices[v]);
    }
  for (auto& t : m.triangles)
    for (uint32_t& v : t) v = to[v];
  m.vertices = std::move(kept);
}

size_t count_components(const Mesh& m) {
  UnionFind parts{m.size()};
  const std::vector<EdgeUse> uses = edge_uses(m);
  for (size_t i = 1; i < uses.size(); ++i)
    if (uses[i].key == uses[i - 1].key) parts.unite(uses[i - 1].tri, uses[i].tri);
  size_t c = 0;
  for (uint32_t t = 0; t < m.size(); ++t) c += parts.find(t) == t;
  return c;
}

// Makes a point cloud of the mesh's finite vertices (or of `corners`, when given) and reports it.
MeshReport& to_point_cloud(Mesh& m, MeshReport& r, const std::vector<uint32_t>* corners) {
  if (corners) {
    std::vector<char> used(m.vertices.size(), 0);
    for (uint32_t v : *corners) used[v] = 1;
    std::vector<Eigen::Vector3d> pts;
    for (size_t v = 0; v < m.vertices.size(); ++v)
      if (used[v]) pts.push_back(m.vertices[v]);
    m.vertices = std::move(pts);
  }
  r.points_only = r.surface_only = true;
  r.vertices = m.vertices.size();
  m.sheet.clear();
  return r;
}

// The bounding box of the vertices the triangles use (of the finite vertices for a point cloud); MeshError when
// nothing finite is left.
void finite_bounds(const Mesh& m, const MeshReport& r, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  lo = Eigen::Vector3d::Constant(HUGE_VAL);
  hi = -lo;
  auto grow = [&](const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  if (!m.triangles.empty()) {
    for (const auto& t : m.triangles)
      for (uint32_t v : t) grow(m.vertices[v]);
  } else {
    for (const auto& p : m.vertices)
      if (p.allFinite()) grow(p);
  }
  if (lo.allFinite()) return;
  if (r.input_triangles)
    throw MeshError(m.name + ": none of the mesh's " + std::to_string(r.input_triangles) +
                    " triangles has finite corners");
  throw MeshError(m.name + (m.vertices.empty() ? ": the file holds no triangles and no points"
                                               : ": the file holds no triangles and no finite points"));
}

}  // namespace

MeshReport repair(Mesh& m) {
  MeshReport r;
  r.input_vertices = m.vertices.size();
  r.input_triangles = m.triangles.size();
  for (size_t t = 0; t < m.size(); ++t)
    for (uint32_t v : m.triangles[t])
      if (v >= m.vertices.size())
        throw MeshError(m.name + ": triangle " + std::to_string(t) + " has vertex index " + std::to_string(v) +
                        " out of range (" + std::to_string(m.vertices.size()) + " vertices)");
  r.dropped_nonfinite = drop_nonfinite(m);
  const bool had_triangles = !m.triangles.empty();
  Eigen::Vector3d lo, hi;
  finite_bounds(m, r, lo, hi);
  r.weld_tolerance = kWeldRelative * (hi - lo).norm();
  size_t near = 0;
  r.welded = weld_near(m, r.weld_tolerance, &near);
  r.welded_near = near;
  if (!had_triangles) return to_point_cloud(m, r, nullptr);
  std::vector<uint32_t> dropped_corners;  // corners of every triangle, in case none survives
  for (const auto& t : m.triangles) dropped_corners.insert(dropped_corners.end(), t.begin(), t.end());
  drop_degenerate_and_duplicates(m, r);
  // Every triangle was a point or a segment: what is left is its corners, a point cloud.
  if (m.triangles.empty()) return to_point_cloud(m, r, &dropped_corners);

  // Cracks between parts: open edges of different parts within kCrackCloseRelative of the model's size are
  // joined (counted as welded within tolerance), and what that makes degenerate or duplicate is dropped.
  std::vector<EdgeUse> uses = edge_uses(m);
  if (const size_t moved = close_cracks(m, uses, kCrackCloseRelative * (hi - lo).norm())) {
    r.welded += moved;
    r.welded_near += moved;
    near += moved;
    drop_degenerate_and_duplicates(m, r);
    uses = edge_uses(m);
  }
  const CellDecision cells = resolve_nonmanifold(m, uses, r);
  if (r.dropped_internal) uses = edge_uses(m);
  Patches patches = orient_patches(m, uses, cells);
  std::vector<EdgeUse> after = std::move(uses);  // the same edges; a reversed triangle runs each the other way
  const std::vector<char> closed = closed_patches(after, patches, r);
  const size_t reversed = orient_outward(m, patches, closed);
  if (reversed == m.size())
    r.flipped = true;
  else
    r.reoriented = reversed;
  mark_sheets(m, patches, after, closed, lo, hi, r);
  r.components = count_components(m);
  drop_unused_vertices(m);
  r.vertices = m.vertices.size();
  r.triangles = m.triangles.size();
  r.closed = near == 0 && r.dropped_nonfinite == 0 && r.dropped_repeated == 0 && r.dropped_collinear == 0 &&
             r.dropped_duplicate == 0 && r.open_edges == 0 && r.nonmanifold_edges == 0 &&
             r.inconsistent_edges == 0 && r.reoriented == 0;
  return r;
}

}  // namespace voxcd
