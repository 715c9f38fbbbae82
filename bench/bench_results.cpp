// The paper's pair-wise evaluation and the speed-against-error studies for docs/results.md. Three parts, each
// writing a Markdown table (stdout, and --out FILE) and the data behind its plots (--csv FILE):
//
//   pairs  Table 1 and Figs. 11-13: update rate and time per lookup of one pair of the paper's 36-face polytopes
//          against the number of shell points (voxmap fixed at about 12,672 voxels) and against the number of
//          voxmap voxels (shell at the matching density), on the cpu backend with one thread, with the modelled
//          device's rate from its cycles at the device clock (its configuration's, measured or an estimate that says
//          so; or --clock), named with its source; the paper's Table 1 beside ours.
//   error  For each voxel size, the pair's update rate and lookups per second beside its error against exact
//          geometry on the same poses (FCL's GJK/EPA on the convex polytope: penetration depth of the contacts
//          voxcd misses, separation of the ones it reports falsely), and the narrow phases of FCL and Bullet
//          (GJK/EPA) timed on the same poses.
//   fixed  The fixed-point widths (MF, PF) against the rate at which the device's voxel index differs from the
//          one exact (double) arithmetic gives, on random poses and points.
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <btBulletCollisionCommon.h>
#include <fcl/fcl.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "bench/bench_common.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/ref/float_model.h"
#include "voxcd/ref/pipeline.h"

using namespace voxcd;

namespace {

struct Args {
  std::string part, out_path, csv_path;
  int repeats = 5;
  size_t poses = 64;
  std::optional<DeviceClock> clock;  // of the device rates when --clock MHZ gives one (else each device's own)
  std::vector<double> voxels = {0.4, 0.2, 0.1, 0.05, 0.025};
  std::vector<size_t> shells = {25, 92, 219, 384, 606, 840, 1150, 1509, 1909, 2314, 5321, 9337};
  std::vector<size_t> maps = {20, 50, 120, 300, 700, 1500, 3500, 8000, 16000, 35000, 80000, 200000};
  size_t map_voxels = 12672;
  std::vector<std::pair<int, int>> widths = {{8, 2}, {10, 4}, {12, 4}, {14, 6}, {16, 8}, {20, 8}};
  size_t points = 1000000;
};

std::vector<double> parse_list(const std::string& s, const char* what) {
  std::vector<double> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const double x = std::strtod(item.c_str(), &end);
    if (item.empty() || *end || !std::isfinite(x) || x <= 0)
      throw std::invalid_argument(std::string(what) + ": '" + item + "' is not a positive number (in '" + s + "')");
    v.push_back(x);
  }
  if (v.empty()) throw std::invalid_argument(std::string(what) + " is empty");
  return v;
}

std::vector<size_t> parse_counts(const std::string& s, const char* what) {
  std::vector<size_t> v;
  for (double x : parse_list(s, what)) {
    if (x != std::floor(x)) throw std::invalid_argument(std::string(what) + ": " + s + " has a non-integer count");
    v.push_back(size_t(x));
  }
  return v;
}

// The paper's Table 1: shell points, update rate (Hz), time per look-up (ms).
struct PaperRow {
  size_t points;
  double hz, ms;
};
const PaperRow kTable1[] = {{25, 618.4, 0.064},  {92, 261.0, 0.042},  {219, 173.0, 0.026}, {384, 73.4, 0.035},
                            {606, 58.7, 0.028},  {840, 41.7, 0.029},  {1150, 26.7, 0.033}, {1509, 22.5, 0.029},
                            {1909, 17.7, 0.030}, {2314, 13.8, 0.031}, {5321, 6.0, 0.031},  {9337, 1.0, 0.105}};

std::shared_ptr<ObjectType> polytope_at(const Mesh& m, double voxel) {
  ObjectOptions o;
  o.voxel = voxel;
  return std::make_shared<ObjectType>(make_object_type(make_object(m, "shape:polytope36", 0, o), "polytope36"));
}

