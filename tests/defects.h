// Defective meshes with known intended solids, for tests and benchmarks (tests/host/object/test_defects.cpp,
// bench/bench_voxelize.cpp): the defects real exports have (holes, flipped and duplicated triangles, degenerate
// triangles, overlapping closed parts, a non-manifold edge, cracks, cavities given the wrong orientation, sheets,
// point clouds), each built from closed meshes whose solid is known, with what repair() must report for it.
//
// The intended solid of a defect is the solid of the mesh before the defect was introduced: the union of the
// insides of `solid`'s closed meshes (each by its own parity, so a mesh with an inward inner shell has a cavity).
// Generators keep the repaired mesh's bounding box equal to the intended solid's wherever they can (holes never
// take every triangle of an extreme vertex; cracks move copies towards the centre and keep one copy of every vertex
// in place), so that both are voxelised on the same grid.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"

namespace voxcd::test {

// What repair() must report for a defect; -1 (or, for the flags, -1) leaves a field unchecked.
struct ExpectedReport {
  long long open_edges = -1, nonmanifold_edges = -1, dropped_duplicate = -1, dropped_repeated = -1,
            dropped_collinear = -1, reoriented = -1, welded = -1, components = -1, closed_components = -1,
            sheet_components = -1, triangles = -1, vertices = -1, nonmanifold_parts = -1, dropped_internal = -1,
            fin_triangles = -1;
  int closed = -1, flipped = -1, surface_only = -1, points_only = -1;
};

struct Defect {
  std::string name;
  Mesh mesh;                // the defective mesh as a file would hold it (neither welded nor repaired)
  std::vector<Mesh> solid;  // the intended solid: the union of these closed meshes' insides; empty: surface only
  double volume = std::numeric_limits<double>::quiet_NaN();  // the intended solid's exact volume, when known
  Mesh removed;             // punched meshes: the triangles taken out, on the intended mesh's vertices
  // The repaired mesh is the intended closed mesh itself (same vertices and triangles up to order): its voxmap must
  // equal the intended mesh's exactly.
  bool repairs_to_intended = false;
  ExpectedReport expect;
};

// ---------------------------------------------------------------------------------------------------------------
// Closed meshes.

// An icosphere of any subdivision level (20 * 4^level triangles: level 8 = 1,310,720), outward.
inline Mesh icosphere(int level, double radius = 1, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  Mesh m = make_icosphere(centre, radius, level);
  m.name = "icosphere level " + std::to_string(level);
  return m;
}

// Appends b's vertices and triangles to a.
inline void append(Mesh& a, const Mesh& b) {
  const uint32_t base = uint32_t(a.vertices.size());
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

inline Mesh reversed(Mesh m) {
  for (auto& t : m.triangles) std::swap(t[1], t[2]);
  return m;
}

// A ball with a spherical cavity: outer icosphere outward, inner (radius `inner`, off centre) inward.
inline Mesh hollow_sphere(int level, double inner = 0.5) {
  Mesh m = icosphere(level);
  append(m, reversed(icosphere(std::max(level - 1, 0), inner, Eigen::Vector3d(0.1, -0.05, 0.08))));
  m.name = "hollow sphere";
  return m;
}

// Vertices rounded to single precision (so that every format, including the float ones, stores them exactly).
inline Mesh to_float(Mesh m) {
  for (auto& v : m.vertices) v = v.cast<float>().cast<double>();
  return m;
}

// ---------------------------------------------------------------------------------------------------------------
// Topology of a mesh as given (vertex indices, no welding): the expected values of the report.

struct Topology {
  size_t open_edges = 0, nonmanifold_edges = 0, components = 0, used_vertices = 0;
};

inline Topology topology(const Mesh& m) {
  Topology r;
  std::vector<std::pair<uint64_t, uint32_t>> uses;
  uses.reserve(3 * m.size());
  for (size_t t = 0; t < m.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(t)});
    }
  std::sort(uses.begin(), uses.end());
  std::vector<uint32_t> parent(m.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (auto i = uses.begin(); i != uses.end();) {
    auto j = i;
    while (j != uses.end() && j->first == i->first) ++j;
    if (j - i == 1) ++r.open_edges;
    if (j - i > 2) ++r.nonmanifold_edges;
    for (auto k = i + 1; k != j; ++k) parent[find(k->second)] = find(i->second);
    i = j;
  }
  for (size_t t = 0; t < parent.size(); ++t) r.components += find(uint32_t(t)) == uint32_t(t);
  std::vector<char> used(m.vertices.size(), 0);
  for (const auto& t : m.triangles)
    for (uint32_t v : t) used[v] = 1;
  r.used_vertices = size_t(std::count(used.begin(), used.end(), 1));
  return r;
}

// Vertices that attain the bounding box on some axis: a hole must leave each of them a triangle, or the grid moves.
inline std::vector<char> extreme_vertices(const Mesh& m) {
  Eigen::Vector3d lo, hi;
  m.bounds(lo, hi);
  std::vector<char> ext(m.vertices.size(), 0);
  for (size_t v = 0; v < m.vertices.size(); ++v)
    for (int a = 0; a < 3; ++a) ext[v] |= m.vertices[v][a] == lo[a] || m.vertices[v][a] == hi[a];
  return ext;
}

// How deep the removed surface of a punched mesh lies below the rim of its hole: for each edge-connected patch of
// removed triangles, the largest distance of its vertices from the plane through its boundary vertices' centroid
// normal to its vector area (the plane the winding number's fill of that hole roughly takes); the largest over the
// patches. 0 for a hole of one triangle.
inline double hole_depth(const Mesh& removed) {
  if (removed.triangles.empty()) return 0;
  std::vector<std::pair<uint64_t, uint32_t>> uses;
  for (size_t t = 0; t < removed.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = removed.triangles[t][k], b = removed.triangles[t][(k + 1) % 3];
      uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(t)});
    }
  std::sort(uses.begin(), uses.end());
  std::vector<uint32_t> parent(removed.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<std::pair<uint64_t, uint32_t>> boundary;  // edges used once: edge, triangle
  for (auto i = uses.begin(); i != uses.end();) {
    auto j = i;
    while (j != uses.end() && j->first == i->first) ++j;
    if (j - i == 1) boundary.push_back(*i);
    for (auto k = i + 1; k != j; ++k) parent[find(k->second)] = find(i->second);
    i = j;
  }
  const size_t n = removed.size();
  std::vector<Eigen::Vector3d> normal(n, Eigen::Vector3d::Zero()), rim(n, Eigen::Vector3d::Zero());
  std::vector<double> rim_n(n, 0);
  for (size_t t = 0; t < n; ++t)
    normal[find(uint32_t(t))] += (removed.corner(t, 1) - removed.corner(t, 0)).cross(removed.corner(t, 2) - removed.corner(t, 0));
  for (const auto& [e, t] : boundary) {
    const uint32_t r = find(t);
    rim[r] += removed.vertices[uint32_t(e >> 32)] + removed.vertices[uint32_t(e)];
    rim_n[r] += 2;
  }
  double depth = 0;
  for (size_t t = 0; t < n; ++t) {
    const uint32_t r = find(uint32_t(t));
    if (rim_n[r] == 0 || normal[r].norm() == 0) continue;
    const Eigen::Vector3d c = rim[r] / rim_n[r], u = normal[r].normalized();
    for (int k = 0; k < 3; ++k) depth = std::max(depth, std::abs(u.dot(removed.corner(t, k) - c)));
  }
  return depth;
}

