#include "voxcd/host/sizing/sweep/contact_measure.h"

#include <algorithm>
#include <stdexcept>

#include "voxcd/host/device/device.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/sizing/sweep/detail/exact_distance.h"
#include "voxcd/host/sizing/size.h"

namespace voxcd {

namespace {

// The pair tests of one frame's broadphase pairs at the bodies' poses.
std::vector<PairRequest> frame_requests(const Simulation& sim) {
  std::vector<PairRequest> reqs;
  const std::vector<Body>& bodies = sim.scene().bodies;
  for (const BodyPair& p : sim.broadphase().pairs()) {
    PairRequest r;
    r.a = bodies.at(p.first).type, r.b = bodies.at(p.second).type;
    r.pose_a = bodies[p.first].pose, r.pose_b = bodies[p.second].pose;
    reqs.push_back(r);
  }
  return reqs;
}

// The signed distance of each checked contact from the other object's mesh, folded into m.
void check_contacts(const Scene& scene, const std::vector<PairRequest>& reqs, const std::vector<PairResult>& res,
                    const std::vector<Mesh>& meshes, uint64_t per_pair, ContactMeasure& m, double& worst) {
  for (size_t i = 0; i < reqs.size(); ++i) {
    const std::vector<Contact>& cs = res[i].contacts;
    const size_t stride = std::max<size_t>(1, (cs.size() + per_pair - 1) / per_pair);
    for (size_t c = 0; c < cs.size(); c += stride) {
      const Contact& ct = cs[c];
      const uint32_t other = ct.a_in_b ? reqs[i].b : reqs[i].a;
      const RigidPose& pose = ct.a_in_b ? reqs[i].pose_b : reqs[i].pose_a;
      const Eigen::Vector3d local = pose.rotation.conjugate() * (ct.position - pose.translation);
      const double d = detail::signed_mesh_distance(meshes.at(other), local);
      const ObjectType& t = *scene.types.at(other);
      const auto& v = ct.voxel;
      if (t.object.distance_near_conservative(Eigen::Vector3d(v[0] + 0.5, v[1] + 0.5, v[2] + 0.5))) {
        m.worst_outside_conservative = std::max(m.worst_outside_conservative, d);
        ++m.conservative;
        continue;
      }
      worst = std::max(worst, d);
      ++m.contacts;
    }
  }
}

}  // namespace

ContactMeasure measure_contacts(const Scene& scene, const RunConfig& f, const DeviceConfig& cfg,
                                const std::vector<Mesh>& meshes, uint64_t frames, uint64_t samples,
                                uint64_t per_pair) {
  if (meshes.size() != scene.types.size())
    throw std::invalid_argument("measure_contacts: " + std::to_string(meshes.size()) + " meshes for " +
                                std::to_string(scene.types.size()) + " types");
  Simulation sim(scene, sizing_sim_options(f, cfg));
  PairCollider collider(make_device("cpu", cfg), scene.types);
  PairOptions po;
  po.mode = Mode::All;
  po.both_directions = f.both_directions;
  ContactMeasure m;
  double worst = 0;
  samples = std::min(samples, frames);
  const uint64_t every = samples ? frames / samples : 0;
  // A sample falls due every `every` frames; a due frame without contacts passes it on to the next frame.
  uint64_t due = every;
  std::vector<PairResult> res;
  for (uint64_t k = 1; k <= frames && m.frames < samples; ++k) {
    sim.step();
    if (k < due) continue;
    const std::vector<PairRequest> reqs = frame_requests(sim);
    collider.collide(reqs, po, res);
    const uint64_t before = m.contacts + m.conservative;
    check_contacts(scene, reqs, res, meshes, per_pair, m, worst);
    if (m.contacts + m.conservative == before) continue;
    m.pairs += reqs.size();
    ++m.frames;
    due = std::max(k + 1, due + every);
  }
  m.worst_outside = worst;
  return m;
}

}  // namespace voxcd