// The voxel size whose object has a count (size(type)) nearest `target`, by bisection of log(voxel) over
// [lo, hi] (counts fall as the voxel grows).
template <class Size>
std::pair<double, std::shared_ptr<ObjectType>> voxel_for(const Mesh& m, size_t target, Size size, double lo = 0.02,
                                                         double hi = 6.0) {
  std::shared_ptr<ObjectType> best;
  double best_v = 0, best_err = INFINITY;
  for (int it = 0; it < 16; ++it) {
    const double v = std::sqrt(lo * hi);
    std::shared_ptr<ObjectType> t;
    try {
      t = polytope_at(m, v);
    } catch (const std::exception&) {  // too coarse to have a surface voxel: go finer
      hi = v;
      continue;
    }
    const double n = double(size(*t));
    const double err = std::fabs(std::log(n / double(target)));
    if (err < best_err) best_err = err, best_v = v, best = t;
    if (n == double(target)) break;
    (n > double(target) ? lo : hi) = v;
  }
  if (!best) throw std::runtime_error("no voxel size in [0.02, 6] gives a usable polytope");
  return {best_v, best};
}

// Random rotations for both, B's centre within `reach` of A's (most poses interpenetrate).
std::vector<PairRequest> random_poses(size_t n, double min_dist, double max_dist, uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PairRequest> reqs(n);
  for (auto& r : reqs) {
    r.a = 0, r.b = 1;
    r.pose_a.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    r.pose_b.rotation = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized();
    r.pose_b.translation =
        Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized() * (min_dist + (max_dist - min_dist) * u(rng));
  }
  return reqs;
}

// The options of the pair timings: A's shell in B's voxmap only, as these tables were always measured.
PairOptions one_way() {
  PairOptions o;
  o.both_directions = false;
  return o;
}

struct PairTiming {
  double seconds = 0;  // per query, median over repeats of the mean over the poses
  double lookups = 0, cycles = 0, hits = 0;  // per query
  DeviceConfig config;  // the device's
};

// One query at a time on the cpu backend with one thread, as an application asks them (buffers reused).
PairTiming time_pairs(std::shared_ptr<ObjectType> ta, std::shared_ptr<ObjectType> tb,
                      const std::vector<PairRequest>& reqs, const PairOptions& opt, int repeats,
                      std::vector<PairResult>* results = nullptr) {
  DeviceConfig cfg = fit_memory(DeviceConfig{}, {ta.get(), tb.get()});
  // A shell much coarser than the voxmap (Table 1's 25-point shell against 12,672 voxels) scales the rotation by
  // the ratio of the grids: widen the matrix entries' integer part to hold it (MW > 18 changes no result bit
  // of the other rows and only the multipliers' width in hardware).
  const double scale = std::max(ta->shell().frame().voxel / tb->voxmap().voxel(), tb->shell().frame().voxel / ta->voxmap().voxel());
  while (std::ldexp(1.0, cfg.MW - cfg.MF - 1) <= scale * 1.001) ++cfg.MW;
  DeviceOptions dopt;
  dopt.threads = 1;
  PairCollider col(make_device("cpu", cfg, dopt), {ta, tb});
  PairTiming out;
  out.config = cfg;
  const std::vector<PairResult> all = col.collide(reqs, opt);
  for (const auto& r : all) out.lookups += double(r.lookups), out.cycles += double(r.device_cycles), out.hits += r.hits;
  out.lookups /= double(reqs.size()), out.cycles /= double(reqs.size()), out.hits /= double(reqs.size());
  if (results) *results = all;
  std::vector<PairResult> one;
  std::vector<PairRequest> req(1);
  out.seconds = bench::median_time(repeats, [&] {
                  for (const auto& r : reqs) {
                    req[0] = r;
                    col.collide(req, opt, one);
                  }
                }) /
                double(reqs.size());
  return out;
}

std::string hz_text(double hz) { return bench::fmt(hz >= 100 ? "%.0f" : "%.1f", hz); }

