// Pair tests on a sparse distance device, for the tests and benchmarks that measure sparse distance fields with
// refined bricks (host/object/sparse_field.h) against exact geometry: objects as voxcd builds them (voxmap grid, the
// shell on the surface) with their sparse field, on the sparse device device_config_for picks (BL 3, SB 8), through
// the pair collider: contacts as host/pairs/contacts.cpp makes them (position from the shell, or for a speculative
// contact on the other surface; depth from D; normal from the sparse field's gradient).
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/sparse_field.h"
#include "voxcd/host/pairs/collide.h"

namespace voxcd::test::sparse {

// An object as the sparse device holds it: its type (grid, voxmap, the shell on the surface, built with an 8-bit
// dense field as make_object builds it) and its sparse field on the same grid.
struct SparseObject {
  std::shared_ptr<const ObjectType> type;
  SparseDistanceField field;
};

// `mesh` as repair() left it, voxelised at `voxel`, with a sparse field refined up to max_level.
inline SparseObject make_sparse_object(const Mesh& mesh, const std::string& name, double voxel, int max_level = 3,
                                       const MeshReport* report = nullptr) {
  ObjectOptions o;
  o.voxel = voxel;
  o.distance_bits = 8;
  SparseObject s;
  s.type = std::make_shared<ObjectType>(make_object_type(make_object(mesh, name, 0, o, report), name));
  SparseFieldOptions so;
  so.distance.bits = 8;
  so.max_level = max_level;
  s.field = sparse_distance_field(mesh, s.type->voxmap().grid(), so);
  return s;
}

// A sparse distance device holding the objects' shells and sparse fields, queried through the pair collider (the
// product's path: its device image, jobs, speculative reach and contacts), on the cpu backend (bit-exact with ref/).
class SparseDevice {
 public:
  explicit SparseDevice(const std::vector<const SparseObject*>& objects) {
    std::vector<std::shared_ptr<const ObjectType>> types;
    std::vector<const ObjectType*> raw;
    for (const SparseObject* o : objects) {
      auto t = std::make_shared<ObjectType>(*o->type);
      t->object.sparse_distance = o->field;  // the field held sparse only
      t->object.distance = DistanceField();
      raw.push_back(t.get());
      types.push_back(std::move(t));
    }
    cfg_ = device_config_for("cpu", 4, raw, 8);
    collider_ = std::make_unique<PairCollider>(make_device("cpu", cfg_), types);
  }
  const DeviceConfig& config() const { return cfg_; }

  // The contacts of object a's shell in object b's field (a_in_b) and, with `both`, of b's in a's, at margin 0,
  // speculative contacts among them unless `speculative` is false.
  std::vector<Contact> collide(uint32_t a, const RigidPose& pa, uint32_t b, const RigidPose& pb, bool both,
                               bool speculative = true) const {
    PairRequest r;
    r.a = a, r.b = b, r.pose_a = pa, r.pose_b = pb;
    PairOptions opt;
    opt.both_directions = both;
    opt.speculative = speculative;
    return collider_->collide({r}, opt).at(0).contacts;
  }

 private:
  DeviceConfig cfg_;
  std::unique_ptr<PairCollider> collider_;
};

// Grid coordinates of a world point in object o's grid at pose p (for SparseDistanceField::near_conservative).
inline Eigen::Vector3d grid_of(const SparseObject& o, const RigidPose& p, const Eigen::Vector3d& world) {
  const Voxmap& vm = o.type->voxmap();
  return (p.rotation.conjugate() * (world - p.translation) - vm.origin()) / vm.voxel();
}

}  // namespace voxcd::test::sparse
