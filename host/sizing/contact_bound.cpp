#include "voxcd/host/sizing/contact_bound.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "voxcd/host/mesh/convex.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/sizing/digits.h"
#include "voxcd/host/sizing/size.h"

namespace voxcd {

namespace {
std::string num(double v) { return detail::digits_text(v, 4); }
}  // namespace

double VoxmapKind::step() const { return distance() ? band * std::ldexp(1.0, 1 - SB) : 0; }

std::string VoxmapKind::text() const {
  if (!distance()) return "2-bit states";
  return "SB " + std::to_string(SB) + " WB " + std::to_string(WB) + ", band " + num(band) + " voxels (step " +
         num(step()) + " voxel)";
}

ContactTerms contact_terms(const VoxmapKind& k, bool convex_b) {
  ContactTerms t;
  if (!k.distance()) {
    t.cell = std::sqrt(3.0);
    return t;
  }
  const double s = k.step();
  t.quantisation = s / 2;
  t.weights = (1 + s) * 3 * std::ldexp(1.0, -k.WB);
  t.interpolation = convex_b ? 0 : kConcaveInterpolation;
  return t;
}

std::vector<bool> types_convex(const RunConfig& f) {
  std::vector<bool> convex;
  for (const SceneTypeSpec& t : f.types) convex.push_back(is_convex(load_source(t.mesh.empty() ? t.shape : t.mesh)));
  return convex;
}

double band_for_motion(const Scene& scene, const RunConfig& f) {
  double fastest = 0, vmin = 0;
  for (const auto& t : scene.types) {
    fastest = std::max(fastest, (f.speed + f.spin) * t->radius);
    vmin = vmin > 0 ? std::min(vmin, t->voxmap().voxel()) : t->voxmap().voxel();
  }
  return std::max(3.0, std::ceil(2 * fastest / vmin));
}

VoxmapKind choose_voxmap(const Scene& scene, const std::vector<bool>& convex, double accuracy, double fixed,
                         double band, bool need_distance, int max_wb) {
  if (!(accuracy > fixed))
    throw SizeError("contact", fixed / accuracy,
                    "the fixed-point path alone may move a point by " + num(fixed) + " world units; a contact bound "
                    "of " + num(accuracy) + " needs a finer --accuracy");
  // The kind must meet the bound on the coarsest voxel of each convexity (the terms scale with B's voxel).
  const auto meets = [&](const VoxmapKind& k) {
    for (size_t i = 0; i < scene.types.size(); ++i)
      if (scene.types[i]->voxmap().voxel() * contact_terms(k, convex.at(i)).total() + fixed > accuracy) return false;
    return true;
  };
  if (!need_distance && meets(VoxmapKind{})) return VoxmapKind{};
  for (int sb : {4, 8, 16})
    for (int wb = 1; wb <= max_wb; ++wb) {
      const VoxmapKind k{sb, wb, band};
      if (meets(k)) return k;
    }
  // None: name the type that fails most and the voxel that would meet the bound with the finest kind.
  const VoxmapKind finest{16, max_wb, band};
  size_t worst = 0;
  double worst_err = 0;
  for (size_t i = 0; i < scene.types.size(); ++i) {
    const double e = scene.types[i]->voxmap().voxel() * contact_terms(finest, convex.at(i)).total() + fixed;
    if (e > worst_err) worst_err = e, worst = i;
  }
  const ObjectType& t = *scene.types[worst];
  const double terms = contact_terms(finest, convex.at(worst)).total();
  throw SizeError("contact", (worst_err - fixed) / (accuracy - fixed),
                  "type " + t.name + (convex.at(worst) ? "" : " (not convex)") + " at voxel " +
                      num(t.voxmap().voxel()) + " bounds contacts at " + num(worst_err) + " world units even with " +
                      finest.text() + "; " + num(accuracy) + " needs its voxel at most " +
                      num((accuracy - fixed) / terms));
}

}  // namespace voxcd