// ---- pairs: Table 1, Figs. 11-13 ----
void part_pairs(const Args& a, std::ostream& md, std::ostream& csv) {
  const Mesh m = make_shape("polytope36");
  const auto reqs = random_poses(a.poses, 0.5, 1.6, 11);
  // The default widths (memories grown to fit); a row whose shell needs a wider MW is marked with its own clock.
  bench::RowClocks clocks(a.clock, DeviceConfig{});
  csv << bench::clock_csv_lines(clocks.heading()) << "series,target,shell_points,map_voxels,voxel_a,voxel_b,us_per_query,hz,ns_per_lookup,device_cycles,"
         "device_hz,paper_points,paper_hz,paper_ms,lookups,device_clock_estimate\n";
  const auto [vb, tb] = voxel_for(m, a.map_voxels, [](const ObjectType& t) { return t.voxmap().size(); });
  md << "Pair: two of the paper's 36-face polytopes (about 2 units across), " << a.poses
     << " random poses with B's centre 0.5 to 1.6 from A's (most interpenetrate), A's shell in B's voxmap, ALL "
        "contacts; one query at a time on the cpu backend with one thread (as the paper's single CPU), median of "
     << a.repeats << " runs over all poses. Update rate = 1 / time per query; time per lookup = time per query / "
        "lookups (the shell points the query submits to the device). Device: the modelled device's cycles for the same jobs (exact timing model, 4 lanes) at "
     << clocks.heading().text() << " (a row marked [n]: at the clock noted below the tables).\n\n";
  md << "**Fixed voxmap (Table 1, Fig. 12)**: B voxelised at " << bench::fmt("%.4f", vb) << " units: "
     << tb->voxmap().dims()[0] << " x " << tb->voxmap().dims()[1] << " x " << tb->voxmap().dims()[2] << " = "
     << tb->voxmap().size() << " voxels (the paper's: 12,672); A's shell at the voxel size whose shell has the "
        "number of points nearest the paper's row. Ratio = ours / the paper's (rate), the paper's / ours (time per "
        "lookup): how many times faster.\n\n"
     << "| paper: shell points | paper: Hz | paper: ms per lookup | ours: shell points | ours: Hz | ours: us per "
        "lookup | rate ratio | per-lookup ratio | device Hz (" << clocks.heading().mhz << " MHz) | device / paper |\n"
     << "|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (size_t target : a.shells) {
    const auto [va, ta] = voxel_for(m, target, [](const ObjectType& t) { return t.shell().size(); });
    const PairTiming t = time_pairs(ta, tb, reqs, one_way(), a.repeats);
    const double hz = 1 / t.seconds, ns = t.seconds * 1e9 / t.lookups;
    const DeviceClock clock = clocks.of(t.config);
    const double dev_hz = clock.rate(t.cycles);
    const PaperRow* p = nullptr;
    for (const auto& row : kTable1)
      if (row.points == target) p = &row;
    md << "| " << (p ? std::to_string(p->points) : "-") << " | " << (p ? bench::fmt("%.1f", p->hz) : "-") << " | "
       << (p ? bench::fmt("%.3f", p->ms) : "-") << " | " << ta->shell().size() << " | " << hz_text(hz) << " | "
       << bench::fmt("%.3f", ns / 1e3) << " | " << (p ? bench::fmt("%.0f", hz / p->hz) : "-") << " | "
       << (p ? bench::fmt("%.0f", p->ms * 1e6 / ns) : "-") << " | " << hz_text(dev_hz) << clocks.mark(clock) << " | "
       << (p ? bench::fmt("%.0f", dev_hz / p->hz) : "-") << " |\n";
    csv << "shell," << target << "," << ta->shell().size() << "," << tb->voxmap().size() << "," << va << "," << vb
        << "," << t.seconds * 1e6 << "," << hz << "," << ns << "," << t.cycles << "," << dev_hz << ","
        << (p ? std::to_string(p->points) : "") << "," << (p ? bench::fmt("%g", p->hz) : "") << ","
        << (p ? bench::fmt("%g", p->ms) : "") << "," << t.lookups << "," << clock.estimate << "\n";
    std::fprintf(stderr, "pairs shell %zu (voxel %.4f): %.1f Hz, %.1f ns/lookup\n", ta->shell().size(), va, hz, ns);
  }
  md << "\n**Voxmap resolution (Fig. 11)**: A and B at the same voxel size (shell at the matching density, the "
        "paper's sqrt(2) rule), chosen so that B's voxmap has the number of voxels nearest each target. The paper "
        "gives Fig. 11's values only as points on a plot: none are quoted, so no ratio is possible.\n\n"
     << "| voxmap voxels | voxel (units) | shell points | Hz | us per lookup | device Hz (" << clocks.heading().mhz
     << " MHz) |\n|--:|--:|--:|--:|--:|--:|\n";
  for (size_t target : a.maps) {
    const auto [v, tv] = voxel_for(m, target, [](const ObjectType& t) { return t.voxmap().size(); });
    const PairTiming t = time_pairs(tv, tv, reqs, one_way(), a.repeats);
    const double hz = 1 / t.seconds, ns = t.seconds * 1e9 / t.lookups;
    const DeviceClock clock = clocks.of(t.config);
    const double dev_hz = clock.rate(t.cycles);
    md << "| " << tv->voxmap().size() << " | " << bench::fmt("%.4f", v) << " | " << tv->shell().size() << " | "
       << hz_text(hz) << " | " << bench::fmt("%.3f", ns / 1e3) << " | " << hz_text(dev_hz) << clocks.mark(clock)
       << " |\n";
    csv << "map," << target << "," << tv->shell().size() << "," << tv->voxmap().size() << "," << v << "," << v << ","
        << t.seconds * 1e6 << "," << hz << "," << ns << "," << t.cycles << "," << dev_hz << ",,,," << t.lookups << ","
        << clock.estimate << "\n";
    std::fprintf(stderr, "pairs map %llu (voxel %.4f): %.1f Hz\n", (unsigned long long)tv->voxmap().size(), v, hz);
  }
  md << clocks.notes();
}

