// What the benchmarks that compare with FCL share: a mesh as FCL's OBBRSS hierarchy, a pose as FCL's transform,
// and a mesh moved to a pose (for exact geometry in world coordinates).
#pragma once

#include <fcl/fcl.h>

#include <memory>
#include <vector>

#include "voxcd/host/object/frame.h"
#include "voxcd/host/mesh/mesh.h"

namespace voxcd::bench {

using Bvh = fcl::BVHModel<fcl::OBBRSSd>;

inline std::shared_ptr<Bvh> bvh_of(const Mesh& m) {
  auto model = std::make_shared<Bvh>();
  std::vector<fcl::Vector3d> v(m.vertices.begin(), m.vertices.end());
  std::vector<fcl::Triangle> t;
  for (const auto& tri : m.triangles) t.emplace_back(tri[0], tri[1], tri[2]);
  model->beginModel();
  model->addSubModel(v, t);
  model->endModel();
  return model;
}

inline fcl::Transform3d to_fcl(const RigidPose& p) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = p.rotation.toRotationMatrix();
  t.translation() = p.translation;
  return t;
}

inline Mesh transformed(const Mesh& m, const RigidPose& pose) {
  Mesh out = m;
  for (auto& v : out.vertices) v = pose.rotation * v + pose.translation;
  return out;
}

}  // namespace voxcd::bench