// ---------------------------------------------------------------------------------------------------------------
// Defects of one closed mesh.

inline Defect clean(const Mesh& closed) {
  Defect d;
  d.name = closed.name + ", clean";
  d.mesh = closed;
  d.solid = {closed};
  d.volume = closed.volume();
  d.repairs_to_intended = true;
  const Topology t = topology(closed);
  d.expect.closed = 1;
  d.expect.open_edges = d.expect.nonmanifold_edges = d.expect.dropped_duplicate = d.expect.dropped_repeated =
      d.expect.dropped_collinear = d.expect.reoriented = d.expect.welded = 0;
  d.expect.components = (long long)t.components;
  d.expect.closed_components = (long long)t.components;
  d.expect.sheet_components = 0;
  d.expect.triangles = (long long)closed.size();
  d.expect.vertices = (long long)t.used_vertices;
  d.expect.flipped = 0;
  d.expect.surface_only = 0;
  return d;
}

// `n` triangles removed: scattered at random, or (contiguous) one hole grown from a random triangle across edges.
// No removed triangle touches a vertex on the bounding box, so the grid stays the intended mesh's.
inline Defect punched(const Mesh& closed, size_t n, uint64_t seed, bool contiguous = false) {
  std::mt19937_64 rng(seed);
  const std::vector<char> ext = extreme_vertices(closed);
  auto allowed = [&](size_t t) {
    return !ext[closed.triangles[t][0]] && !ext[closed.triangles[t][1]] && !ext[closed.triangles[t][2]];
  };
  std::vector<char> take(closed.size(), 0);
  if (!contiguous) {
    std::vector<uint32_t> order(closed.size());
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), rng);
    size_t got = 0;
    for (size_t i = 0; i < order.size() && got < n; ++i)
      if (allowed(order[i])) {
        take[order[i]] = 1;
        ++got;
      }
  } else {
    // Triangles by edge: neighbours across each edge.
    std::vector<std::pair<uint64_t, uint32_t>> uses;
    for (size_t t = 0; t < closed.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = closed.triangles[t][k], b = closed.triangles[t][(k + 1) % 3];
        uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b), uint32_t(t)});
      }
    std::sort(uses.begin(), uses.end());
    std::vector<std::vector<uint32_t>> adj(closed.size());
    for (size_t i = 0; i + 1 < uses.size(); ++i)
      if (uses[i].first == uses[i + 1].first) {
        adj[uses[i].second].push_back(uses[i + 1].second);
        adj[uses[i + 1].second].push_back(uses[i].second);
      }
    std::uniform_int_distribution<size_t> pick(0, closed.size() - 1);
    size_t start = pick(rng);
    while (!allowed(start)) start = pick(rng);
    std::vector<uint32_t> queue = {uint32_t(start)};
    take[start] = 1;
    for (size_t q = 0; q < queue.size() && queue.size() < n; ++q)
      for (uint32_t u : adj[queue[q]])
        if (!take[u] && allowed(u) && queue.size() < n) {
          take[u] = 1;
          queue.push_back(u);
        }
  }
  Defect d;
  d.name = closed.name + ", " + std::to_string(n) + (contiguous ? " triangles removed in one hole" : " triangles removed");
  d.mesh = closed;
  d.mesh.triangles.clear();
  d.removed.vertices = closed.vertices;
  d.removed.name = "removed";
  for (size_t t = 0; t < closed.size(); ++t) (take[t] ? d.removed.triangles : d.mesh.triangles).push_back(closed.triangles[t]);
  d.mesh.name = d.name;
  d.solid = {closed};
  d.volume = closed.volume();
  const Topology t = topology(d.mesh);
  d.expect.open_edges = (long long)t.open_edges;
  d.expect.nonmanifold_edges = 0;
  d.expect.components = (long long)t.components;
  d.expect.closed_components = 0;
  d.expect.sheet_components = 0;  // a few holes leave a solid, not a sheet
  d.expect.reoriented = 0;
  d.expect.closed = 0;
  d.expect.surface_only = 0;
  d.expect.triangles = (long long)d.mesh.size();
  return d;
}