// ---- error: speed against error per voxel size, and the narrow-phase peers ----
double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(q * double(v.size() - 1) + 0.5))];
}

fcl::Transform3d to_fcl(const RigidPose& p) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = p.rotation.toRotationMatrix();
  t.translation() = p.translation;
  return t;
}

btTransform to_bullet(const RigidPose& p) {
  const auto& q = p.rotation;
  return btTransform(btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())),
                     btVector3(btScalar(p.translation.x()), btScalar(p.translation.y()), btScalar(p.translation.z())));
}

// Exact geometry of one pose set (FCL on the convex polytope: GJK for touching and separation, EPA for the
// penetration depth), and the peers' narrow phases timed on it.
struct ExactSet {
  std::vector<PairRequest> reqs;
  std::vector<bool> touching;
  std::vector<double> depth, separation;
  size_t n_touching = 0;
  double fcl_seconds = 0, bullet_seconds = 0;  // per query
  size_t bullet_agree = 0;                     // poses where Bullet's GJK/EPA agrees with FCL on touching
};

class ConvexPeers {
 public:
  explicit ConvexPeers(const Mesh& m) {
    auto verts = std::make_shared<std::vector<fcl::Vector3d>>(m.vertices.begin(), m.vertices.end());
    auto faces = std::make_shared<std::vector<int>>();
    for (const auto& t : m.triangles) faces->insert(faces->end(), {3, int(t[0]), int(t[1]), int(t[2])});
    convex_ = std::make_shared<fcl::Convexd>(verts, int(m.triangles.size()), faces);
    for (const auto& v : m.vertices) hull_.addPoint(btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z())), false);
    hull_.recalcLocalAabb();
    hull_.setMargin(0);
  }

  bool collides(const PairRequest& r) const {
    fcl::CollisionObjectd oa(convex_, to_fcl(r.pose_a)), ob(convex_, to_fcl(r.pose_b));
    fcl::CollisionRequestd creq;
    fcl::CollisionResultd cres;
    fcl::collide(&oa, &ob, creq, cres);
    return cres.isCollision();
  }

  // Random orientations and direction; B's centre where the two first touch along it (bisection) plus an offset
  // uniform in +-near.
  std::vector<PairRequest> near_contact(size_t n, double radius, double near, uint64_t seed) const {
    auto reqs = random_poses(n, 1, 1, seed);
    std::mt19937_64 rng(seed + 1);
    std::uniform_real_distribution<double> u(-near, near);
    for (auto& r : reqs) {
      const Eigen::Vector3d dir = r.pose_b.translation.normalized();
      double lo = 0, hi = 2.5 * radius;
      for (int it = 0; it < 40; ++it) {
        r.pose_b.translation = dir * (0.5 * (lo + hi));
        (collides(r) ? lo : hi) = 0.5 * (lo + hi);
      }
      r.pose_b.translation = dir * (0.5 * (lo + hi) + u(rng));
    }
    return reqs;
  }

  ExactSet exact(std::vector<PairRequest> reqs, int repeats) {
    ExactSet e;
    const size_t n = reqs.size();
    e.touching.resize(n);
    e.depth.assign(n, 0);
    e.separation.assign(n, 0);
    for (size_t k = 0; k < n; ++k) {
      fcl::CollisionObjectd oa(convex_, to_fcl(reqs[k].pose_a)), ob(convex_, to_fcl(reqs[k].pose_b));
      fcl::CollisionRequestd creq(1, true);
      fcl::CollisionResultd cres;
      fcl::collide(&oa, &ob, creq, cres);
      e.touching[k] = cres.isCollision();
      e.n_touching += e.touching[k];
      if (e.touching[k]) {
        e.depth[k] = cres.getContact(0).penetration_depth;
      } else {
        fcl::DistanceRequestd dreq;
        fcl::DistanceResultd dres;
        fcl::distance(&oa, &ob, dreq, dres);
        e.separation[k] = dres.min_distance;
      }
    }
    e.fcl_seconds = bench::median_time(repeats, [&] {
                      size_t hits = 0;
                      for (const auto& r : reqs) hits += collides(r);
                      bench::keep(hits);
                    }) /
                    double(n);
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    e.bullet_seconds = bench::median_time(repeats, [&] {
                         e.bullet_agree = 0;
                         for (size_t k = 0; k < n; ++k) {
                           btGjkPairDetector gjk(&hull_, &hull_, &simplex, &epa);
                           btGjkPairDetector::ClosestPointInput in;
                           in.m_transformA = to_bullet(reqs[k].pose_a);
                           in.m_transformB = to_bullet(reqs[k].pose_b);
                           btPointCollector out;
                           gjk.getClosestPoints(in, out, nullptr);
                           e.bullet_agree += out.m_hasResult && ((out.m_distance <= 0) == e.touching[k]);
                         }
                       }) /
                       double(n);
    e.reqs = std::move(reqs);
    return e;
  }

 private:
  std::shared_ptr<fcl::Convexd> convex_;
  btConvexHullShape hull_;
};

