// Meshes: the Mesh type's measures, welding, strict validation and load_mesh, which reads a file through the
// reader of its format (formats/) and then repairs or validates what it read.
#include "voxcd/host/mesh/mesh.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <unordered_map>

#include "voxcd/host/mesh/detail/edge_uses.h"
#include "voxcd/host/mesh/detail/point_hash.h"
#include "voxcd/host/mesh/formats/formats.h"

namespace voxcd {

namespace {

std::string fmt_point(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << std::setprecision(9) << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

}  // namespace

void Mesh::bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const {
  lo = Eigen::Vector3d::Constant(HUGE_VAL);
  hi = Eigen::Vector3d::Constant(-HUGE_VAL);
  if (points_only()) {
    for (const auto& p : vertices)
      if (p.allFinite()) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
    return;
  }
  for (const auto& t : triangles)
    for (uint32_t v : t) {
      lo = lo.cwiseMin(vertices[v]);
      hi = hi.cwiseMax(vertices[v]);
    }
}

double Mesh::volume() const {
  // Relative to the first vertex, so that far-from-origin meshes keep their precision.
  if (triangles.empty()) return 0;
  const Eigen::Vector3d o = vertices[triangles[0][0]];
  double v = 0;
  for (size_t t = 0; t < triangles.size(); ++t)
    v += (corner(t, 0) - o).dot((corner(t, 1) - o).cross(corner(t, 2) - o));
  return v / 6;
}

double Mesh::area() const {
  double a = 0;
  for (size_t t = 0; t < triangles.size(); ++t) a += (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0)).norm();
  return a / 2;
}

size_t weld(Mesh& m) {
  detail::ExactPoints points(m.vertices.size());
  std::vector<uint32_t> remap(m.vertices.size(), UINT32_MAX);
  size_t used = 0;
  for (auto& t : m.triangles)
    for (uint32_t& v : t) {
      if (v >= m.vertices.size())
        throw MeshError(m.name + ": triangle " + std::to_string(&t - m.triangles.data()) + " has vertex index " +
                        std::to_string(v) + " out of range (" + std::to_string(m.vertices.size()) + " vertices)");
      if (remap[v] == UINT32_MAX) {
        ++used;
        const Eigen::Vector3d& p = m.vertices[v];
        remap[v] = p.allFinite() ? points.add(p) : points.add_apart(p);  // apart: validate() names it
      }
      v = remap[v];
    }
  m.vertices = points.take();
  return used - m.vertices.size();
}

namespace {

// Each triangle: indices in range, finite corners, no repeated vertex, a non-zero area.
void check_triangles(const Mesh& m) {
  const std::string& n = m.name;
  auto tri_name = [&](size_t t) { return "triangle " + std::to_string(t); };
  for (size_t t = 0; t < m.size(); ++t) {
    const auto& tr = m.triangles[t];
    for (uint32_t v : tr) {
      if (v >= m.vertices.size())
        throw MeshError(n + ": " + tri_name(t) + " has vertex index " + std::to_string(v) + " out of range");
      if (!m.vertices[v].allFinite())
        throw MeshError(n + ": " + tri_name(t) + " has a vertex that is not a finite number " +
                        fmt_point(m.vertices[v]));
    }
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[0] == tr[2])
      throw MeshError(n + ": " + tri_name(t) + " is degenerate (a repeated vertex at " +
                      fmt_point(m.vertices[tr[0] == tr[1] || tr[0] == tr[2] ? tr[0] : tr[1]]) + ")");
    const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    const double l2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    if ((b - a).cross(c - a).squaredNorm() <= 1e-26 * l2 * l2)
      throw MeshError(n + ": " + tri_name(t) + " is degenerate (zero area: " + fmt_point(a) + " " + fmt_point(b) +
                      " " + fmt_point(c) + " are collinear)");
  }
}

// Every undirected edge must be used exactly twice, once in each direction.
void check_edges(const Mesh& m) {
  const std::string& n = m.name;
  const std::vector<detail::EdgeUse> uses = detail::edge_uses(m);
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const uint32_t lo = uint32_t(uses[i].key >> 32), hi = uint32_t(uses[i].key);
    if (j - i == 2 && uses[i].forward != uses[i + 1].forward) {
      i = j;
      continue;
    }
    // Only a bad edge is worth formatting (formatting every edge would dominate the time of a large mesh).
    const std::string edge = "edge " + fmt_point(m.vertices[lo]) + "-" + fmt_point(m.vertices[hi]) +
                             " (vertices " + std::to_string(lo) + ", " + std::to_string(hi) + ")";
    std::string tris;
    for (size_t k = i; k < j && k < i + 4; ++k) tris += (k > i ? ", " : "") + std::to_string(uses[k].tri);
    if (j - i == 1)
      throw MeshError(n + ": the mesh is open: " + edge + " belongs to triangle " + tris + " only");
    if (j - i > 2)
      throw MeshError(n + ": the mesh is not manifold: " + edge + " is shared by " + std::to_string(j - i) +
                      " triangles (" + tris + (j - i > 4 ? ", ..." : "") + ")");
    throw MeshError(n + ": inconsistent orientation: " + edge + " runs the same way in triangles " + tris);
  }
}

}  // namespace

void validate(Mesh& m, MeshReport* report) {
  if (m.triangles.empty()) throw MeshError(m.name + ": the mesh has no triangles");
  check_triangles(m);
  check_edges(m);
  bool flipped = false;
  if (m.volume() < 0) {
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    flipped = true;
  }
  if (report) {
    report->vertices = m.vertices.size();
    report->triangles = m.triangles.size();
    report->flipped = flipped;
  }
}

MeshReport prepare(Mesh& m) {
  MeshReport r;
  const size_t welded = weld(m);
  validate(m, &r);
  r.welded = welded;
  return r;
}

namespace {

// The reader of the file's format, by its extension.
Mesh read_by_format(const std::string& path) {
  const std::string ext = formats::lower_ext(path);
  if (ext == "raw") return formats::read_raw(path);
  if (ext == "ply") return formats::read_ply(path);
  if (ext == "off") return formats::read_off(path);
  if (ext == "obj") return formats::read_obj(path);
  return formats::read_assimp(path);
}

}  // namespace

Mesh load_mesh(const std::string& path, MeshReport* report, const LoadOptions& opt) {
  Mesh m = read_by_format(path);
  if (m.name.empty()) m.name = path;
  MeshReport r;
  if (opt.strict) {
    const size_t in_v = m.vertices.size(), in_t = m.triangles.size();
    r = prepare(m);
    r.input_vertices = in_v;
    r.input_triangles = in_t;
    r.closed = true;
  } else if (opt.repair) {
    r = repair(m);
  } else {
    r.input_vertices = r.vertices = m.vertices.size();
    r.input_triangles = r.triangles = m.triangles.size();
  }
  if (report) *report = r;
  return m;
}

}  // namespace voxcd
