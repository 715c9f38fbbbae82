// Where repair changed a mesh, for the viewer to mark: what it dropped, moved and turned, and the edges it left open
// or shared by more than two triangles. Found by comparing the triangles as read with the repaired mesh.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "voxcd/host/mesh/mesh.h"

namespace voxcd::view {

struct RepairPlaces {
  std::vector<Eigen::Vector3d> dropped;     // centroids (of the finite corners) of triangles repair dropped
  std::vector<Eigen::Vector3d> moved;       // input vertices welded within tolerance or moved to close a crack
  std::vector<Eigen::Vector3d> reoriented;  // centroids of triangles turned to agree with their neighbours
  std::vector<std::array<Eigen::Vector3d, 2>> open_edges, nonmanifold_edges;  // of the repaired mesh
  std::vector<uint32_t> sheet_triangles;    // repaired triangles of sheets (Mesh::sheet)
};

// `input`: the triangles as read (LoadOptions::repair false); `repaired`: load_mesh's result and `report` its
// MeshReport (a mesh flipped whole marks no triangle as reoriented: the report says so).
RepairPlaces repair_places(const Mesh& input, const Mesh& repaired, const MeshReport& report);

}  // namespace voxcd::view