void part_error(const Args& a, std::ostream& md, std::ostream& csv) {
  const Mesh m = make_shape("polytope36");
  double radius = 0;
  for (const auto& v : m.vertices) radius = std::max(radius, v.norm());
  const double kNear = 3;  // voxels either side of first contact: past every bound of docs/pairs.md
  ConvexPeers peers(m);
  bench::RowClocks clocks(a.clock, DeviceConfig{});  // as part_pairs

  md << "Pair: two of the paper's 36-face polytopes (convex, radius " << bench::fmt("%.2f", radius) << "). For each "
     << "voxel size, " << a.poses << " random poses near first contact: random orientations and direction, B's "
        "centre where the two first touch along that direction (bisection) moved by up to +-"
     << kNear << " voxels along it. Exact geometry on the same poses: FCL " << FCL_VERSION
     << " on the convex polytopes (GJK for touching and separation, EPA for penetration depth). voxcd: one "
        "query at a time on the cpu backend with one thread, ALL contacts, median of "
     << a.repeats
     << " runs. A missed contact is a pose that touches by exact geometry where voxcd reports no hit (its "
        "penetration depth); a false contact is a pose voxcd reports touching that is separated by exact "
        "geometry (its separation). Depths and separations in voxels: the quantiles (50%, 90%, max) of the "
        "missed and of the false poses. Peers timed on the same poses: FCL `fcl::collide` (boolean, GJK on "
        "`fcl::Convexd`) and Bullet "
     << BT_BULLET_VERSION / 100 << "." << BT_BULLET_VERSION % 100
     << " `btGjkPairDetector` with EPA on `btConvexHullShape` (single precision, margin 0); ratio = the peer's "
        "time per query over voxcd's. Device Hz: the modelled device's cycles for the same jobs (exact timing model, 4 "
        "lanes) at "
     << clocks.heading().text() << " (a row marked [n]: at the clock noted below the table).\n\n"
     << "| voxel (units) | direction | shell points | voxmap voxels | us per query | update rate (Hz) | lookups / s "
        "| device Hz (" << clocks.heading().mhz << " MHz) | touching poses | missed | missed depth, voxels (50/90/max) | "
        "false | false separation, voxels (50/90/max) | FCL / voxcd time | Bullet / voxcd time |\n"
     << "|--:|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  csv << bench::clock_csv_lines(clocks.heading()) << "kind,voxel,both,value_voxels\n";
  std::ostringstream summary, peer_note;
  uint64_t seed = 12;
  for (double voxel : a.voxels) {
    const ExactSet e = peers.exact(peers.near_contact(a.poses, radius, kNear * voxel, seed += 2), a.repeats);
    const size_t n = e.reqs.size();
    peer_note << (peer_note.str().empty() ? "" : ", ") << voxel << ": FCL " << bench::fmt("%.2f", e.fcl_seconds * 1e6)
              << " us, Bullet " << bench::fmt("%.2f", e.bullet_seconds * 1e6) << " us (agrees with FCL in "
              << e.bullet_agree << " of " << n << ")";
    const auto t = polytope_at(m, voxel);
    for (bool both : {false, true}) {
      PairOptions opt;
      opt.both_directions = both;
      std::vector<PairResult> res;
      const PairTiming tm = time_pairs(t, t, e.reqs, opt, a.repeats, &res);
      const DeviceClock clock = clocks.of(tm.config);
      std::vector<double> missed, falses;
      for (size_t k = 0; k < n; ++k) {
        const bool hit = res[k].hits > 0;
        if (e.touching[k] && !hit) missed.push_back(e.depth[k] / voxel);
        if (!e.touching[k] && hit) falses.push_back(e.separation[k] / voxel);
      }
      for (double d : missed) csv << "missed," << voxel << "," << both << "," << d << "\n";
      for (double d : falses) csv << "false," << voxel << "," << both << "," << d << "\n";
      auto q3 = [](const std::vector<double>& v) {
        return v.empty() ? std::string("-")
                         : bench::fmt("%.2f", quantile(v, 0.5)) + " / " + bench::fmt("%.2f", quantile(v, 0.9)) +
                               " / " + bench::fmt("%.2f", quantile(v, 1.0));
      };
      md << "| " << voxel << " | " << (both ? "both" : "A in B") << " | " << t->shell().size() << " | "
         << t->voxmap().size() << " | " << bench::fmt("%.2f", tm.seconds * 1e6) << " | "
         << hz_text(1 / tm.seconds) << " | " << bench::fmt("%.3g", tm.lookups / tm.seconds) << " | "
         << hz_text(clock.rate(tm.cycles)) << clocks.mark(clock) << " | " << e.n_touching << " of " << n << " | "
         << missed.size() << " | " << q3(missed) << " | " << falses.size() << " of " << n - e.n_touching << " | "
         << q3(falses) << " | " << bench::fmt("%.2f", e.fcl_seconds / tm.seconds) << " | "
         << bench::fmt("%.2f", e.bullet_seconds / tm.seconds) << " |\n";
      summary << "summary," << voxel << "," << both << "," << tm.seconds * 1e6 << "," << 1 / tm.seconds << ","
              << tm.lookups / tm.seconds << "," << clock.rate(tm.cycles) << "," << missed.size() << ","
              << falses.size() << "," << quantile(missed, 1.0) << "," << quantile(falses, 1.0) << ","
              << quantile(missed, 0.9) << "," << quantile(falses, 0.9) << "," << e.fcl_seconds * 1e6 << ","
              << e.bullet_seconds * 1e6 << "\n";
      std::fprintf(stderr, "error voxel %g both %d: %.1f us, %zu missed, %zu false\n", voxel, both,
                   tm.seconds * 1e6, missed.size(), falses.size());
    }
  }
  csv << "# summary: voxel,both,us_per_query,hz,lookups_per_s,device_hz,missed,false,missed_max,false_max,"
         "missed_q90,false_q90,fcl_us,bullet_us\n"
      << summary.str();
  md << clocks.notes() << "\nPeers per query, by voxel size's pose set: " << peer_note.str()
     << ". Both peers are exact narrow phases for convex shapes only and return one contact; voxcd returns "
        "every contact and treats concave shapes the same (the concave case, against FCL's mesh hierarchies, is "
        "the bench_pair table below). Quantiles are of the missed or false poses only; the bounds they meet are "
        "in docs/pairs.md.\n";
}

