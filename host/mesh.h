// Triangle meshes: loading (the paper's RAW triangles, PLY, and every other format assimp reads), welding of exactly equal
// vertices, and validation (finite, non-degenerate, closed, edge-manifold, consistently oriented).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

namespace voxcd {

// Bad mesh input: says what is wrong and where (file and line, triangle or edge index).
struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;  // counter-clockwise seen from outside once validated
  std::string name;                                // file or shape name, used in error messages

  size_t size() const { return triangles.size(); }
  Eigen::Vector3d corner(size_t t, int k) const { return vertices[triangles[t][k]]; }
  void bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const;  // AABB of the vertices used by triangles
  // Volume enclosed (divergence theorem); exact up to rounding for a closed mesh, positive when outward.
  double volume() const;
  double area() const;
};

struct MeshReport {
  size_t vertices = 0, triangles = 0;
  size_t welded = 0;    // vertices merged because their coordinates were exactly equal
  bool flipped = false; // the mesh was inside out (negative volume) and every triangle was reversed
};

// Loads a mesh by file extension: .raw through parse_raw, .ply through its own reader (assimp 5.2's hangs on
// damaged files), everything else through assimp. Then welds and validates. Throws MeshError naming the file (and line or triangle) on any problem.
Mesh load_mesh(const std::string& path, MeshReport* report = nullptr);

// The paper's RAW triangle format: one triangle per line as nine numbers "x1 y1 z1 x2 y2 z2 x3 y3 z3";
// blank lines and lines starting with '#' are ignored, a line holding a single word names the next object.
// Only parses (no welding or validation); MeshError names `name` and the line.
Mesh parse_raw(std::istream& in, const std::string& name);
// Writes the RAW format (17 significant digits, so a round trip is exact).
void write_raw(const Mesh& m, std::ostream& out);

// Merges vertices with exactly equal coordinates and drops vertices no triangle uses; returns how many merged.
size_t weld(Mesh& m);

// Throws MeshError for: no triangles, an index out of range, a NaN or infinite coordinate, a degenerate
// triangle (repeated vertex or zero area), an edge used by one triangle (open), by more than two (non-manifold)
// or twice in the same direction (inconsistent orientation). Reverses every triangle when the volume is
// negative (reported in `flipped`). Expects a welded mesh.
void validate(Mesh& m, MeshReport* report = nullptr);

// weld + validate.
MeshReport prepare(Mesh& m);

}  // namespace voxcd
