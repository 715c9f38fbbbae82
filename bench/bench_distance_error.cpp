// Speed against error: 2-bit voxmaps and distance voxmaps (SB = 4, 8, 16) on the same meshes and poses, beside FCL,
// each against exact geometry. Per voxel size and kind: the time of one pair query (cpu backend, one thread, both
// directions, ALL contacts; median over repeats), the false-contact distance (how far contact points lie outside
// the other mesh: worst and 99th percentile) and the missed depth (poses FCL finds colliding with no contact: the
// deepest vertex inside the other mesh). Then the Pareto front of time against worst error, and for each distance
// row the 2-bit row that reaches the same worst error, with the ratio of their times. Writes Markdown to stdout
// (and to --out FILE).
#include <fcl/fcl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "bench/bench_common.h"
#include "bench/fcl_common.h"
#include "tests/exact_geometry.h"
#include "tests/sparse_pairs.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/pairs/collide.h"

using namespace voxcd;

namespace {

using bench::bvh_of;
using bench::to_fcl;
using bench::transformed;

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5))];
}

struct Row {
  std::string kind;  // "2-bit" or "SB 8"
  int bits = 0;
  double voxel = 0;
  size_t shell_a = 0, shell_b = 0;
  double us = 0;            // per query
  double worst = 0, p99 = 0;  // false-contact distance, world units
  double missed = 0;        // deepest missed penetration, world units
  size_t touching = 0;
  double contacts = 0;      // per query
};

// The false-contact distance (of up to 60 contacts a pose, how far outside the other mesh) and the missed depth (a
// pose FCL finds colliding without a contact: the deepest vertex of one mesh inside the other) of one kind's contacts.
void contact_errors(Row& row, const std::vector<std::vector<Contact>>& contacts, const std::vector<bool>& fcl_hit,
                    const std::vector<Mesh>& wa, const std::vector<Mesh>& wb) {
  std::vector<double> outside;
  size_t total = 0;
  std::mt19937_64 pick(7);
  for (size_t k = 0; k < contacts.size(); ++k) {
    const auto& cs = contacts[k];
    total += cs.size();
    row.touching += !cs.empty();
    for (size_t s = 0; s < std::min<size_t>(cs.size(), 60); ++s) {
      const Contact& c = cs[cs.size() <= 60 ? s : pick() % cs.size()];
      const Mesh& other = c.a_in_b ? wb[k] : wa[k];
      outside.push_back(test::inside_reference(other, c.position) ? 0.0 : test::mesh_distance(other, c.position));
    }
    if (fcl_hit[k] && cs.empty()) {
      for (const auto& v : wa[k].vertices)
        if (test::inside_reference(wb[k], v)) row.missed = std::max(row.missed, test::mesh_distance(wb[k], v));
      for (const auto& v : wb[k].vertices)
        if (test::inside_reference(wa[k], v)) row.missed = std::max(row.missed, test::mesh_distance(wa[k], v));
    }
  }
  row.worst = outside.empty() ? 0 : *std::max_element(outside.begin(), outside.end());
  row.p99 = quantile(outside, 0.99);
  row.contacts = double(total) / double(contacts.size());
}

