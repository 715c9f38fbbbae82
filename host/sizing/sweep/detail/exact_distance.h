// Internal to host/sizing (the sweep's measured contact error) and shared with the tests and benchmarks that check
// results against the meshes themselves: exact geometry by brute force over a mesh's triangles.
#pragma once

#include <Eigen/Core>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd::detail {

// Whether p lies inside the closed mesh m: the parity of crossings along a fixed generic direction
// (Moller-Trumbore).
bool inside_mesh(const Mesh& m, const Eigen::Vector3d& p);

// The distance from p to the triangle a, b, c (Ericson, Real-Time Collision Detection, 5.1.5).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c);

// The distance from p to the surface of m (the nearest of its triangles).
double mesh_distance(const Mesh& m, const Eigen::Vector3d& p);

// The signed distance from p to the closed mesh m: negative inside, positive outside.
double signed_mesh_distance(const Mesh& m, const Eigen::Vector3d& p);

}  // namespace voxcd::detail
