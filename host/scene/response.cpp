// The response: a touching pair pushed apart along its contact normal (respond), applied to a frame's tested pairs
// in pair order (Simulation::respond_all).
#include "voxcd/host/scene/response.h"

#include <Eigen/Geometry>

#include "voxcd/host/scene/scene.h"

namespace voxcd {

bool respond(Body& a, Body& b, const Eigen::Vector3d& n) {
  const double closing = (b.velocity - a.velocity).dot(n);
  if (closing >= 0) return false;
  if (a.pushed() && b.pushed()) {
    a.velocity += closing * n;
    b.velocity -= closing * n;
    a.spin = -a.spin;
    b.spin = -b.spin;
    return true;
  }
  // Against a body the response does not push (of infinite mass): the relative velocity along n is reflected.
  if (a.pushed()) {
    a.velocity += 2 * closing * n;
    a.spin = -a.spin;
    return true;
  }
  if (b.pushed()) {
    b.velocity -= 2 * closing * n;
    b.spin = -b.spin;
    return true;
  }
  return false;
}

void Simulation::respond_all(FrameStats& st) {
  for (const PairOutcome& o : outcomes_) {
    st.lookups += o.lookups;
    st.hits += o.hits;
    st.contacts += o.contacts;
    if (o.hits == 0) continue;
    ++st.touching;
    if (!opt_.response) continue;  // found and reported only (WorldDef::response)
    Body &a = scene_.bodies[o.a], &b = scene_.bodies[o.b];
    // The normal from A towards B (PairOutcome::normal); the line between the bounding spheres' centres when the
    // contacts give none (COUNT, or normals that cancel).
    Eigen::Vector3d nrm = o.normal;
    if (nrm.squaredNorm() < 1e-12) nrm = bounds_[o.b].centre - bounds_[o.a].centre;
    if (nrm.squaredNorm() < 1e-24) nrm = Eigen::Vector3d::UnitX();
    nrm.normalize();
    if (!respond(a, b, nrm)) continue;  // separating already
    moved_[o.a] = moved_[o.b] = 1;
    ++st.responses;
  }
}

}  // namespace voxcd