// The SB 8 row of sparse distance voxmaps with refined bricks on ref's sparse device (tests/sparse_pairs.h): the same
// objects' shells, their sparse fields, the same poses; errors as contact_errors measures them. No time: ref's scalar
// engine is the specification, not a backend's speed.
Row sparse_row(double voxel, const Mesh& ma, const Mesh& mb, const std::vector<PairRequest>& reqs,
               const std::vector<bool>& fcl_hit, const std::vector<Mesh>& wa, const std::vector<Mesh>& wb) {
  const test::sparse::SparseObject sa = test::sparse::make_sparse_object(ma, "torus A", voxel);
  const test::sparse::SparseObject sb = test::sparse::make_sparse_object(mb, "torus B", voxel);
  const test::sparse::SparseDevice dev({&sa, &sb});
  Row row;
  row.kind = "SB 8 sparse";
  row.bits = 8;
  row.voxel = voxel;
  row.shell_a = sa.type->shell().size();
  row.shell_b = sb.type->shell().size();
  std::vector<std::vector<Contact>> cs;
  for (const PairRequest& r : reqs) cs.push_back(dev.collide(0, r.pose_a, 1, r.pose_b, true));
  contact_errors(row, cs, fcl_hit, wa, wb);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path;
  int repeats = 3;
  size_t poses = 40;
  std::vector<double> voxels = {0.08, 0.04, 0.02};
  std::vector<double> fine = {0.01};  // 2-bit only: finer voxels, to reach the distance voxmaps' error
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--out") && i + 1 < argc) out_path = argv[++i];
    else if (!std::strcmp(argv[i], "--repeats") && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (!std::strcmp(argv[i], "--poses") && i + 1 < argc) poses = size_t(std::atol(argv[++i]));
    else if (!std::strcmp(argv[i], "--quick")) voxels = {0.08, 0.04}, fine = {0.02};
    else {
      std::fprintf(stderr, "usage: bench_distance_error [--out FILE] [--repeats N] [--poses N] [--quick]\n");
      return 2;
    }
  }
  const std::string provenance = bench::provenance(argc, argv);
  Mesh ma = make_torus(1.0, 0.35, 100, 50);
  Mesh mb = make_torus(0.8, 0.3, 100, 50);
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
  std::vector<bool> fcl_hit(poses);
  const double fcl_t = bench::median_time(repeats, [&] {
    for (size_t k = 0; k < poses; ++k) {
      fcl::CollisionRequestd req(1000000, true);
      fcl::CollisionResultd res;
      fcl::CollisionObjectd oa(fa, to_fcl(reqs[k].pose_a)), ob(fb, to_fcl(reqs[k].pose_b));
      fcl::collide(&oa, &ob, req, res);
      fcl_hit[k] = res.isCollision();
    }
  });
  size_t fcl_touching = 0;
  for (bool h : fcl_hit) fcl_touching += h;
  std::vector<Mesh> wa, wb;
  for (const auto& r : reqs) wa.push_back(transformed(ma, r.pose_a)), wb.push_back(transformed(mb, r.pose_b));

  std::vector<Row> rows;
  auto measure = [&](double voxel, int bits) {
    ObjectOptions o;
    o.voxel = voxel;
    o.distance_bits = bits;
    auto ta = std::make_shared<ObjectType>(make_object_type(make_object(ma, "torus A", 0, o), "torus A"));
    auto tb = std::make_shared<ObjectType>(make_object_type(make_object(mb, "torus B", 0, o), "torus B"));
    DeviceConfig base;
    if (bits) base.SB = bits;
    const DeviceConfig cfg = fit_memory(base, {ta.get(), tb.get()});
    DeviceOptions dopt;
    dopt.threads = 1;
    PairCollider col(make_device("cpu", cfg, dopt), {ta, tb});
    PairOptions opt;
    opt.both_directions = true;
    const std::vector<PairResult> res = col.collide(reqs, opt);
    std::vector<PairResult> one;
    std::vector<PairRequest> req(1);
    const double t = bench::median_time(repeats, [&] {
      for (const PairRequest& r : reqs) {
        req[0] = r;
        col.collide(req, opt, one);
      }
    });
    Row row;
    row.kind = bits ? "SB " + std::to_string(bits) : "2-bit";
    row.bits = bits;
    row.voxel = voxel;
    row.shell_a = ta->shell().size();
    row.shell_b = tb->shell().size();
    row.us = t * 1e6 / double(poses);
    std::vector<std::vector<Contact>> cs(poses);
    for (size_t k = 0; k < poses; ++k) cs[k] = res[k].contacts;
    contact_errors(row, cs, fcl_hit, wa, wb);
    std::fprintf(stderr, "%s voxel %g: %.1f us, worst %.4f (%.2f voxels)\n", row.kind.c_str(), voxel, row.us, row.worst,
                 row.worst / voxel);
    rows.push_back(row);
  };
  for (double v : voxels) {
    for (int bits : {0, 4, 8, 16}) measure(v, bits);
    rows.push_back(sparse_row(v, ma, mb, reqs, fcl_hit, wa, wb));
  }
  for (double v : fine) measure(v, 0);

  std::ostringstream md;
  md << provenance << "\n\n"
     << "Meshes: two tori of 10,000 triangles (radii 1.0/0.35 and 0.8/0.3); " << poses
     << " random poses with B's centre within 1.2 of A's, the same poses for every row. voxcd: cpu backend, one "
        "thread, both directions, ALL contacts, one query at a time, median of "
     << repeats << " runs; distance voxmaps with a band of 4 voxels, margin 0. FCL " << FCL_VERSION
     << ": `fcl::collide`, all contacts, OBBRSS: " << bench::fmt("%.1f", fcl_t * 1e6 / double(poses))
     << " us per query, " << fcl_touching << " touching poses. False-contact distance: of up to 60 contacts a pose, "
        "how far the contact point lies outside the other mesh (0 inside), exact. Missed depth: poses FCL finds "
        "colliding and voxcd does not, the deepest vertex of one mesh inside the other. SB 8 sparse: the same "
        "objects with sparse distance fields (bricks refined up to level 3) on ref's sparse device, which gives no "
        "time.\n\n"
     << "| voxmap | voxel | shell points A/B | us per query | FCL / this | contacts per query | touching | false contact, "
        "worst | false contact, 99% | missed depth, worst | Pareto |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    bool pareto = r.us > 0;  // a row without a time (ref's sparse device) is beside the front, not on it
    for (const Row& o : rows)
      if (&o != &r && o.us > 0 && o.us <= r.us && o.worst <= r.worst && (o.us < r.us || o.worst < r.worst))
        pareto = false;
    md << "| " << r.kind << " | " << r.voxel << " | " << r.shell_a << "/" << r.shell_b << " | "
       << (r.us > 0 ? bench::fmt("%.1f", r.us) : std::string("-")) << " | "
       << (r.us > 0 ? bench::fmt("%.2f", fcl_t * 1e6 / double(poses) / r.us) : std::string("-")) << " | "
       << bench::fmt("%.0f", r.contacts) << " | " << r.touching << " | " << bench::fmt("%.4f", r.worst) << " ("
       << bench::fmt("%.2f", r.worst / r.voxel) << " voxel) | " << bench::fmt("%.4f", r.p99) << " ("
       << bench::fmt("%.2f", r.p99 / r.voxel) << ") | " << bench::fmt("%.4f", r.missed) << " ("
       << bench::fmt("%.2f", r.missed / r.voxel) << ") | " << (pareto ? "yes" : "") << " |\n";
  }
  md << "\nAt equal worst error: each SB 8 row beside the fastest 2-bit row whose worst false-contact distance is at "
        "most the SB 8 row's (the 2-bit voxel small enough to match it), and the ratio of their times.\n\n"
     << "| SB 8 voxel | worst error | matching 2-bit voxel | its worst error | 2-bit us / SB 8 us |\n|---|---|---|---|---|\n";
  for (const Row& d : rows) {
    if (d.bits != 8 || d.us <= 0) continue;
    const Row* best = nullptr;
    for (const Row& s : rows)
      if (s.bits == 0 && s.worst <= d.worst && (!best || s.us < best->us)) best = &s;
    md << "| " << d.voxel << " | " << bench::fmt("%.4f", d.worst) << " | ";
    if (best)
      md << best->voxel << " | " << bench::fmt("%.4f", best->worst) << " | " << bench::fmt("%.1f", best->us / d.us)
         << " |\n";
    else
      md << "none measured (the finest 2-bit row's worst is " << bench::fmt("%.4f", rows.back().worst) << ") | - | > "
         << bench::fmt("%.1f", rows.back().us / d.us) << " |\n";
  }
  // Beyond the finest 2-bit voxel measured: the 2-bit rows' own trends, worst error = k * voxel (k their mean) and
  // time = c * voxel^b (least squares on the logarithms), give the voxel and the time that would match.
  double k = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, m = 0;
  for (const Row& r : rows) {
    if (r.bits) continue;
    k += r.worst / r.voxel;
    const double x = std::log(r.voxel), y = std::log(r.us);
    sx += x, sy += y, sxx += x * x, sxy += x * y, m += 1;
  }
  if (m >= 2) {
    k /= m;
    const double b = (m * sxy - sx * sy) / (m * sxx - sx * sx), c = std::exp((sy - b * sx) / m);
    md << "\nExtrapolated from the " << int(m) << " 2-bit rows (worst error " << bench::fmt("%.2f", k)
       << " voxel on average; time per query proportional to voxel^" << bench::fmt("%.2f", b)
       << "): the 2-bit voxel whose worst error equals each distance row's, and its predicted time.\n\n"
       << "| distance row | worst error | 2-bit voxel to match | predicted 2-bit us | predicted 2-bit / this |\n"
          "|---|---|---|---|---|\n";
    for (const Row& d : rows) {
      if (!d.bits || d.worst <= 0 || d.us <= 0) continue;
      const double v = d.worst / k, t = c * std::pow(v, b);
      md << "| " << d.kind << " at " << d.voxel << " | " << bench::fmt("%.2g", d.worst) << " | "
         << bench::fmt("%.3g", v) << " | " << bench::fmt("%.3g", t) << " | " << bench::fmt("%.3g", t / d.us) << " |\n";
    }
  }
  md << "\nMachine: " << bench::machine_description() << ".\n";
  std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  return 0;
}