// A fraction of the triangles (at least one) reversed at random.
inline Defect flipped(const Mesh& closed, double fraction, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<uint32_t> order(closed.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), rng);
  const size_t n = std::max<size_t>(1, size_t(std::llround(fraction * double(closed.size()))));
  Defect d;
  d.mesh = closed;
  for (size_t i = 0; i < n; ++i) std::swap(d.mesh.triangles[order[i]][1], d.mesh.triangles[order[i]][2]);
  d.name = closed.name + ", " + std::to_string(n) + " triangles flipped";
  d.mesh.name = d.name;
  d.solid = {closed};
  d.volume = closed.volume();
  d.repairs_to_intended = true;
  d.expect.reoriented = (long long)n;
  d.expect.flipped = 0;
  d.expect.open_edges = d.expect.nonmanifold_edges = 0;
  d.expect.closed_components = 1;
  d.expect.closed = 0;
  d.expect.triangles = (long long)closed.size();
  return d;
}

// Every triangle given twice: the copy follows the original, on its own copies of the vertices (as STL and RAW
// repeat them), so welding must merge them before the duplicates show.
inline Defect duplicated(const Mesh& closed) {
  Defect d;
  d.mesh.vertices = closed.vertices;
  const uint32_t base = uint32_t(closed.vertices.size());
  d.mesh.vertices.insert(d.mesh.vertices.end(), closed.vertices.begin(), closed.vertices.end());
  for (const auto& t : closed.triangles) {
    d.mesh.triangles.push_back(t);
    d.mesh.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  d.name = closed.name + ", every triangle duplicated";
  d.mesh.name = d.name;
  d.solid = {closed};
  d.volume = closed.volume();
  d.repairs_to_intended = true;
  d.expect.dropped_duplicate = (long long)closed.size();
  d.expect.welded = (long long)topology(closed).used_vertices;
  d.expect.open_edges = d.expect.nonmanifold_edges = 0;
  d.expect.reoriented = 0;
  d.expect.closed = 0;
  d.expect.triangles = (long long)closed.size();
  return d;
}

// Degenerate triangles sprinkled at random places of the triangle list, `per_kind` of each kind, on the mesh's
// edges (so that they add nothing to the surface): a repeated vertex index (a, a, b); a repeated vertex by
// coordinates (a, a', b) with a' a new vertex equal to a; collinear corners (a, midpoint of ab, b); and a zero-area
// sliver (a, b, a + 0.3 (b - a)).
inline Defect degenerate(const Mesh& closed, size_t per_kind, uint64_t seed) {
  std::mt19937_64 rng(seed);
  Defect d;
  d.mesh = closed;
  std::uniform_int_distribution<size_t> pick(0, closed.size() - 1);
  std::vector<std::array<uint32_t, 3>> extra;
  for (int kind = 0; kind < 4; ++kind)
    for (size_t i = 0; i < per_kind; ++i) {
      const auto& t = closed.triangles[pick(rng)];
      const int k = int(rng() % 3);
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      const Eigen::Vector3d pa = closed.vertices[a], pb = closed.vertices[b];
      const uint32_t nv = uint32_t(d.mesh.vertices.size());
      if (kind == 0) {
        extra.push_back({a, a, b});
      } else if (kind == 1) {
        d.mesh.vertices.push_back(pa);
        extra.push_back({a, nv, b});
      } else if (kind == 2) {
        d.mesh.vertices.push_back((pa + pb) / 2);
        extra.push_back({a, nv, b});
      } else {
        d.mesh.vertices.push_back(pa + 0.3 * (pb - pa));
        extra.push_back({a, b, nv});
      }
    }
  std::shuffle(extra.begin(), extra.end(), rng);
  for (const auto& e : extra) {
    const size_t at = std::uniform_int_distribution<size_t>(0, d.mesh.triangles.size())(rng);
    d.mesh.triangles.insert(d.mesh.triangles.begin() + long(at), e);
  }
  d.name = closed.name + ", " + std::to_string(4 * per_kind) + " degenerate triangles";
  d.mesh.name = d.name;
  d.solid = {closed};
  d.volume = closed.volume();
  d.repairs_to_intended = true;
  d.expect.dropped_repeated = (long long)(2 * per_kind);
  d.expect.dropped_collinear = (long long)(2 * per_kind);
  d.expect.welded = (long long)per_kind;  // the coordinate copies a'
  d.expect.dropped_duplicate = 0;
  d.expect.open_edges = d.expect.nonmanifold_edges = 0;
  d.expect.reoriented = 0;
  d.expect.closed = 0;
  d.expect.triangles = (long long)closed.size();
  return d;
}

// The mesh split into four parts (by the sign of x and z of each triangle's centroid, about a point off the
// centre), each part given its own copies of its vertices; copies of vertices shared with a lower-numbered part are
// moved towards the bounding box's centre by `relative` x the box's diagonal x (1 + part / 8), so that the parts no
// longer meet: hairline cracks. Every vertex keeps one copy in place (the bounding box does not change). Below the
// weld tolerance (kWeldRelative) repair welds them; below kCrackCloseRelative it joins the open edges of the parts;
// above that they stay open and only the winding number copes.
inline Defect cracked(const Mesh& closed, double relative) {
  Eigen::Vector3d lo, hi;
  closed.bounds(lo, hi);
  const Eigen::Vector3d centre = (lo + hi) / 2, size = hi - lo;
  const double step = relative * size.norm();
  const double sx = centre.x() + 0.1 * size.x(), sz = centre.z() - 0.07 * size.z();
  std::vector<int> part(closed.size());
  std::vector<uint8_t> users(closed.vertices.size(), 0);  // bit p: part p uses the vertex
  for (size_t t = 0; t < closed.size(); ++t) {
    const Eigen::Vector3d c = (closed.corner(t, 0) + closed.corner(t, 1) + closed.corner(t, 2)) / 3;
    part[t] = (c.x() > sx ? 1 : 0) + (c.z() > sz ? 2 : 0);
    for (uint32_t v : closed.triangles[t]) users[v] |= uint8_t(1u << part[t]);
  }
  Defect d;
  d.mesh.vertices = closed.vertices;  // part 0 keeps the original vertices
  // Copies made part by part, so that the copy left in place (the lowest part's) precedes the moved ones.
  std::vector<std::vector<uint32_t>> copy(4, std::vector<uint32_t>(closed.vertices.size(), UINT32_MAX));
  for (int p = 1; p < 4; ++p)
    for (size_t t = 0; t < closed.size(); ++t) {
      if (part[t] != p) continue;
      for (uint32_t v : closed.triangles[t]) {
        if (copy[p][v] != UINT32_MAX) continue;
        copy[p][v] = uint32_t(d.mesh.vertices.size());
        Eigen::Vector3d q = closed.vertices[v];
        if (users[v] & ((1u << p) - 1)) q += (centre - q).normalized() * step * (1 + p / 8.0);
        d.mesh.vertices.push_back(q);
      }
    }
  for (size_t t = 0; t < closed.size(); ++t) {
    const int p = part[t];
    std::array<uint32_t, 3> out = closed.triangles[t];
    if (p > 0)
      for (uint32_t& v : out) v = copy[p][v];
    d.mesh.triangles.push_back(out);
  }
  char b[32];
  std::snprintf(b, sizeof b, "%.0e", relative);
  d.name = closed.name + ", 4 parts with cracks of " + b + " x the diagonal";
  d.mesh.name = d.name;
  d.solid = {closed};
  d.volume = closed.volume();
  d.expect.nonmanifold_edges = 0;
  d.expect.closed = 0;
  d.expect.sheet_components = 0;
  d.expect.surface_only = 0;
  const Topology cut = topology(d.mesh), whole = topology(closed);
  if (relative * (1 + 3 / 8.0) < kWeldRelative) {
    // Every crack is narrower than the weld tolerance: the repaired mesh is the closed one again.
    d.repairs_to_intended = true;
    d.expect.open_edges = 0;
    d.expect.components = d.expect.closed_components = (long long)whole.components;
    d.expect.welded = (long long)(cut.used_vertices - whole.used_vertices);
    d.expect.triangles = (long long)closed.size();
    d.expect.vertices = (long long)whole.used_vertices;
  } else if (relative * (1 + 3 / 8.0) < kCrackCloseRelative) {
    // Wider than the weld tolerance, narrower than a crack repair closes: every moved copy joins the copy left in
    // place (the nearest vertex on an open edge of another part), and the mesh is closed again.
    d.repairs_to_intended = true;
    d.expect.open_edges = 0;
    d.expect.components = d.expect.closed_components = (long long)whole.components;
    d.expect.welded = (long long)(cut.used_vertices - whole.used_vertices);
    d.expect.triangles = (long long)closed.size();
    d.expect.vertices = (long long)whole.used_vertices;
  } else {
    // (Moved copies of different parts lie closer to each other than to the copy in place, and some of those
    // join: the counts of open edges and welded vertices are not the cut's exactly.)
    d.expect.components = (long long)cut.components;
    d.expect.closed_components = 0;
  }
  return d;
}

// The mesh with every triangle reversed (an inside-out export): repair must turn it all back.
inline Defect inside_out(const Mesh& closed) {
  Defect d;
  d.mesh = reversed(closed);
  d.name = closed.name + ", inside out";
  d.mesh.name = d.name;
  d.solid = {closed};
  d.volume = closed.volume();
  d.repairs_to_intended = true;
  d.expect.flipped = 1;
  d.expect.reoriented = 0;
  d.expect.open_edges = d.expect.nonmanifold_edges = 0;
  return d;
}

// ---------------------------------------------------------------------------------------------------------------
// Defects of several parts.

// Two closed boxes that overlap (no coplanar faces): the intended solid is their union, of exactly known volume.
inline Defect overlapping_boxes() {
  const Eigen::Vector3d a0(-1, -1, -1), a1(1, 1, 1), b0(0, -0.5, 0.25), b1(2, 1.5, 1.75);
  Defect d;
  d.mesh = make_box(a0, a1);
  append(d.mesh, make_box(b0, b1));
  d.name = "two overlapping boxes";
  d.mesh.name = d.name;
  d.solid = {make_box(a0, a1), make_box(b0, b1)};
  const Eigen::Vector3d o = (a1.cwiseMin(b1) - a0.cwiseMax(b0)).cwiseMax(0.0);
  d.volume = (a1 - a0).prod() + (b1 - b0).prod() - o.prod();
  d.expect.components = d.expect.closed_components = 2;
  d.expect.open_edges = d.expect.nonmanifold_edges = 0;
  d.expect.reoriented = 0;
  d.expect.closed = 1;  // closed, manifold and oriented: the overlap is geometric, not topological
  return d;
}

// Two icospheres that overlap: union (volume not known exactly; the tests compare voxel by voxel).
inline Defect overlapping_spheres(int level) {
  Defect d;
  const Mesh a = icosphere(level, 1.0), b = icosphere(level, 0.7, Eigen::Vector3d(0.9, 0.35, -0.2));
  d.mesh = a;
  append(d.mesh, b);
  d.name = "two overlapping icospheres (level " + std::to_string(level) + ")";
  d.mesh.name = d.name;
  d.solid = {a, b};
  d.expect.components = d.expect.closed_components = 2;
  d.expect.open_edges = d.expect.nonmanifold_edges = 0;
  d.expect.reoriented = 0;
  d.expect.closed = 1;
  return d;
}

// Two cubes that share one edge and nothing else: after welding, that edge has four triangles.
inline Defect edge_sharing_cubes() {
  const Eigen::Vector3d a0(0, 0, 0), a1(1, 1, 1), b0(1, 1, 0), b1(2, 2, 1);
  Defect d;
  d.mesh = make_box(a0, a1);
  append(d.mesh, make_box(b0, b1));
  d.name = "two cubes sharing an edge";
  d.mesh.name = d.name;
  d.solid = {make_box(a0, a1), make_box(b0, b1)};
  d.volume = 2;
  d.expect.nonmanifold_edges = 1;
  d.expect.open_edges = 0;
  d.expect.welded = 2;
  d.expect.components = 1;  // connected through the edge
  d.expect.closed = 0;
  d.expect.reoriented = 0;
  d.expect.surface_only = 0;
  return d;
}

// Two unit cubes side by side, each a closed box as a modeller exports it: the face they share is given twice, once by
// each cube (opposite orientations). After welding one copy is an exact duplicate; the other has solid on both
// sides and must go: the solid is the 2 x 1 x 1 box.
inline Defect face_sharing_boxes() {
  const Eigen::Vector3d a0(0, 0, 0), a1(1, 1, 1), b0(1, 0, 0), b1(2, 1, 1);
  Defect d;
  d.mesh = make_box(a0, a1);
  append(d.mesh, make_box(b0, b1));
  d.name = "two boxes sharing a face";
  d.mesh.name = d.name;
  d.solid = {make_box(a0, a1), make_box(b0, b1)};
  d.volume = 2;
  d.expect.welded = 4;
  d.expect.dropped_duplicate = 2;
  d.expect.nonmanifold_edges = 4;  // the shared face's sides: a triangle of each cube and the face's
  d.expect.nonmanifold_parts = 1;
  d.expect.dropped_internal = 2;
  d.expect.fin_triangles = 0;
  d.expect.open_edges = 0;
  d.expect.components = d.expect.closed_components = 1;
  d.expect.triangles = 20;
  d.expect.sheet_components = 0;
  d.expect.surface_only = 0;
  d.expect.closed = 0;
  return d;
}

// A closed box with an internal face: the 2 x 1 x 1 box triangulated to meet the plane x = 1, with a partition
// wall there (one copy, as CAD exports of multi-body parts give it). The wall has solid on both sides.
inline Defect box_with_internal_face() {
  Defect d;
  d.mesh = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  Mesh right = make_box(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 1, 1));
  right.triangles.erase(right.triangles.begin() + 8, right.triangles.begin() + 10);  // its x = 1 face
  append(d.mesh, right);
  d.name = "a box with an internal face";
  d.mesh.name = d.name;
  d.solid = {make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1))};
  d.volume = 2;
  d.expect.dropped_duplicate = 0;
  d.expect.nonmanifold_edges = 4;
  d.expect.nonmanifold_parts = 1;
  d.expect.dropped_internal = 2;
  d.expect.fin_triangles = 0;
  d.expect.open_edges = 0;
  d.expect.components = d.expect.closed_components = 1;
  d.expect.triangles = 20;
  d.expect.sheet_components = 0;
  d.expect.surface_only = 0;
  d.expect.closed = 0;
  return d;
}

