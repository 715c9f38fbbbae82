// voxcd pair: the contacts of two objects at one pose or at many random ones, on any backend.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <random>
#include <stdexcept>
#include <sstream>

#include "voxcd/host/api/object.h"
#include "voxcd/host/cli/commands.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/pairs/pose_text.h"
#include "voxcd/host/report/json_text.h"

namespace voxcd::cli {

using report::Json;
using report::json_text;

namespace {

struct PairArgs {
  std::string a, b;
  std::string pose;
  size_t random = 0;
  uint64_t seed = 1;
  ObjectDef object;  // meshes' and shapes' voxel (or resolution, 32 by default) and distance field
  PairOptions opt;   // both directions, cull, margin; the mode as given in `mode`
  std::string backend = "cpu";
  int lanes = 4;
  std::string mode = "ALL";
  std::string storage = "dense";  // meshes' and shapes' forms (object files keep theirs)
  bool json = false;
  size_t show = 10;
};

// B's pose in A's frame as --pose gives it (any form parse_pose reads); an error naming --pose.
RigidPose pose_option(const std::string& s) {
  try {
    return parse_pose(s);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError("--pose", e.what());
  }
}

// v with `digits` significant digits (the precision a quantity is printed with).
double rounded(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return std::strtod(b, nullptr);
}

Json vec_json(const Eigen::Vector3d& v) { return {rounded(v.x(), 9), rounded(v.y(), 9), rounded(v.z(), 9)}; }

Json pose_json(const RigidPose& p) {
  const Eigen::Quaterniond& q = p.rotation;
  return {{"translation", {p.translation.x(), p.translation.y(), p.translation.z()}},
          {"rotation_wxyz", {q.w(), q.x(), q.y(), q.z()}}};
}

// The requests: --random N poses where the enclosing spheres overlap (B's centre uniform in that ball, both
// orientations uniform), else the one --pose (the identity without it).
std::vector<PairRequest> pair_requests(const PairArgs& a, const ObjectType& ta, const ObjectType& tb) {
  std::vector<PairRequest> reqs;
  PairRequest r;
  r.a = 0;
  r.b = 1;
  if (a.random == 0) {
    if (!a.pose.empty()) r.pose_b = pose_option(a.pose);
    return {r};
  }
  std::mt19937_64 rng(a.seed);
  std::normal_distribution<double> n(0, 1);
  std::uniform_real_distribution<double> u(0, 1);
  const double reach = ta.radius + tb.radius;
  for (size_t k = 0; k < a.random; ++k) {
    r.pose_a.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    r.pose_b.rotation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    Eigen::Vector3d d(n(rng), n(rng), n(rng));
    d = d.normalized() * reach * std::cbrt(u(rng));
    r.pose_a.translation = -(r.pose_a.rotation * ta.centre);
    r.pose_b.translation = d - r.pose_b.rotation * tb.centre;
    reqs.push_back(r);
  }
  return reqs;
}

// What a run of the requests gave, summed over them.
struct PairRun {
  std::vector<PairRequest> reqs;
  std::vector<PairResult> res;
  double secs = 0;
  uint64_t hits = 0, lookups = 0, cycles = 0, touching = 0, contacts = 0;
  bool has_cycles = false;
};

Json result_json(const PairRequest& q, const PairResult& r, bool has_cycles) {
  Json j = {{"pose_b_translation", vec_json(q.pose_b.translation)}, {"pose_a", pose_json(q.pose_a)},
            {"pose_b", pose_json(q.pose_b)}, {"hits", r.hits}, {"lookups", r.lookups}};
  if (has_cycles) j["device_cycles"] = r.device_cycles;
  Json contacts = Json::array();
  for (const Contact& c : r.contacts)
    contacts.push_back({{"shell", c.a_in_b ? "A" : "B"}, {"point", c.point}, {"position", vec_json(c.position)},
                        {"normal", vec_json(c.normal)}, {"voxel", {c.voxel[0], c.voxel[1], c.voxel[2]}},
                        {"state", int(c.state)}, {"depth", rounded(c.depth, 6)}});
  j["contacts"] = std::move(contacts);
  return j;
}

std::string pair_json(const PairArgs& a, const ObjectType& ta, const ObjectType& tb, const DeviceConfig& cfg,
                      const PairRun& run) {
  // The voxel the objects were built at (an object file brings its own): one number when they share it.
  const double va = ta.voxmap().voxel(), vb = tb.voxmap().voxel();
  Json j = {{"a", a.a},
            {"b", a.b},
            {"voxel", va == vb ? Json(va) : Json{va, vb}},
            {"backend", a.backend},
            {"mode", a.mode},
            {"both_directions", a.opt.both_directions},
            {"pairs", run.res.size()},
            {"touching", run.touching},
            {"hits", run.hits},
            {"lookups", run.lookups},
            {"seconds", rounded(run.secs, 6)}};
  if (run.has_cycles) j["device_cycles"] = run.cycles;
  j["lanes"] = cfg.LANES;
  j["bl"] = cfg.BL;  // a sparse device's brick size (0: dense maps and shells only)
  if (cfg.distance()) {
    j["distance_bits"] = cfg.SB;
    j["band"] = {rounded(ta.object.distance_band() * va, 6), rounded(tb.object.distance_band() * vb, 6)};
    j["margin"] = rounded(a.opt.margin, 6);
  }
  Json results = Json::array();
  for (size_t i = 0; i < run.res.size(); ++i) results.push_back(result_json(run.reqs[i], run.res[i], run.has_cycles));
  j["results"] = std::move(results);
  return json_text(j) + "\n";
}

void print_pair_text(const PairArgs& a, const ObjectType& ta, const ObjectType& tb, const DeviceConfig& cfg,
                     const PairRun& run) {
  std::printf("A %s: %zu shell points, voxmap %ux%ux%u, voxel %g; B %s: %zu shell points, voxmap %ux%ux%u, voxel %g\n",
              a.a.c_str(), ta.shell().size(), ta.voxmap().dims()[0], ta.voxmap().dims()[1], ta.voxmap().dims()[2],
              ta.voxmap().voxel(), a.b.c_str(), tb.shell().size(), tb.voxmap().dims()[0], tb.voxmap().dims()[1],
              tb.voxmap().dims()[2], tb.voxmap().voxel());
  std::printf("backend %s, mode %s%s: %zu pair%s, %llu touching, %llu hits, %llu contacts, %llu lookups in %.3f ms "
              "(%.2f ns per lookup)\n",
              a.backend.c_str(), a.mode.c_str(), a.opt.both_directions ? ", both directions" : "", run.res.size(),
              run.res.size() == 1 ? "" : "s", (unsigned long long)run.touching, (unsigned long long)run.hits,
              (unsigned long long)run.contacts, (unsigned long long)run.lookups, run.secs * 1e3,
              run.lookups ? run.secs * 1e9 / double(run.lookups) : 0.0);
  if (run.has_cycles)
    std::printf("device cycles: %llu at %d lanes%s (%s)\n", (unsigned long long)run.cycles, cfg.LANES,
                cfg.sparse() ? (", sparse device BL " + std::to_string(cfg.BL)).c_str() : "",
                a.backend == "rtl" ? "measured on the RTL" : "the exact timing model of ref/");
  size_t shown = 0;
  for (const PairResult& r : run.res)
    for (const Contact& c : r.contacts) {
      if (shown++ >= a.show) break;
      std::printf("  contact: %s point %u at (%.4g, %.4g, %.4g) normal (%.3f, %.3f, %.3f) state %d depth %.4g\n",
                  c.a_in_b ? "A" : "B", c.point, c.position.x(), c.position.y(), c.position.z(), c.normal.x(),
                  c.normal.y(), c.normal.z(), int(c.state), c.depth);
    }
  if (run.contacts > a.show)
    std::printf("  ... %llu more (--show N, or --json for all)\n", (unsigned long long)(run.contacts - a.show));
}

int pair_cmd(const PairArgs& a) {
  // Without --voxel: the longest side of the larger mesh / --resolution (32 by default), shared by both objects.
  const ObjectDef& o = a.object;
  const double voxel = o.voxel > 0 ? o.voxel : shared_voxel({a.a, a.b}, o.resolution);
  const std::optional<ObjectStorage> storage = parse_storage(a.storage);
  if (!storage) throw CLI::ValidationError("--storage", "'" + a.storage + "' is not auto, dense or sparse");
  auto ta = std::make_shared<ObjectType>(load_object_type(a.a, voxel, o.distance_bits, o.band, *storage));
  auto tb = std::make_shared<ObjectType>(load_object_type(a.b, voxel, o.distance_bits, o.band, *storage));
  const DeviceConfig cfg = device_config_for(a.backend, a.lanes, {ta.get(), tb.get()}, o.distance_bits);
  PairCollider collider(make_device(a.backend, cfg), {ta, tb});
  PairOptions opt = a.opt;
  const auto mode = parse_mode(a.mode);
  if (!mode) throw CLI::ValidationError("--mode", "'" + a.mode + "' is not ALL, FIRST or COUNT");
  opt.mode = *mode;
  PairRun run;
  run.reqs = pair_requests(a, *ta, *tb);
  const auto t0 = std::chrono::steady_clock::now();
  run.res = collider.collide(run.reqs, opt);
  run.secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const PairResult& r : run.res) {
    run.hits += r.hits;
    run.lookups += r.lookups;
    run.cycles += r.device_cycles;
    run.contacts += r.contacts.size();
    run.touching += r.hits > 0;
  }
  run.has_cycles = collider.device().models_cycles();
  if (a.json)
    std::cout << pair_json(a, *ta, *tb, cfg, run);
  else
    print_pair_text(a, *ta, *tb, cfg, run);
  return 0;
}

}  // namespace

