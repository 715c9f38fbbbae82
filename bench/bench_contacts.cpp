// Pair queries that return every contact, against FCL's exhaustive collide, on one thread each, in one run: the
// room-and-robot scene (bench/room_scene.h: few triangles filling a large space, 300 poses in one batch, voxel = the
// room's size / 64) and the two 10,000-triangle tori of bench_pair (voxel 0.02). voxcd runs both directions, ALL
// contacts, as a batch into PairResults, as a batch into ContactArrays, and one pose per call. Every method runs on
// the calling thread and is timed by that thread's CPU time (the machine is shared: wall times would measure its
// load); the methods take turns within every repeat, and times are medians. Writes Markdown to
// stdout (and to --out FILE); --write DIR also writes the objects and poses for bench/contacts_python.py, and --json
// prints one JSON line per scene with the times.
#include <fcl/fcl.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

#include "bench/bench_common.h"
#include "bench/fcl_common.h"
#include "bench/room_scene.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/pairs/pose_text.h"

using namespace voxcd;

namespace {

struct Scene {
  std::string name;
  Mesh a, b;
  double voxel;
  std::vector<PairRequest> poses;
};

struct Times {
  std::vector<double> fcl, batch, arrays, one;
};

// B's pose in A's frame as `voxcd pair --pose` takes it (A is at the identity): tx ty tz rx ry rz, degrees about x,
// then y, then z.
std::string pose_line(const RigidPose& p) {
  const Eigen::Vector3d e = p.rotation.toRotationMatrix().eulerAngles(2, 1, 0) * (180.0 / M_PI);
  char b[256];
  std::snprintf(b, sizeof b, "%.17g %.17g %.17g %.17g %.17g %.17g", p.translation.x(), p.translation.y(),
                p.translation.z(), e[2], e[1], e[0]);
  return b;
}

// The poses as the Python module will read them back (Euler angles in degrees), so both run the same poses.
void as_euler(std::vector<PairRequest>& poses) {
  for (PairRequest& r : poses) {
    std::istringstream in(pose_line(r.pose_b));
    double v[6];
    for (double& x : v) in >> x;
    r.pose_b = euler_pose(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(v[3], v[4], v[5]));
  }
}

// Every method in turn within each repeat, each timed by the thread's CPU time; the last repeat's batch results in
// `batch` and `arrays`, FCL's contacts in `fcl_contacts`.
Times time_methods(const Scene& s, PairCollider& col, const PairOptions& opt, int repeats, bool profile,
                   std::vector<PairResult>& batch, ContactArrays& arrays, size_t& fcl_contacts) {
  auto fa = bench::bvh_of(s.a), fb = bench::bvh_of(s.b);
  std::vector<PairResult> one;
  std::vector<PairRequest> req(1);
  Times t;
  for (int r = 0; r < repeats; ++r) {
    if (!profile) {
      double t0 = bench::thread_cpu_seconds();
      fcl_contacts = 0;
      for (const PairRequest& p : s.poses) {
        fcl::CollisionRequestd rq(100000000, true);
        fcl::CollisionResultd rs;
        fcl::CollisionObjectd oa(fa, bench::to_fcl(p.pose_a)), ob(fb, bench::to_fcl(p.pose_b));
        fcl::collide(&oa, &ob, rq, rs);
        fcl_contacts += rs.numContacts();
      }
      t.fcl.push_back(bench::thread_cpu_seconds() - t0);
    }
    double t0 = bench::thread_cpu_seconds();
    col.collide(s.poses, opt, batch);
    t.batch.push_back(bench::thread_cpu_seconds() - t0);
    t0 = bench::thread_cpu_seconds();
    col.collide(s.poses, opt, arrays);
    t.arrays.push_back(bench::thread_cpu_seconds() - t0);
    t0 = bench::thread_cpu_seconds();
    for (const PairRequest& p : s.poses) {
      req[0] = p;
      col.collide(req, opt, one);
      bench::keep(one);
    }
    t.one.push_back(bench::thread_cpu_seconds() - t0);
  }
  return t;
}

void run_scene(const Scene& s, int repeats, bool profile, const std::string& write_dir, bool json,
               std::ostringstream& md) {
  ObjectOptions o;
  o.voxel = s.voxel;
  o.threads = 1;
  auto ta = std::make_shared<ObjectType>(make_object_type(make_object(s.a, s.a.name, 0, o), s.a.name));
  auto tb = std::make_shared<ObjectType>(make_object_type(make_object(s.b, s.b.name, 0, o), s.b.name));
  if (!write_dir.empty()) {
    write_object(write_dir + "/" + s.name + "_a.vxo", ta->object);
    write_object(write_dir + "/" + s.name + "_b.vxo", tb->object);
    std::ofstream poses(write_dir + "/" + s.name + "_poses.txt");
    for (const PairRequest& r : s.poses) poses << pose_line(r.pose_b) << "\n";
  }
  DeviceOptions dopt;
  dopt.threads = 1;
  PairCollider col(make_device("cpu", fit_memory(DeviceConfig{}, {ta.get(), tb.get()}), dopt), {ta, tb});
  PairOptions opt;
  opt.both_directions = true;
  size_t fcl_contacts = 0;
  ContactArrays arrays;
  std::vector<PairResult> batch;
  const Times t = time_methods(s, col, opt, repeats, profile, batch, arrays, fcl_contacts);
  size_t contacts = 0, lookups = 0;
  for (const PairResult& r : batch) contacts += r.contacts.size(), lookups += r.lookups;
  if (arrays.size() != contacts) {
    std::fprintf(stderr, "%s: ContactArrays holds %zu contacts, the PairResults %zu\n", s.name.c_str(), arrays.size(),
                 contacts);
    std::exit(1);
  }
  const double n = double(s.poses.size());
  const double fcl_us = bench::median(t.fcl) * 1e6 / n;
  auto row = [&](const char* method, const std::vector<double>& v) {
    const double us = bench::median(v) * 1e6 / n;
    md << "| " << s.name << " | " << method << " | " << bench::fmt("%.1f", us) << " | "
       << (profile ? "-" : bench::fmt("%.1f", fcl_us / us)) << " | " << bench::fmt("%.0f", double(contacts) / n)
       << " | " << bench::fmt("%.0f", double(lookups) / n) << " |\n";
  };
  md << "| " << s.name << " | FCL exhaustive collide | " << bench::fmt("%.1f", fcl_us) << " | 1.0 | "
     << bench::fmt("%.0f", double(fcl_contacts) / n) << " | - |\n";
  row("voxcd, batch into PairResults", t.batch);
  row("voxcd, batch into ContactArrays", t.arrays);
  row("voxcd, one pose per call", t.one);
  std::fprintf(stderr, "%s: %zu+%zu triangles, shells %zu/%zu, voxmaps %ux%ux%u/%ux%ux%u\n", s.name.c_str(),
               s.a.size(), s.b.size(), ta->shell().size(), tb->shell().size(), ta->voxmap().dims()[0],
               ta->voxmap().dims()[1], ta->voxmap().dims()[2], tb->voxmap().dims()[0], tb->voxmap().dims()[1],
               tb->voxmap().dims()[2]);
  if (json)
    std::printf("{\"scene\": \"%s\", \"poses\": %zu, \"fcl_us\": %.3f, \"batch_us\": %.3f, \"arrays_us\": %.3f, "
                "\"one_us\": %.3f, \"contacts\": %zu, \"lookups\": %zu}\n",
                s.name.c_str(), s.poses.size(), fcl_us, bench::median(t.batch) * 1e6 / n,
                bench::median(t.arrays) * 1e6 / n, bench::median(t.one) * 1e6 / n, contacts, lookups);
}

}  // namespace