// A closed triangular prism with corners a, b, c at z0 and z1, each face's triangles facing away from its centroid;
// quads split along the diagonal from the bottom corner that is lower in (x, y) order, so every prism that shares a
// face splits it the same way.
inline Mesh prism(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, double z0, double z1) {
  Mesh p;
  for (double z : {z0, z1})
    for (const Eigen::Vector3d& v : {a, b, c}) p.vertices.emplace_back(v.x(), v.y(), z);
  p.triangles = {{0, 1, 2}, {3, 4, 5}};
  auto lower = [&](uint32_t i, uint32_t j) {
    const Eigen::Vector3d &u = p.vertices[i], &v = p.vertices[j];
    return u.x() != v.x() ? u.x() < v.x() : u.y() < v.y();
  };
  for (uint32_t k = 0; k < 3; ++k) {
    const uint32_t i = k, j = (k + 1) % 3;
    if (lower(i, j)) {  // the diagonal from i's bottom corner to j's top corner
      p.triangles.push_back({i, j, j + 3});
      p.triangles.push_back({i, j + 3, i + 3});
    } else {  // from j's bottom corner to i's top corner
      p.triangles.push_back({i, j, i + 3});
      p.triangles.push_back({j, j + 3, i + 3});
    }
  }
  const Eigen::Vector3d mid = (p.vertices[0] + p.vertices[1] + p.vertices[2] + p.vertices[3] + p.vertices[4] +
                               p.vertices[5]) / 6;
  for (auto& t : p.triangles) {
    const Eigen::Vector3d n = (p.vertices[t[1]] - p.vertices[t[0]]).cross(p.vertices[t[2]] - p.vertices[t[0]]);
    if (n.dot(p.vertices[t[0]] - mid) < 0) std::swap(t[1], t[2]);
  }
  p.name = "prism";
  return p;
}

