// Shared by the object-pipeline tests: the seed, mesh writers, and brute-force references.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/object/voxelize.h"
#include "tests/exact_geometry.h"
#include "tests/seed.h"

namespace voxcd::test {

inline std::string tmp_path(const std::string& name) {
  return ::testing::TempDir() + "voxcd_" + std::to_string(::getpid()) + "_" + name;
}

inline void write_file(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// Wavefront OBJ, indexed.
// A file's bytes ("" when it cannot be read).
inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline void write_obj(const Mesh& m, const std::string& path) {
  std::ofstream o(path);
  o.precision(17);
  for (const auto& v : m.vertices) o << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : m.triangles) o << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
}

// ASCII STL: every triangle has its own three vertices, so loading must weld them.
inline void write_stl(const Mesh& m, const std::string& path) {
  std::ofstream o(path);
  o.precision(17);
  o << "solid test\n";
  for (size_t t = 0; t < m.size(); ++t) {
    o << " facet normal 0 0 0\n  outer loop\n";
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = m.corner(t, k);
      o << "   vertex " << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    }
    o << "  endloop\n endfacet\n";
  }
  o << "endsolid test\n";
}

// ASCII PLY, indexed.
inline void write_ply(const Mesh& m, const std::string& path) {
  std::ofstream o(path);
  o.precision(17);
  o << "ply\nformat ascii 1.0\nelement vertex " << m.vertices.size()
    << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << m.size()
    << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& v : m.vertices) o << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  for (const auto& t : m.triangles) o << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

// Triangle a, b, c against the axis-aligned cube centred at c0 with half side h (separating axes, no shortcuts).
inline bool tri_box_reference(const Eigen::Vector3d& c0, double h, Eigen::Vector3d a, Eigen::Vector3d b,
                              Eigen::Vector3d c) {
  a -= c0;
  b -= c0;
  c -= c0;
  const Eigen::Vector3d e[3] = {b - a, c - b, a - c};
  std::vector<Eigen::Vector3d> axes = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                       Eigen::Vector3d::UnitZ(), e[0].cross(e[1])};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) axes.push_back(Eigen::Vector3d::Unit(i).cross(e[k]));
  for (const auto& ax : axes) {
    const double r = h * ax.cwiseAbs().sum();
    const double p0 = ax.dot(a), p1 = ax.dot(b), p2 = ax.dot(c);
    if (std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r) return false;
  }
  return true;
}

// Checks every voxel of vm against brute force on the mesh as given: a voxel the surface touches must be
// Surface; a Surface voxel must be touched once grown by 2^-17 voxel; any other voxel is Interior exactly when
// its centre is inside. Returns the number of failures (each reported).
inline int check_voxels(const Mesh& m, const Voxmap& vm) {
  int bad = 0;
  const auto& d = vm.dims();
  const double s = vm.voxel();
  for (uint32_t z = 0; z < d[2]; ++z)
    for (uint32_t y = 0; y < d[1]; ++y)
      for (uint32_t x = 0; x < d[0]; ++x) {
        const Eigen::Vector3d c = vm.centre(x, y, z);
        bool touched = false, near = false;
        for (size_t t = 0; t < m.size() && !touched; ++t) {
          const Eigen::Vector3d a = (m.corner(t, 0) - vm.origin()) / s, b = (m.corner(t, 1) - vm.origin()) / s,
                                cc = (m.corner(t, 2) - vm.origin()) / s;
          const Eigen::Vector3d g(x + 0.5, y + 0.5, z + 0.5);
          if (tri_box_reference(g, 0.5, a, b, cc)) touched = true;
          if (!near && tri_box_reference(g, 0.5 + 1.0 / (1 << 17), a, b, cc)) near = true;
        }
        const VoxelState st = vm.at(x, y, z);
        std::string why;
        if (touched && st != kSurface) why = "touched by the surface but not Surface";
        if (st == kSurface && !near && !touched) why = "Surface but not touched";
        if (!near && !touched && st != kSurface) {
          const bool in = inside_reference(m, c);
          if (in != (st == kInterior)) why = in ? "centre inside but Empty" : "centre outside but Interior";
        }
        if (!why.empty() && ++bad <= 10)
          ADD_FAILURE() << m.name << ": voxel (" << x << ", " << y << ", " << z << ") state " << int(st) << ": "
                        << why;
      }
  return bad;
}

}  // namespace voxcd::test
