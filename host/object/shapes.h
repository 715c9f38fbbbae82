// Built-in solids generated in code, closed and outward oriented, about 2 units across and centred on the
// origin: the paper's test objects and a few simple ones.
#pragma once

#include <string>
#include <vector>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd {

// "polytope36" (the paper's irregular convex polytope: 20 vertices on an ellipsoid, 36 faces),
// "stellated" (small stellated dodecahedron, concave, 60 faces), "icosahedron", "sphere" (icosphere, 1280
// faces, radius 1), "torus" (radii 1 and 0.35, 2048 faces), "cube" (side 2), "plate" (2 x 2 x 0.05).
std::vector<std::string> shape_names();
bool is_shape(const std::string& name);
// The shape, welded and validated (name = the shape's name). Throws MeshError for an unknown name, listing
// the known ones.
Mesh make_shape(const std::string& name);

// An axis-aligned box [lo, hi], 12 triangles, outward.
Mesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);
// An icosphere: the icosahedron subdivided `level` times, vertices on the sphere.
Mesh make_icosphere(const Eigen::Vector3d& centre, double radius, int level);
// A torus around the z axis: n segments around the axis, m around the tube.
Mesh make_torus(double major, double minor, int n, int m);

}  // namespace voxcd