// ---- fixed: MF, PF against disagreement with exact arithmetic ----
void part_fixed(const Args& a, std::ostream& md, std::ostream& csv) {
  const int kGrid = 128;  // voxels per axis of B's map; shell points span it
  const size_t kPoses = 1000;
  const size_t per_pose = std::max<size_t>(1, a.points / kPoses);
  md << "Random poses (uniform rotation, scale 1/sqrt(2): the paper's shell spacing against the voxel size, a "
        "translation that centres them on a "
     << kGrid << "^3 map) and " << per_pose * kPoses << " random points (" << per_pose
     << " per pose, up to " << int(kGrid * std::sqrt(2.0)) << " shell units from the origin). Exact: floor of "
        "the double-precision transform of the unquantised point and pose (ref/float_model.h). Device: the "
        "quantised pose and point through ref/'s transform and floor (bit-exact with the RTL). A point disagrees "
        "when its voxel index differs on any axis. 'Shell points' are half-integers (a voxelised object's shell "
        "words, exact for PF >= 1): only the matrix and translation quantisation acts on them. 'Any points' are "
        "real-valued (points quantised to PF bits). MW = MF + 2, PW = PF + 16, TW = 48, other widths the "
        "defaults (rtl/voxcd_arch_pkg.sv).\n\n"
     << "| MF | PF | shell points: disagreeing | rate | any points: disagreeing | rate | design bound (voxels) "
        "|\n|--:|--:|--:|--:|--:|--:|--:|\n";
  csv << "mf,pf,shell_rate,any_rate,bound\n";
  for (auto [mf, pf] : a.widths) {
    DeviceConfig cfg;
    cfg.MF = mf, cfg.MW = mf + 2, cfg.PF = pf, cfg.PW = pf + 16;
    cfg.validate();
    std::mt19937_64 rng(42);
    std::normal_distribution<double> g(0, 1);
    std::uniform_real_distribution<double> u(0, 1);
    size_t bad_shell = 0, bad_any = 0, total = 0;
    double bound = 0;
    const double span = kGrid * std::sqrt(2.0);
    for (size_t k = 0; k < kPoses; ++k) {
      const Eigen::Matrix3d R = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
      FloatPose pose;
      const Eigen::Vector3d c(span / 2, span / 2, span / 2);
      const Eigen::Vector3d t = Eigen::Vector3d::Constant(kGrid / 2.0) - R * c / std::sqrt(2.0) +
                                Eigen::Vector3d(u(rng), u(rng), u(rng));
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) pose.M[i][j] = R(i, j) / std::sqrt(2.0);
        pose.t[i] = t[i];
      }
      Job job;
      job.nx = job.ny = job.nz = uint32_t(cfg.max_dim());
      quantize_pose(cfg, pose, job);
      bound = std::max(bound, error_bound_max(cfg, job, span));
      for (size_t s = 0; s < per_pose; ++s) {
        for (int kind = 0; kind < 2; ++kind) {
          double p[3];
          for (int i = 0; i < 3; ++i)
            p[i] = kind == 0 ? std::floor(u(rng) * span) + 0.5 : u(rng) * span;
          double exact[3];
          float_transform(pose, p, exact);
          const ShellWord w = quantize_point(cfg, p, "point");
          const Located l = locate(cfg, job, transform(cfg, job, w));
          bool differs = false;
          for (int i = 0; i < 3; ++i) differs |= l.index[i] != int64_t(std::floor(exact[i]));
          (kind == 0 ? bad_shell : bad_any) += differs;
        }
        ++total;
      }
    }
    const double rs = double(bad_shell) / double(total), ra = double(bad_any) / double(total);
    md << "| " << mf << " | " << pf << " | " << bad_shell << " of " << total << " | " << bench::fmt("%.2e", rs)
       << " | " << bad_any << " of " << total << " | " << bench::fmt("%.2e", ra) << " | "
       << bench::fmt("%.2g", bound) << " |\n";
    csv << mf << "," << pf << "," << rs << "," << ra << "," << bound << "\n";
    std::fprintf(stderr, "fixed MF %d PF %d: %.3g %.3g\n", mf, pf, rs, ra);
  }
  md << "\nA disagreement is a point within the error of a voxel boundary: it moves to the neighbouring voxel, "
        "which the one-voxel bounds of docs/pairs.md already cover. The design bound is the largest per-axis "
        "error bound (ref/float_model.h, error_bound_max) over the poses for points up to the span.\n";
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  try {
    if (argc < 2) throw std::invalid_argument("missing the part (pairs, error or fixed)");
    a.part = argv[1];
    if (a.part != "pairs" && a.part != "error" && a.part != "fixed")
      throw std::invalid_argument("unknown part '" + a.part + "' (pairs, error or fixed)");
    for (int i = 2; i < argc; ++i) {
      const std::string arg = argv[i];
      auto next = [&]() -> std::string {
        if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
        return argv[++i];
      };
      if (arg == "--out") a.out_path = next();
      else if (arg == "--csv") a.csv_path = next();
      else if (arg == "--repeats") a.repeats = int(parse_counts(next(), "--repeats").at(0));
      else if (arg == "--poses") a.poses = parse_counts(next(), "--poses").at(0);
      else if (arg == "--clock") a.clock = bench::clock_arg(next().c_str());
      else if (arg == "--voxels") a.voxels = parse_list(next(), "--voxels");
      else if (arg == "--shells") a.shells = parse_counts(next(), "--shells");
      else if (arg == "--maps") a.maps = parse_counts(next(), "--maps");
      else if (arg == "--points") a.points = parse_counts(next(), "--points").at(0);
      else if (arg == "--widths") {
        // MF:PF,MF:PF,...
        a.widths.clear();
        std::stringstream in(next());
        std::string item;
        while (std::getline(in, item, ',')) {
          int mf = 0, pf = 0;
          char sep = 0;
          std::stringstream is(item);
          if (!(is >> mf >> sep >> pf) || sep != ':' || !is.eof())
            throw std::invalid_argument("--widths: '" + item + "' is not MF:PF");
          a.widths.push_back({mf, pf});
        }
      } else
        throw std::invalid_argument("unknown option " + arg);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr,
                 "bench_results: %s\nusage: bench_results pairs|error|fixed [--out FILE] [--csv FILE] [--repeats N] "
                 "[--poses N] [--clock MHZ] [--voxels S,S,..] [--shells N,N,..] [--maps N,N,..] [--points N] "
                 "[--widths MF:PF,..]\n",
                 e.what());
    return 2;
  }
  std::ostringstream md, csv;
  md << bench::provenance(argc, argv) << "\n\n";
  try {
    if (a.part == "pairs") part_pairs(a, md, csv);
    else if (a.part == "error") part_error(a, md, csv);
    else part_fixed(a, md, csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_results %s: %s\n", a.part.c_str(), e.what());
    return 1;
  }
  md << "\nMachine: " << bench::machine_description() << ".\n";
  std::cout << md.str();
  if (!a.out_path.empty() && !(std::ofstream(a.out_path) << md.str())) {
    std::fprintf(stderr, "bench_results: cannot write %s\n", a.out_path.c_str());
    return 1;
  }
  if (!a.csv_path.empty() && !(std::ofstream(a.csv_path) << csv.str())) {
    std::fprintf(stderr, "bench_results: cannot write %s\n", a.csv_path.c_str());
    return 1;
  }
  return 0;
}
