#include "voxcd/host/object/shapes.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

namespace voxcd {

namespace {

const double kPhi = (1 + std::sqrt(5.0)) / 2;

// Reverses triangles whose normal points towards `inside`: every shape here is star-shaped about it.
void orient_from(Mesh& m, const Eigen::Vector3d& inside) {
  for (size_t t = 0; t < m.size(); ++t) {
    const Eigen::Vector3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    if ((b - a).cross(c - a).dot((a + b + c) / 3 - inside) < 0) std::swap(m.triangles[t][1], m.triangles[t][2]);
  }
}

std::vector<Eigen::Vector3d> icosahedron_vertices() {
  std::vector<Eigen::Vector3d> v;
  for (double s1 : {-1.0, 1.0})
    for (double s2 : {-1.0, 1.0}) {
      v.emplace_back(0, s1, s2 * kPhi);
      v.emplace_back(s1, s2 * kPhi, 0);
      v.emplace_back(s2 * kPhi, 0, s1);
    }
  return v;
}

Mesh icosahedron() {
  Mesh m;
  m.vertices = icosahedron_vertices();
  const size_t n = m.vertices.size();
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j)
      for (uint32_t k = j + 1; k < n; ++k) {
        auto edge = [&](uint32_t a, uint32_t b) {
          return std::abs((m.vertices[a] - m.vertices[b]).norm() - 2.0) < 1e-9;
        };
        if (edge(i, j) && edge(j, k) && edge(i, k)) m.triangles.push_back({i, j, k});
      }
  orient_from(m, Eigen::Vector3d::Zero());
  return m;
}

// Convex hull of points in general position (no four coplanar), by testing every triple: fine for tens of
// points.
Mesh hull_of(const std::vector<Eigen::Vector3d>& p) {
  Mesh m;
  m.vertices = p;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const auto& q : p) centroid += q / double(p.size());
  const uint32_t n = uint32_t(p.size());
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t j = i + 1; j < n; ++j)
      for (uint32_t k = j + 1; k < n; ++k) {
        const Eigen::Vector3d nrm = (p[j] - p[i]).cross(p[k] - p[i]);
        int pos = 0, neg = 0;
        for (uint32_t l = 0; l < n; ++l) {
          if (l == i || l == j || l == k) continue;
          const double s = nrm.dot(p[l] - p[i]);
          (s > 0 ? pos : neg)++;
        }
        if (pos == 0 || neg == 0) m.triangles.push_back({i, j, k});
      }
  orient_from(m, centroid);
  return m;
}

Mesh polytope36() {
  // 20 directions from a fixed seed, on an ellipsoid so that every point is a hull vertex; a triangulated
  // convex polytope with 20 vertices has 2*20 - 4 = 36 faces.
  std::mt19937_64 rng(36);
  std::normal_distribution<double> g;
  std::vector<Eigen::Vector3d> p;
  while (p.size() < 20) {
    Eigen::Vector3d d(g(rng), g(rng), g(rng));
    if (d.norm() < 1e-3) continue;
    d.normalize();
    p.push_back(Eigen::Vector3d(1.0 * d.x(), 0.8 * d.y(), 0.65 * d.z()));
  }
  return hull_of(p);
}