int main(int argc, char** argv) {
  std::string out_path, write_dir, only;
  int repeats = 5;
  size_t room_poses = 300, torus_poses = 40;
  bool profile = false, json = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) out_path = argv[++i];
    else if (a == "--repeats" && i + 1 < argc) repeats = std::atoi(argv[++i]);
    else if (a == "--scene" && i + 1 < argc) only = argv[++i];
    else if (a == "--room-poses" && i + 1 < argc) room_poses = size_t(std::atol(argv[++i]));
    else if (a == "--torus-poses" && i + 1 < argc) torus_poses = size_t(std::atol(argv[++i]));
    else if (a == "--write" && i + 1 < argc) write_dir = argv[++i];
    else if (a == "--profile") profile = true;  // voxcd only (for callgrind)
    else if (a == "--json") json = true;
    else {
      std::fprintf(stderr,
                   "usage: bench_contacts [--scene room|torus] [--repeats N] [--room-poses N] [--torus-poses N] "
                   "[--write DIR] [--json] [--profile] [--out FILE]\n");
      return 2;
    }
  }
  if (repeats < 1 || (!only.empty() && only != "room" && only != "torus")) {
    std::fprintf(stderr, "bench_contacts: --repeats must be >= 1 and --scene room or torus\n");
    return 2;
  }
  std::vector<Scene> scenes;
  if (only.empty() || only == "room") {
    Mesh room = bench::make_room(), robot = bench::make_robot();
    const double voxel = voxel_for_resolution(room, 64);
    scenes.push_back({"room", room, robot, voxel, bench::robot_poses(room_poses, 11)});
  }
  if (only.empty() || only == "torus") {
    Mesh a = make_torus(1.0, 0.35, 100, 50), b = make_torus(0.8, 0.3, 100, 50);
    a.name = "torus A", b.name = "torus B";
    scenes.push_back({"torus", a, b, 0.02, bench::torus_poses(torus_poses, 5)});
  }
  std::ostringstream md;
  md << bench::provenance(argc, argv) << "\n\n"
     << "| scene | method | us per pose (median of " << repeats << ") | ratio (FCL / this) | contacts per pose | "
        "lookups per pose |\n|---|---|--:|--:|--:|--:|\n";
  for (Scene& s : scenes) {
    as_euler(s.poses);
    run_scene(s, repeats, profile, write_dir, json, md);
  }
  md << "\nOne thread each, CPU time of the thread. room: " << bench::make_room().size() << " + "
     << bench::make_robot().size()
     << " triangles; torus: 10,000 + 10,000. voxcd: cpu backend, both directions, every contact (position, normal, "
        "voxel, state, depth). FCL "
     << FCL_VERSION << ": `fcl::collide` on OBBRSS hierarchies, every contact (exact triangle pairs). Machine: "
     << bench::machine_description() << ".\n";
  if (!json) std::cout << md.str();
  if (!out_path.empty()) std::ofstream(out_path) << md.str();
  return 0;
}