// A hexagonal prism given as the union of `n` triangular wedges around its axis, each a closed prism: the axis is
// an edge of every wedge (2n triangles before repair), each radial face is shared by two wedges (given twice), the
// caps' radial edges have three triangles. The solid is the whole prism.
inline Defect wedge_union(int n = 6) {
  Defect d;
  const double pi = std::acos(-1.0);
  double area = 0;
  for (int i = 0; i < n; ++i) {
    const double t0 = 2 * pi * i / n, t1 = 2 * pi * (i + 1) / n;
    const Eigen::Vector3d a(0, 0, 0), b(std::cos(t0), std::sin(t0), 0), c(std::cos(t1), std::sin(t1), 0);
    const Mesh w = prism(a, b, c, -0.25, 0.5);
    append(d.mesh, w);
    d.solid.push_back(w);
    area += 0.5 * b.cross(c).norm();
  }
  d.name = "a union of " + std::to_string(n) + " prisms sharing edges and faces";
  d.mesh.name = d.name;
  d.volume = 0.75 * area;
  d.expect.nonmanifold_parts = 1;
  d.expect.dropped_internal = n * 2;  // each radial face once (its duplicate goes as a duplicate)
  d.expect.dropped_duplicate = n * 2;
  d.expect.fin_triangles = 0;
  d.expect.open_edges = 0;
  d.expect.components = d.expect.closed_components = 1;
  d.expect.sheet_components = 0;
  d.expect.surface_only = 0;
  d.expect.closed = 0;
  return d;
}

