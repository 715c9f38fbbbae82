// Triangle meshes: loading (the paper's RAW triangles, PLY, and every other format assimp reads), repair of the
// defects real exports have (host/mesh/repair.cpp), and the strict validation --strict keeps (finite, non-degenerate,
// closed, edge-manifold, consistently oriented).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/host/mesh/errors.h"

namespace voxcd {

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<uint32_t, 3>> triangles;  // counter-clockwise seen from outside once validated
  std::string name;                                // file or shape name, used in error messages
  // Per triangle, set by repair(): 1 when the triangle belongs to a sheet, a connected part that encloses nothing
  // (its holes are too large for a solid, docs/objects.md): it makes surface voxels and shell points, never
  // interior. Empty: every triangle bounds the solid.
  std::vector<uint8_t> sheet;
  // A point cloud: no triangles, the vertices are the surface (surface voxels and shell points, no interior).
  bool points_only() const { return triangles.empty() && !vertices.empty(); }
  bool is_sheet(size_t t) const { return !sheet.empty() && sheet[t]; }

  size_t size() const { return triangles.size(); }
  Eigen::Vector3d corner(size_t t, int k) const { return vertices[triangles[t][k]]; }
  void bounds(Eigen::Vector3d& lo, Eigen::Vector3d& hi) const;  // AABB of the vertices used by triangles
  // Volume enclosed (divergence theorem); exact up to rounding for a closed mesh, positive when outward.
  double volume() const;
  double area() const;
};

// What loading and repair found and did. Strict validation fills the first four fields only.
struct MeshReport {
  size_t vertices = 0, triangles = 0;  // after repair
  size_t welded = 0;    // vertices merged: exactly equal coordinates, or (repair) within weld_tolerance
  bool flipped = false; // the mesh was inside out (negative volume) and every triangle was reversed
  // Repair (host/mesh/repair.cpp):
  size_t input_vertices = 0, input_triangles = 0;
  double weld_tolerance = 0;        // absolute: kWeldRelative x the diagonal of the bounding box
  size_t welded_near = 0;           // of those, vertices merged with one that was not exactly equal
  size_t dropped_nonfinite = 0;     // triangles with a NaN or infinite corner
  size_t dropped_repeated = 0;      // triangles with a repeated vertex (after welding)
  size_t dropped_collinear = 0;     // triangles of zero area (collinear corners)
  size_t dropped_duplicate = 0;     // exact duplicates of another triangle (same vertices, either orientation)
  size_t reoriented = 0;            // triangles reversed to make orientation consistent
  size_t open_edges = 0;            // edges used by one triangle (after repair)
  size_t nonmanifold_edges = 0;     // edges used by more than two triangles (found, before what repair did)
  size_t nonmanifold_parts = 0;     // edge-connected parts with such edges, decided by the cells they bound
  size_t dropped_internal = 0;      // of those parts, triangles with solid on both sides (shared faces, membranes)
  size_t fin_triangles = 0;         // of those parts, triangles with empty space on both sides (fins): sheets
  size_t inconsistent_edges = 0;    // edges whose two triangles still disagree (a non-orientable surface)
  size_t components = 0;            // edge-connected parts
  size_t closed_components = 0;     // parts that are closed and consistently oriented
  size_t sheet_components = 0;      // parts that enclose nothing (Mesh::sheet)
  bool closed = false;              // the input was a closed, manifold, consistently oriented mesh
  bool points_only = false;         // a point cloud (no triangles)
  bool surface_only = false;        // nothing encloses a volume: no interior (sheets only, or a point cloud)
  bool repaired() const {
    return welded_near || dropped_nonfinite || dropped_repeated || dropped_collinear || dropped_duplicate ||
           dropped_internal || reoriented || flipped;
  }
};

// Vertices closer than this fraction of the bounding box's diagonal are welded by repair().
constexpr double kWeldRelative = 1e-7;
// Vertices on open edges of different edge-connected parts closer than this fraction of the diagonal are joined by
// repair(): cracks between parts close.
constexpr double kCrackCloseRelative = 2e-3;

struct LoadOptions {
  bool strict = false;  // refuse anything that is not a closed, edge-manifold, consistently oriented mesh
  bool repair = true;   // false (and not strict): the triangles as read, nothing dropped or welded (to show repairs)
};

// Loads a mesh by file extension through the reader of its format (host/mesh/formats/): .raw through parse_raw,
// .ply through voxcd's own reader (assimp 5.2's hangs on damaged files), everything else through assimp. Then repairs it (repair()), or with opt.strict welds and
// validates it (prepare()). Throws MeshError naming the file (and line or triangle) when the file cannot be read
// or holds neither triangles nor points, and in strict mode for any defect.
Mesh load_mesh(const std::string& path, MeshReport* report = nullptr, const LoadOptions& opt = {});

// The paper's RAW triangle format: one triangle per line as nine numbers "x1 y1 z1 x2 y2 z2 x3 y3 z3" (as assimp reads
// it, also preceded by a colour "r g b" or "r g b a", or followed by a texture name);
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

// weld + validate: the strict path (built-in shapes, --strict).
MeshReport prepare(Mesh& m);

// Repairs a triangle soup (host/mesh/repair.cpp): drops non-finite and degenerate triangles and exact duplicates, welds
// vertices within kWeldRelative of the model's size, closes cracks between parts (kCrackCloseRelative), decides parts
// with non-manifold edges by the cells of space they bound (internal faces dropped, fins made sheets), orients each
// part consistently where the surface allows it (outward, nested closed parts alternating, so cavities stay empty),
// marks sheets, and reports it all.
// MeshError only when nothing is left: no triangle and no finite point.
MeshReport repair(Mesh& m);

}  // namespace voxcd
