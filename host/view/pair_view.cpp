#include "voxcd/host/view/pair_view.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "voxcd/host/object/voxmap_surface.h"
#include "voxcd/host/pairs/pose_text.h"
#include "voxcd/host/detail/base64.h"

namespace voxcd::view {

namespace {

using nlohmann::json;

json vec(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

json type_json(const std::string& name, const ObjectType& t) {
  const bool from_mesh = t.mesh && !t.mesh->triangles.empty();
  const Mesh surface = from_mesh ? *t.mesh : voxmap_surface(t.voxmap());
  std::vector<float> verts, pts, nrm;
  std::vector<uint32_t> idx;
  for (const auto& p : surface.vertices) verts.insert(verts.end(), {float(p.x()), float(p.y()), float(p.z())});
  for (const auto& tri : surface.triangles) idx.insert(idx.end(), tri.begin(), tri.end());
  for (size_t k = 0; k < t.shell().size(); ++k) {
    const auto& p = t.shell().points[k];
    const auto& n = t.shell().normals[k];
    pts.insert(pts.end(), {float(p.x()), float(p.y()), float(p.z())});
    nrm.insert(nrm.end(), {float(n.x()), float(n.y()), float(n.z())});
  }
  return {{"name", name}, {"voxel", t.voxmap().voxel()}, {"centre", vec(t.centre)}, {"radius", t.radius},
          {"surface", {{"from_mesh", from_mesh}, {"vertices", detail::base64(verts)},
                       {"triangles", detail::base64(idx)}, {"triangle_count", surface.triangles.size()}}},
          {"shell", {{"count", t.shell().size()}, {"points", detail::base64(pts)}, {"normals", detail::base64(nrm)}}}};
}

}  // namespace

PairPose parse_pair_pose(const std::string& s) {
  const RigidPose pose = parse_pose(s);
  // Three or six plain numbers are kept as typed (the page shows them); another form's rotation becomes degrees.
  const bool plain = s.find_first_of("[{") == std::string::npos && std::count(s.begin(), s.end(), ',') < 6;
  if (plain) {
    PairPose p{};
    std::istringstream in(s);
    std::string item;
    for (size_t i = 0; i < p.size() && std::getline(in, item, ','); ++i) p[i] = std::stod(item);
    return p;
  }
  const Eigen::Vector3d d = euler_degrees(pose.rotation);
  return {pose.translation.x(), pose.translation.y(), pose.translation.z(), d.x(), d.y(), d.z()};
}

PairView::PairView(const std::string& a, const std::string& b, const PairViewOptions& opt)
    : a_name_(a), b_name_(b), backend_(opt.backend) {
  const double voxel = opt.voxel > 0 ? opt.voxel : shared_voxel({a, b}, opt.resolution);
  a_ = std::make_shared<ObjectType>(load_object_type(a, voxel, opt.distance_bits, opt.band));
  b_ = std::make_shared<ObjectType>(load_object_type(b, voxel, opt.distance_bits, opt.band));
  const DeviceConfig cfg = device_config_for(opt.backend, 4, {a_.get(), b_.get()}, opt.distance_bits);
  collider_ = std::make_unique<PairCollider>(make_device(opt.backend, cfg),
                                             std::vector<std::shared_ptr<const ObjectType>>{a_, b_});
  opt_.both_directions = opt.both_directions;
  opt_.margin = opt.margin;
}

PairPose PairView::default_pose() const {
  const Eigen::Vector3d t = a_->centre + Eigen::Vector3d::UnitX() * 0.75 * (a_->radius + b_->radius) - b_->centre;
  return {t.x(), t.y(), t.z(), 0, 0, 0};
}

std::string PairView::contacts_json(const PairPose& pose) {
  PairRequest r;
  r.a = 0;
  r.b = 1;
  r.pose_b = euler_pose({pose[0], pose[1], pose[2]}, {pose[3], pose[4], pose[5]});
  const PairResult res = collider_->collide({r}, opt_).at(0);
  json contacts = json::array();
  for (const Contact& c : res.contacts)
    contacts.push_back({{"shell", c.a_in_b ? "A" : "B"}, {"point", c.point}, {"position", vec(c.position)},
                        {"normal", vec(c.normal)}, {"depth", c.depth}});
  json j = {{"pose", pose}, {"hits", res.hits}, {"lookups", res.lookups}, {"contacts", contacts}};
  j["device_cycles"] = collider_->device().models_cycles() ? json(res.device_cycles) : json(nullptr);
  return j.dump();
}

std::string PairView::page_json(const PairPose& pose) {
  json j = {{"kind", "pair"}, {"backend", backend_}, {"both_directions", opt_.both_directions},
            {"a", type_json(a_name_, *a_)}, {"b", type_json(b_name_, *b_)}};
  j["result"] = json::parse(contacts_json(pose));
  return j.dump();
}

}  // namespace voxcd::view