// Prisms that share only edges: a ring of `n` wedges with every other one left out (a pinwheel), so the axis has
// four or more triangles and no face is shared. Each wedge is solid.
inline Defect pinwheel(int n = 8) {
  Defect d;
  const double pi = std::acos(-1.0);
  double area = 0;
  for (int i = 0; i < n; i += 2) {
    const double t0 = 2 * pi * i / n, t1 = 2 * pi * (i + 1) / n;
    const Eigen::Vector3d a(0, 0, 0), b(std::cos(t0), std::sin(t0), 0), c(std::cos(t1), std::sin(t1), 0);
    const Mesh w = prism(a, b, c, 0, 0.6);
    append(d.mesh, w);
    d.solid.push_back(w);
    area += 0.5 * b.cross(c).norm();
  }
  d.name = "a pinwheel of " + std::to_string(n / 2) + " prisms sharing an edge";
  d.mesh.name = d.name;
  d.volume = 0.6 * area;
  d.expect.nonmanifold_parts = 1;
  d.expect.nonmanifold_edges = 1;
  d.expect.dropped_internal = 0;
  d.expect.fin_triangles = 0;
  d.expect.open_edges = 0;
  d.expect.sheet_components = 0;
  d.expect.surface_only = 0;
  d.expect.closed = 0;
  return d;
}

// Two closed boxes that overlap and share an edge (an L exported as two overlapping parts): the edge has four
// triangles, two pairs of them coplanar. Each box keeps its inside: the solid is their union.
inline Defect overlapping_boxes_sharing_an_edge() {
  const Eigen::Vector3d a0(0, 0, 0), a1(2, 1, 1), b0(1.5, 0, 0), b1(2, 3, 1);
  Defect d;
  d.mesh = make_box(a0, a1);
  append(d.mesh, make_box(b0, b1));
  d.name = "two overlapping boxes sharing an edge";
  d.mesh.name = d.name;
  d.solid = {make_box(a0, a1), make_box(b0, b1)};
  d.volume = 2 + 1.5 - 0.5;
  d.expect.nonmanifold_edges = 1;
  d.expect.nonmanifold_parts = 1;
  d.expect.dropped_internal = 0;
  d.expect.fin_triangles = 0;
  d.expect.sheet_components = 0;
  d.expect.surface_only = 0;
  d.expect.closed = 0;
  return d;
}

// A unit cube with a fin: a flat flap on one of its edges, sticking out (empty space on both sides). The fin is a
// sheet; the cube stays solid.
inline Defect box_with_fin() {
  Defect d;
  const Mesh box = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  d.mesh = box;
  Mesh fin;
  fin.vertices = {{0, 0, 1}, {1, 0, 1}, {1, -0.4, 1.5}, {0, -0.4, 1.5}};
  fin.triangles = {{0, 1, 2}, {0, 2, 3}};
  append(d.mesh, fin);
  d.name = "a box with a fin on an edge";
  d.mesh.name = d.name;
  d.solid = {box};
  d.volume = 1;
  d.expect.nonmanifold_edges = 1;
  d.expect.nonmanifold_parts = 1;
  d.expect.dropped_internal = 0;
  d.expect.fin_triangles = 2;
  d.expect.sheet_components = 1;
  d.expect.surface_only = 0;
  d.expect.closed = 0;
  return d;
}