void add_pair(CLI::App& app) {
  auto a = std::make_shared<PairArgs>();
  CLI::App* c = app.add_subcommand("pair", "Contacts of two objects (object files, meshes or built-in shapes) at "
                                           "a pose or at random poses (docs/pairs.md)");
  c->add_option("a", a->a, "Object A: an object file, a mesh file or a built-in shape")->required();
  c->add_option("b", a->b, "Object B: an object file, a mesh file or a built-in shape")->required();
  c->add_option("--pose", a->pose,
                "B's pose in A's frame: tx,ty,tz[,rx,ry,rz] (rotation in degrees about x, then y, then z), "
                "tx,ty,tz,qw,qx,qy,qz (a unit quaternion), 12 or 16 numbers (a 3x4 or 4x4 matrix, row-major), or "
                "the JSON of a pose this command prints ({\"translation\": [...], \"rotation_wxyz\": [...]})");
  c->add_option("--random", a->random, "Test N random poses where the bounding spheres overlap instead");
  c->add_option("--seed", a->seed, "Seed of --random")->capture_default_str();
  CLI::Option* voxel = c->add_option("--voxel", a->object.voxel,
                                     "Voxel size for meshes and shapes (default: 1/32 of the larger one's longest side)");
  CLI::Option* res = c->add_option("--resolution", a->object.resolution,
                                   "Voxels along the larger mesh's longest side, shared by both (instead of --voxel)")
                         ->check(CLI::Range(4u, 1u << 20));
  voxel->excludes(res);
  res->excludes(voxel);
  c->add_option("--distance-bits", a->object.distance_bits,
                "Distance voxmaps of B bits (4, 8 or 16) on a distance device instead of 2-bit states "
                "(meshes and shapes get a distance field; object files must have one)")
      ->check(CLI::IsMember(kDistanceBits));
  c->add_option("--band", a->object.band, "Band of the distance fields, voxels (with --distance-bits)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  c->add_option("--storage", a->storage,
                "Meshes and shapes: dense, sparse (on a sparse device) or auto, whichever takes less device memory "
                "(docs/objects.md, \"Sparse objects\"); object files keep the forms they were saved in")
      ->check(CLI::IsMember({"auto", "dense", "sparse"}))
      ->capture_default_str();
  c->add_option("--margin", a->opt.margin,
                "Distance device: contacts where the other object's distance is at most this, world units")
      ->capture_default_str();
  c->add_option("--backend", a->backend, "Device backend: " + comma_list(backend_names()))->capture_default_str();
  c->add_option("--lanes", a->lanes, "Lanes of the modelled device")->check(CLI::Range(1, 64))->capture_default_str();
  c->add_option("--mode", a->mode, "ALL (every contact), FIRST (one per direction) or COUNT")->capture_default_str();
  c->add_flag("--both,!--no-both", a->opt.both_directions,
              "Test both directions, A's shell in B and B's shell in A (the default); --no-both: A's shell in B only");
  c->add_option("--show", a->show, "Contacts to print (text output)")->capture_default_str();
  c->add_flag("!--no-cull", a->opt.cull,
              "submit every shell point (by default only the clusters of points that can land in the other "
              "object's voxmap; the contacts are the same)");
  c->add_flag("--json", a->json, "Print the result as JSON, with every contact");
  c->callback([a] { exit_code() = pair_cmd(*a); });
}

}  // namespace voxcd::cli