Mesh stellated() {
  // Kernel: the dodecahedron whose face normals are the icosahedron's vertex directions. Each pentagonal face
  // carries a spike whose apex lies where the five neighbouring face planes meet: at sqrt(5) times the
  // inradius along the face normal (adjacent dodecahedron faces meet at cos = 1/sqrt(5)).
  std::vector<Eigen::Vector3d> dv;
  for (double a : {-1.0, 1.0})
    for (double b : {-1.0, 1.0}) {
      for (double c : {-1.0, 1.0}) dv.emplace_back(a, b, c);
      dv.emplace_back(0, a / kPhi, b * kPhi);
      dv.emplace_back(a / kPhi, b * kPhi, 0);
      dv.emplace_back(b * kPhi, 0, a / kPhi);
    }
  Mesh m;
  m.vertices = dv;
  std::vector<Eigen::Vector3d> normals;
  for (double a : {-1.0, 1.0})
    for (double b : {-1.0, 1.0}) {
      normals.emplace_back(0, a * kPhi, b);
      normals.emplace_back(a * kPhi, b, 0);
      normals.emplace_back(b, 0, a * kPhi);
    }
  for (const Eigen::Vector3d& nraw : normals) {
    const Eigen::Vector3d n = nraw.normalized();
    double d = -HUGE_VAL;
    for (const auto& v : dv) d = std::max(d, n.dot(v));
    std::vector<uint32_t> face;
    for (uint32_t i = 0; i < dv.size(); ++i)
      if (n.dot(dv[i]) > d - 1e-9) face.push_back(i);
    const Eigen::Vector3d u = n.unitOrthogonal(), w = n.cross(u);
    std::sort(face.begin(), face.end(), [&](uint32_t a, uint32_t b) {
      return std::atan2(w.dot(dv[a]), u.dot(dv[a])) < std::atan2(w.dot(dv[b]), u.dot(dv[b]));
    });
    const uint32_t apex = uint32_t(m.vertices.size());
    m.vertices.push_back(n * d * std::sqrt(5.0));
    for (size_t k = 0; k < face.size(); ++k) m.triangles.push_back({apex, face[k], face[(k + 1) % face.size()]});
  }
  orient_from(m, Eigen::Vector3d::Zero());
  // Scale so that the spike tips are at radius about 1.
  double r = 0;
  for (const auto& v : m.vertices) r = std::max(r, v.norm());
  for (auto& v : m.vertices) v /= r;
  return m;
}

void finish(Mesh& m, const std::string& name) {
  m.name = name;
  prepare(m);
}

}  // namespace

Mesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  // Two triangles per face, outward.
  m.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  m.name = "box";
  return m;
}

Mesh make_icosphere(const Eigen::Vector3d& centre, double radius, int level) {
  Mesh m = icosahedron();
  for (auto& v : m.vertices) v.normalize();
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
    auto midpoint = [&](uint32_t a, uint32_t b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const uint32_t id = uint32_t(m.vertices.size());
      m.vertices.push_back((m.vertices[a] + m.vertices[b]).normalized());
      mid.emplace(key, id);
      return id;
    };
    std::vector<std::array<uint32_t, 3>> next;
    for (const auto& t : m.triangles) {
      const uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
      next.push_back({t[0], ab, ca});
      next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]});
      next.push_back({ab, bc, ca});
    }
    m.triangles = std::move(next);
  }
  for (auto& v : m.vertices) v = centre + radius * v;
  m.name = "icosphere";
  return m;
}

Mesh make_torus(double major, double minor, int n, int mseg) {
  Mesh m;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < mseg; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / mseg;
      const double r = major + minor * std::cos(v);
      m.vertices.emplace_back(r * std::cos(u), r * std::sin(u), minor * std::sin(v));
    }
  auto id = [&](int i, int j) { return uint32_t((i % n) * mseg + (j % mseg)); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < mseg; ++j) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  m.name = "torus";
  return m;
}

std::vector<std::string> shape_names() {
  return {"polytope36", "stellated", "icosahedron", "sphere", "torus", "cube", "plate"};
}

bool is_shape(const std::string& name) {
  const auto v = shape_names();
  return std::find(v.begin(), v.end(), name) != v.end();
}

Mesh make_shape(const std::string& name) {
  Mesh m;
  if (name == "polytope36") m = polytope36();
  else if (name == "stellated") m = stellated();
  else if (name == "icosahedron") m = icosahedron();
  else if (name == "sphere") m = make_icosphere(Eigen::Vector3d::Zero(), 1.0, 3);
  else if (name == "torus") m = make_torus(1.0, 0.35, 64, 16);
  else if (name == "cube") m = make_box(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1));
  else if (name == "plate") m = make_box(Eigen::Vector3d(-1, -1, -0.025), Eigen::Vector3d(1, 1, 0.025));
  else {
    std::string known;
    for (const auto& s : shape_names()) known += (known.empty() ? "" : ", ") + s;
    throw MeshError("unknown shape '" + name + "' (known: " + known + ")");
  }
  finish(m, name);
  return m;
}

}  // namespace voxcd