// A unit cube whose top face is split at the midpoint of one of its edges while the side face below keeps the whole
// edge: a T-junction, so that edge shows as open on both sides although the surface is closed.
inline Defect box_with_t_junction() {
  Defect d;
  Mesh m = make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1));
  // Top face (z = 1): vertices 4 (0,0,1), 5 (1,0,1), 6 (0,1,1), 7 (1,1,1), triangles {4,5,6}, {5,7,6}. Split the
  // edge 4-5 at its midpoint in the top face only.
  m.vertices.emplace_back(0.5, 0, 1);
  const uint32_t mid = uint32_t(m.vertices.size() - 1);
  m.triangles[2] = {4, mid, 6};
  m.triangles.push_back({mid, 5, 6});
  d.mesh = m;
  d.name = "a box with a T-junction";
  d.expect.open_edges = 3;  // the long edge, and its two halves
  d.mesh.name = d.name;
  d.solid = {make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 1, 1))};
  d.volume = 1;
  d.expect.nonmanifold_edges = 0;
  d.expect.sheet_components = 0;
  d.expect.surface_only = 0;
  d.expect.closed = 0;
  return d;
}

// A ball with a cavity, given three ways: right (outer outward, inner inward), inside out (every triangle reversed),
// and with the cavity's shell outward like the outer one. The intended solid is the shell each time: nested closed
// parts alternate in orientation, so the cavity stays empty.
inline Defect hollow(int level, int variant) {
  const Mesh right = hollow_sphere(level);
  Defect d;
  d.solid = {right};
  d.volume = right.volume();
  d.expect.components = d.expect.closed_components = 2;
  d.expect.open_edges = d.expect.nonmanifold_edges = 0;
  const size_t outer = icosphere(level).size();
  if (variant == 0) {
    d.mesh = right;
    d.name = "hollow sphere";
    d.expect.closed = 1;
    d.expect.reoriented = 0;
    d.expect.flipped = 0;
  } else if (variant == 1) {
    d.mesh = reversed(right);
    d.name = "hollow sphere, inside out";
    d.expect.flipped = 1;
    d.expect.reoriented = 0;
  } else {
    d.mesh = right;
    for (size_t t = outer; t < d.mesh.size(); ++t) std::swap(d.mesh.triangles[t][1], d.mesh.triangles[t][2]);
    d.name = "hollow sphere, cavity outward";
    d.expect.reoriented = (long long)(right.size() - outer);
    d.expect.closed = 0;
  }
  d.repairs_to_intended = true;
  d.mesh.name = d.name;
  return d;
}

// ---------------------------------------------------------------------------------------------------------------
// Surface only.

// A square in a slanted plane, two triangles: encloses nothing.
inline Defect square_sheet() {
  Defect d;
  const Eigen::Vector3d o(-1, -1, -0.2), u(2, 0, 0.3), v(0, 2, 0.15);
  d.mesh.vertices = {o, o + u, o + u + v, o + v};
  d.mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  d.name = "a square sheet";
  d.mesh.name = d.name;
  d.expect.surface_only = 1;
  d.expect.sheet_components = 1;
  d.expect.closed_components = 0;
  d.expect.open_edges = 4;
  d.expect.closed = 0;
  return d;
}

// A terrain patch: z = f(x, y) on an n x n grid over [-1, 1]^2, seeded bumps.
inline Defect terrain(int n, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  double a[4];
  for (double& x : a) x = u(rng);
  Defect d;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      const double z = 0.25 * (a[0] * std::sin(3 * x + a[1]) * std::cos(2 * y + a[2]) + 0.3 * a[3] * x * y) +
                       0.01 * u(rng);
      d.mesh.vertices.emplace_back(x, y, z);
    }
  auto id = [&](int i, int j) { return uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      d.mesh.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      d.mesh.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  d.name = "a terrain patch " + std::to_string(n) + " x " + std::to_string(n);
  d.mesh.name = d.name;
  d.expect.surface_only = 1;
  d.expect.sheet_components = 1;
  d.expect.closed_components = 0;
  d.expect.open_edges = 4 * n;
  d.expect.closed = 0;
  return d;
}

// The vertices of a mesh and no triangles.
inline Defect point_cloud(const Mesh& m) {
  Defect d;
  d.mesh.vertices = m.vertices;
  d.name = "point cloud (" + std::to_string(m.vertices.size()) + " points)";
  d.mesh.name = d.name;
  d.expect.points_only = 1;
  d.expect.surface_only = 1;
  d.expect.closed = 0;
  d.expect.welded = 0;
  d.expect.vertices = (long long)m.vertices.size();
  return d;
}

// A closed icosphere and a separate square sheet beside it: interior from the ball only.
inline Defect sphere_and_sheet(int level) {
  const Mesh ball = icosphere(level);
  Defect d;
  d.mesh = ball;
  Mesh sq;
  sq.vertices = {{1.4, -1, -1}, {1.5, 1, -1}, {1.5, 1, 1}, {1.4, -1, 1}};
  sq.triangles = {{0, 1, 2}, {0, 2, 3}};
  append(d.mesh, sq);
  d.name = "icosphere and a sheet beside it";
  d.mesh.name = d.name;
  d.solid = {ball};
  d.volume = ball.volume();
  d.expect.sheet_components = 1;
  d.expect.closed_components = 1;
  d.expect.components = 2;
  d.expect.surface_only = 0;
  d.expect.open_edges = 4;
  d.expect.closed = 0;
  return d;
}

