// Pair queries against FCL, on the same meshes and poses in the same run: the time of voxcd's pair test on the
// cpu backend (A's shell in B's voxmap, ALL contacts; and both directions) beside FCL's all-contacts collision
// query (OBBRSS bounding volume hierarchies), with the error of each against exact geometry. Writes Markdown to
// stdout (and to --out FILE).
#include <fcl/fcl.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "bench/bench_common.h"
#include "bench/fcl_common.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/object/shapes.h"
#include "tests/exact_geometry.h"

using namespace voxcd;

namespace {

using bench::bvh_of;
using bench::to_fcl;
using bench::transformed;


}  // namespace

int main(int argc, char** argv) {
  std::string out_path;
  int repeats = 5;
  size_t poses = 60;
  std::vector<double> voxels = {0.08, 0.04, 0.02};
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--poses") && i + 1 < argc) poses = size_t(std::atol(argv[++i]));
    else if (!std::strcmp(argv[i], "--voxel") && i + 1 < argc) voxels = {std::atof(argv[++i])};
    else {
      std::fprintf(stderr, "usage: bench_pair [--out FILE] [--repeats N] [--poses N] [--voxel S]\n");
      return 2;
    }
  }
  const std::string provenance = bench::provenance(argc, argv);
  // Two interlocking-prone concave meshes of 10,000 triangles each.
  Mesh ma = make_torus(1.0, 0.35, 100, 50);
  ma.name = "torus (10000 triangles)";
  Mesh mb = make_torus(0.8, 0.3, 100, 50);
  mb.name = "torus (10000 triangles)";
  auto fa = bvh_of(ma), fb = bvh_of(mb);

  std::mt19937_64 rng(5);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PairRequest> reqs;
  for (size_t k = 0; k < poses; ++k) {
    PairRequest r;
    r.a = 0;
    r.b = 1;
    r.pose_a.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    r.pose_b.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    r.pose_b.translation = Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized() * 1.2 * std::cbrt(u(rng));
    reqs.push_back(r);
  }

  // FCL: all contacts, every pose, median over repeats of the whole set.
  std::vector<bool> fcl_hit(poses);
  size_t fcl_contacts = 0;
  const double fcl_t = bench::median_time(repeats, [&] {
    fcl_contacts = 0;
    for (size_t k = 0; k < poses; ++k) {
      fcl::CollisionRequestd req(1000000, true);
      fcl::CollisionResultd res;
      fcl::CollisionObjectd oa(fa, to_fcl(reqs[k].pose_a)), ob(fb, to_fcl(reqs[k].pose_b));
      fcl::collide(&oa, &ob, req, res);
      fcl_hit[k] = res.isCollision();
      fcl_contacts += res.numContacts();
    }
  });
  size_t fcl_touching = 0;
  for (bool h : fcl_hit) fcl_touching += h;

  std::ostringstream md;
  md << provenance << "\n\n";
  md << "Meshes: A = " << ma.name << ", B = " << mb.name << "; " << poses
     << " random poses with B's centre within 1.2 of A's (most interpenetrate), the same poses for every method. "
        "Times are per pair query, medians of "
     << repeats << " runs over all poses. voxcd: cpu backend, one thread and all threads, ALL contacts. FCL "
     << FCL_VERSION << ": `fcl::collide` on OBBRSS hierarchies with all contacts (exact triangle intersections).\n\n"
     << "| method | voxel | shell points A/B | us per query | ratio (FCL / this) | contacts per query | touching poses | max false-contact distance | the same along the grid's axes | deepest missed penetration |\n"
     << "|---|---|---|---|---|---|---|---|---|---|\n"
     << "| FCL all contacts | - | - | " << bench::fmt("%.1f", fcl_t * 1e6 / double(poses)) << " | 1.0 | " << bench::fmt("%.0f", double(fcl_contacts) / double(poses)) << " | " << fcl_touching
     << " | 0 (exact) | 0 (exact) | 0 (exact) |\n";
  for (double voxel : voxels) {
    ObjectOptions o;
    o.voxel = voxel;
    auto ta = std::make_shared<ObjectType>(make_object_type(make_object(ma, "torus A", 0, o), "torus A"));
    auto tb = std::make_shared<ObjectType>(make_object_type(make_object(mb, "torus B", 0, o), "torus B"));
    const DeviceConfig cfg = fit_memory(DeviceConfig{}, {ta.get(), tb.get()});
    for (bool both : {false, true}) {
      for (unsigned threads : {1u, 0u}) {
        DeviceOptions dopt;
        dopt.threads = threads;
        PairCollider col(make_device("cpu", cfg, dopt), {ta, tb});
        PairOptions opt;
        opt.both_directions = both;
        // The results of every pose, for the error measurement below (untimed).
        const std::vector<PairResult> res = col.collide(reqs, opt);
        // One query at a time, as an application asks them, reusing the collider's and the result's buffers.
        std::vector<PairResult> one;
        std::vector<PairRequest> req(1);
        const double t = bench::median_time(repeats, [&] {
          for (size_t k = 0; k < reqs.size(); ++k) {
            req[0] = reqs[k];
            col.collide(req, opt, one);
          }
        });
        size_t touching = 0, contacts = 0;
        for (const auto& r : res) touching += r.hits > 0, contacts += r.contacts.size();
        // Error against exact geometry (first configuration of each voxel size only: it is the same for every
        // thread count): the farthest contact outside the other mesh, and the deepest penetration of a pose
        // FCL says collides but voxcd misses (lower bound from the meshes' vertices inside the other).
        std::string false_dist = "-", false_max = "-", missed = "-";
        if (threads == 1) {
          double worst_out = 0, worst_out_max = 0, worst_missed = 0;
          std::mt19937_64 pick(7);
          for (size_t k = 0; k < poses; ++k) {
            const Mesh wa = transformed(ma, reqs[k].pose_a), wb = transformed(mb, reqs[k].pose_b);
            const auto& cs = res[k].contacts;
            for (size_t s = 0; s < std::min<size_t>(cs.size(), 40); ++s) {
              const Contact& c = cs[pick() % cs.size()];
              const Mesh& other = c.a_in_b ? wb : wa;
              if (!test::inside_reference(other, c.position)) {
                worst_out = std::max(worst_out, test::mesh_distance(other, c.position));
                // The max norm along the other object's grid axes: its mesh in its own frame.
                const RigidPose& pose = c.a_in_b ? reqs[k].pose_b : reqs[k].pose_a;
                worst_out_max = std::max(worst_out_max,
                                         test::mesh_distance_max_norm(c.a_in_b ? mb : ma, pose.rotation.conjugate() *
                                                                      (c.position - pose.translation)));
              }
            }
            if (fcl_hit[k] && res[k].hits == 0) {
              for (const auto& v : wa.vertices)
                if (test::inside_reference(wb, v)) worst_missed = std::max(worst_missed, test::mesh_distance(wb, v));
              if (both)
                for (const auto& v : wb.vertices)
                  if (test::inside_reference(wa, v)) worst_missed = std::max(worst_missed, test::mesh_distance(wa, v));
            }
          }
          false_dist = bench::fmt("%.4f", worst_out) + " (" + bench::fmt("%.2f", worst_out / voxel) + " voxels)";
          false_max = bench::fmt("%.4f", worst_out_max) + " (" + bench::fmt("%.2f", worst_out_max / voxel) + " voxels)";
          missed = bench::fmt("%.4f", worst_missed) + " (" + bench::fmt("%.2f", worst_missed / voxel) + " voxels)";
        }
        md << "| voxcd " << (both ? "both directions" : "A in B") << ", " << (threads ? "1 thread" : "all threads")
           << " | " << voxel << " | " << ta->shell().size() << "/" << tb->shell().size() << " | "
           << bench::fmt("%.1f", t * 1e6 / double(poses)) << " | " << bench::fmt("%.1f", fcl_t / t) << " | " << bench::fmt("%.0f", double(contacts) / double(poses)) << " | " << touching << " | "
           << false_dist << " | " << false_max << " | " << missed << " |\n";
        std::fprintf(stderr, "voxel %g both %d threads %u: %.1f us\n", voxel, both, threads, t * 1e6 / double(poses));
      }
    }
  }
  md << "\nFalse-contact distance: over 40 sampled contacts per pose, the largest distance of a contact point "
        "outside the other mesh: Euclidean (the bound is sqrt(3) voxels) and in the max norm along the other object's grid "
        "axes (the bound is one voxel: a hit voxel's cube meets the surface or lies inside). Missed penetration: over poses FCL finds in "
        "collision and voxcd does not, the deepest vertex of one mesh inside the other (the bound is "
        "sqrt(3)/2 shell spacings, 0.61 voxel, for both directions). Machine: "
     << bench::machine_description() << ".\n";
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  return 0;
}
