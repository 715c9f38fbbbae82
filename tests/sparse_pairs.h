// Pair tests on a sparse distance device, for the tests and benchmarks that measure sparse distance fields with
// refined bricks (host/object/sparse_field.h) against exact geometry: objects as voxcd builds them (voxmap grid, the
// shell on the surface) with their sparse field, placed in a sparse device's memories (BL 3, SB 8: table words, then
// bricks), jobs built by host/pairs/pose.h, run by ref's run_stream, and hits made contacts the way
// host/pairs/contacts.cpp makes them on a distance device (position from the shell, depth from D, normal from the
// field's gradient, here the sparse field's).
#pragma once

#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/sparse_field.h"
#include "voxcd/host/pairs/contact.h"
#include "voxcd/host/pairs/image.h"
#include "voxcd/host/pairs/pose.h"
#include "voxcd/ref/pipeline.h"
#include "voxcd/ref/sparse.h"

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

// A sparse distance device on ref/ holding the objects' shells and sparse maps.
class SparseDevice {
 public:
  explicit SparseDevice(const std::vector<const SparseObject*>& objects) : objects_(objects) {
    cfg_.SB = 8;
    cfg_.BL = 3;
    std::vector<const ObjectType*> types;
    for (const SparseObject* o : objects) types.push_back(o->type.get());
    cfg_.MW = matrix_width_for(cfg_, types);
    for (const SparseObject* o : objects) place(*o);
    while (cfg_.shell_depth() < mem_.shell.size()) ++cfg_.SAW;
    while (cfg_.map_depth() < mem_.map.size()) ++cfg_.MAW;
    cfg_.validate();
  }
  const DeviceConfig& config() const { return cfg_; }

  // The contacts of object a's shell in object b's field (a_in_b) and, with `both`, of b's in a's, at margin 0.
  std::vector<Contact> collide(uint32_t a, const RigidPose& pa, uint32_t b, const RigidPose& pb, bool both) const {
    std::vector<Job> jobs = {job(a, pa, b, pb, 0)};
    if (both) jobs.push_back(job(b, pb, a, pa, 1));
    const std::vector<Record> recs = run_stream(cfg_, mem_, jobs);
    std::vector<Contact> out;
    for (const Record& r : recs)
      if (r.kind == Record::Hit)
        out.push_back(r.tag == 0 ? contact(a, pa, b, pb, r, true) : contact(b, pb, a, pa, r, false));
    return out;
  }

 private:
  struct Placement {
    uint32_t shell_base, shell_count, map_base, brick_base, brick_units;
  };

  void place(const SparseObject& o) {
    Placement p;
    const std::vector<ShellWord> sw = o.type->shell().words(cfg_);
    p.shell_base = uint32_t(mem_.shell.size());
    p.shell_count = uint32_t(sw.size());
    mem_.shell.insert(mem_.shell.end(), sw.begin(), sw.end());
    const SparseImage im = o.field.device_image(cfg_);
    mem_.map.resize((mem_.map.size() + 7) / 8 * 8, 0);
    p.map_base = uint32_t(mem_.map.size());
    mem_.map.insert(mem_.map.end(), im.table.begin(), im.table.end());
    mem_.map.resize((mem_.map.size() + 7) / 8 * 8, 0);
    p.brick_base = uint32_t(mem_.map.size());
    p.brick_units = uint32_t(im.brick_units);
    mem_.map.insert(mem_.map.end(), im.bricks.begin(), im.bricks.end());
    placements_.push_back(p);
  }

  Job job(uint32_t s, const RigidPose& ps, uint32_t m, const RigidPose& pm, uint32_t tag) const {
    const ObjectType& st = *objects_[s]->type;
    const ObjectType& mt = *objects_[m]->type;
    Job j;
    j.tag = tag;
    j.mode = Mode::All;
    j.shell_base = placements_[s].shell_base;
    j.shell_count = placements_[s].shell_count;
    j.map_base = placements_[m].map_base;
    j.nx = mt.voxmap().dims()[0];
    j.ny = mt.voxmap().dims()[1];
    j.nz = mt.voxmap().dims()[2];
    j.sparse = kSparseMap;
    j.brick_base = placements_[m].brick_base;
    j.brick_units = placements_[m].brick_units;
    pose_job(cfg_, ps, st.shell().frame(), pm, mt.voxmap().grid().frame(), j);
    j.threshold = distance_threshold(cfg_, 0.0, mt.voxmap().voxel(), objects_[m]->field.step());
    return j;
  }

  Contact contact(uint32_t s, const RigidPose& ps, uint32_t m, const RigidPose& pm, const Record& r,
                  bool a_in_b) const {
    const ObjectType& st = *objects_[s]->type;
    const ObjectType& mt = *objects_[m]->type;
    const SparseDistanceField& f = objects_[m]->field;
    const Eigen::Matrix3d Rs = ps.rotation.toRotationMatrix(), Rm = pm.rotation.toRotationMatrix();
    Contact c;
    c.a_in_b = a_in_b;
    c.point = r.point;
    c.position = Rs * st.shell().points[r.point] + ps.translation;
    c.voxel = {r.x, r.y, r.z};
    c.depth = -double(r.dist) * mt.voxmap().voxel() * f.step() / std::ldexp(1.0, 3 * cfg_.WB);
    const Eigen::Vector3d g =
        (Rm.transpose() * (c.position - pm.translation) - mt.voxmap().origin()) / mt.voxmap().voxel();
    Eigen::Vector3d grad;
    f.sample(g, &grad);
    const Eigen::Vector3d n = -(Rm * grad);
    c.normal =
        n.squaredNorm() > 1e-24 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d(Rs * st.shell().normals[r.point]);
    return c;
  }

  std::vector<const SparseObject*> objects_;
  DeviceConfig cfg_;
  DeviceMemory mem_;
  std::vector<Placement> placements_;
};

// Grid coordinates of a world point in object o's grid at pose p (for SparseDistanceField::near_conservative).
inline Eigen::Vector3d grid_of(const SparseObject& o, const RigidPose& p, const Eigen::Vector3d& world) {
  const Voxmap& vm = o.type->voxmap();
  return (p.rotation.conjugate() * (world - p.translation) - vm.origin()) / vm.voxel();
}

}  // namespace voxcd::test::sparse