// A closed icosphere with a square partition wall through it (a sheet inside the solid, as CAD exports leave
// them): the interior is the ball's.
inline Defect sphere_with_inner_sheet(int level) {
  const Mesh ball = icosphere(level);
  Defect d;
  d.mesh = ball;
  Mesh sq;
  sq.vertices = {{-0.5, -0.45, 0.1}, {0.5, -0.45, 0.13}, {0.5, 0.55, 0.16}, {-0.5, 0.55, 0.12}};
  sq.triangles = {{0, 1, 2}, {0, 2, 3}};
  append(d.mesh, sq);
  d.name = "icosphere with a sheet inside";
  d.mesh.name = d.name;
  d.solid = {ball};
  d.volume = ball.volume();
  d.expect.sheet_components = 1;
  d.expect.closed_components = 1;
  d.expect.components = 2;
  d.expect.surface_only = 0;
  d.expect.open_edges = 4;
  d.expect.closed = 0;
  return d;
}

// Every defect kind on an icosphere of `level` (and the fixed multi-part cases), seeded.
inline std::vector<Defect> all_defects(int level, uint64_t seed) {
  const Mesh s = icosphere(level);
  std::vector<Defect> v;
  v.push_back(clean(s));
  for (size_t n : {1, 10, 100}) v.push_back(punched(s, n, seed + n));
  v.push_back(punched(s, 100, seed + 7, true));
  v.push_back(flipped(s, 0.01, seed + 11));
  v.push_back(inside_out(s));
  v.push_back(duplicated(s));
  v.push_back(degenerate(s, 5, seed + 13));
  v.push_back(cracked(s, 1e-9));
  v.push_back(cracked(s, 1e-4));
  v.push_back(cracked(s, 1e-3));
  v.push_back(overlapping_boxes());
  v.push_back(overlapping_spheres(std::max(level - 1, 1)));
  v.push_back(edge_sharing_cubes());
  v.push_back(face_sharing_boxes());
  v.push_back(box_with_internal_face());
  v.push_back(wedge_union());
  v.push_back(pinwheel());
  v.push_back(box_with_fin());
  v.push_back(overlapping_boxes_sharing_an_edge());
  v.push_back(box_with_t_junction());
  for (int k = 0; k < 3; ++k) v.push_back(hollow(std::max(level - 1, 1), k));
  v.push_back(sphere_and_sheet(std::max(level - 1, 1)));
  v.push_back(sphere_with_inner_sheet(std::max(level - 1, 1)));
  v.push_back(square_sheet());
  v.push_back(terrain(24, seed + 17));
  v.push_back(point_cloud(icosphere(std::max(level - 1, 1))));
  return v;
}

// ---------------------------------------------------------------------------------------------------------------
// The intended solid on a voxmap's grid.

// A closed tetrahedron with corner p and edges e along +/- each axis (sign s).
inline Mesh corner_tet(const Eigen::Vector3d& p, double e, double s) {
  Mesh t;
  t.vertices = {p, p + Eigen::Vector3d(s * e, 0, 0), p + Eigen::Vector3d(0, s * e, 0), p + Eigen::Vector3d(0, 0, s * e)};
  t.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  if (s < 0) t = reversed(t);
  return t;
}

// States of the intended solid on the grid of `vm` (voxelised from a mesh with bounding box [lo, hi]): Interior
// where some closed mesh of `solid` has an interior voxel (by the exact ray-casting voxeliser), else Surface where
// some has a surface voxel, else Empty. Each closed mesh is voxelised with two tiny tetrahedra (1/1000 voxel) added
// at lo and hi, so that its grid is the voxmap's exactly; they only add surface voxels at the box's corners.
// Throws std::logic_error when a closed mesh does not fit in [lo, hi].
inline std::vector<uint8_t> intended_states(const std::vector<Mesh>& solid, const Voxmap& vm,
                                            const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                                            const Eigen::Vector3d& shift, unsigned threads = 0) {
  std::vector<uint8_t> st(vm.size(), kEmpty);
  for (const Mesh& part : solid) {
    Mesh aug = part;
    append(aug, corner_tet(lo, 1e-3 * vm.voxel(), 1));
    append(aug, corner_tet(hi, 1e-3 * vm.voxel(), -1));
    aug.name = part.name + " (on the defect's grid)";
    VoxelizeOptions o;
    o.voxel = vm.voxel();
    o.shift = shift;
    o.threads = threads;
    o.max_dim = std::max({vm.dims()[0], vm.dims()[1], vm.dims()[2], 1024u});
    const Voxmap ref = voxelize_raycast(aug, o);
    if (ref.dims() != vm.dims() || ref.origin() != vm.origin())
      throw std::logic_error(part.name + ": the intended solid does not fit in the defective mesh's bounding box");
    for (uint64_t i = 0; i < vm.size(); ++i) {
      const VoxelState s = ref.at(i);
      if (s == kInterior) st[i] = kInterior;
      else if (s == kSurface && st[i] == kEmpty) st[i] = kSurface;
    }
  }
  return st;
}

// Voxels that are surface in neither map and disagree: the defect's voxmap against the intended states.
inline uint64_t wrong_voxels(const Voxmap& vm, const std::vector<uint8_t>& intended) {
  uint64_t n = 0;
  for (uint64_t i = 0; i < vm.size(); ++i) {
    const VoxelState s = vm.at(i);
    if (s != kSurface && intended[i] != kSurface && s != intended[i]) ++n;
  }
  return n;
}

}  // namespace voxcd::test
