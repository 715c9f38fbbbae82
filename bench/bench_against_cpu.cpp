// The figures of docs/hardware.md "Against the CPU" that `voxcd simulate` does not give (bench/against_cpu.sh makes
// the table): on two scenes of real objects, the device's cycles from the exact timing model for every lane count and
// depth asked (the cpu backend returns the cycles of the configuration it is given, those of the RTL cycle for
// cycle), and on those scenes and the built-in scene of `voxcd simulate` the cpu backend's own lookups per second on
// the same jobs, on one core and on every core.
//  - builtin: `voxcd simulate --objects N --frames F`'s scene (polytopes, seed 1); the pairs each frame tested, at
//    the poses of that frame, as PairRequests, and simulate's PairOptions (ALL, one direction, culled);
//  - room: the robot at random poses in the room (bench/room_scene.h, voxel = the room's size / 64), both directions,
//    as bench_contacts runs it;
//  - tori: torus B at random poses about torus A (bench_pair's tori of 10,000 triangles, voxel 0.02), both
//    directions.
// Prints one JSON object a line: {"kind": "scene", ...} describing each scene, {"kind": "cycles", ...} per scene and
// configuration (room and tori), {"kind": "cpu", ...} per scene: median seconds of `repeats` runs of the jobs on the
// cpu backend with one thread (that thread's CPU time) and with every hardware thread (wall time).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "bench/room_scene.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/pairs/collide.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/simulate.h"

using namespace voxcd;

namespace {

struct Args {
  std::vector<int> lanes = {4, 8, 16, 32, 64}, depths = {0, 4};
  uint64_t objects = 1024, frames = 1000;
  size_t room_poses = 20000, torus_poses = 1000;
  int repeats = 5;
};

// One workload: the object types, the pair queries and how they are asked.
struct Workload {
  std::string name, description;
  std::vector<std::shared_ptr<const ObjectType>> types;
  std::vector<PairRequest> requests;
  PairOptions options;
};

std::vector<int> int_list(const char* text) {
  std::vector<int> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) out.push_back(std::atoi(item.c_str()));
  return out;
}

bool parse_args(int argc, char** argv, Args& a) {
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    if (i + 1 >= argc) return false;
    const char* v = argv[++i];
    if (k == "--lanes") a.lanes = int_list(v);
    else if (k == "--depths") a.depths = int_list(v);
    else if (k == "--objects") a.objects = std::strtoull(v, nullptr, 10);
    else if (k == "--frames") a.frames = std::strtoull(v, nullptr, 10);
    else if (k == "--room-poses") a.room_poses = std::strtoull(v, nullptr, 10);
    else if (k == "--torus-poses") a.torus_poses = std::strtoull(v, nullptr, 10);
    else if (k == "--repeats") a.repeats = std::atoi(v);
    else return false;
  }
  return a.repeats >= 1 && a.frames >= 1 && a.objects >= 1 && !a.lanes.empty() && !a.depths.empty();
}

std::shared_ptr<const ObjectType> voxelised(const Mesh& mesh, double voxel) {
  ObjectOptions o;
  o.voxel = voxel;
  return std::make_shared<ObjectType>(make_object_type(make_object(mesh, mesh.name, 0, o), mesh.name));
}

// The pairs one frame of the simulation tested, at that frame's poses, appended to `out`.
void append_frame_requests(const Simulation& sim, std::vector<PairRequest>& out) {
  const std::vector<Body>& bodies = sim.scene().bodies;
  for (const BodyPair& p : sim.tested_pairs()) {
    PairRequest r;
    r.a = bodies[p.first].type, r.b = bodies[p.second].type;
    r.pose_a = bodies[p.first].pose, r.pose_b = bodies[p.second].pose;
    out.push_back(r);
  }
}

Workload builtin_workload(const Args& a) {
  RunConfig o;
  o.types[0].count = a.objects;
  o.given["types[0].count"] = SettingSource{"", "objects"};
  o.frames = a.frames;
  o.given["frames"] = SettingSource{"", "frames"};
  const RunConfig c = run_config(o);
  Scene scene = make_scene(c);
  Workload w;
  w.name = "builtin";
  w.types = scene.types;
  Simulation sim(std::move(scene), c);
  for (uint64_t f = 0; f < c.frames; ++f) {
    sim.step();
    append_frame_requests(sim, w.requests);
  }
  w.options.mode = c.mode, w.options.both_directions = c.both_directions, w.options.cull = c.cull;
  w.description = "voxcd simulate's built-in scene: " + std::to_string(a.objects) + " polytope36 objects, " +
                  std::to_string(a.frames) + " frames, the pairs each frame tested (ALL, one direction)";
  return w;
}

Workload room_workload(const Args& a) {
  Workload w;
  w.name = "room";
  const Mesh room = bench::make_room(), robot = bench::make_robot();
  const double voxel = voxel_for_resolution(room, 64);
  w.types = {voxelised(room, voxel), voxelised(robot, voxel)};
  w.requests = bench::robot_poses(a.room_poses, 11);
  w.options.both_directions = true;
  w.description = "bench/room_scene.h: the robot (" + std::to_string(robot.size()) + " triangles) at " +
                  std::to_string(a.room_poses) + " poses in the room (" + std::to_string(room.size()) +
                  " triangles), voxel = the room / 64, ALL, both directions";
  return w;
}

Workload torus_workload(const Args& a) {
  Workload w;
  w.name = "tori";
  Mesh ta = make_torus(1.0, 0.35, 100, 50), tb = make_torus(0.8, 0.3, 100, 50);
  ta.name = "torus A", tb.name = "torus B";
  w.types = {voxelised(ta, 0.02), voxelised(tb, 0.02)};
  w.requests = bench::torus_poses(a.torus_poses, 5);
  w.options.both_directions = true;
  w.description = "bench/room_scene.h torus_poses: torus B (10,000 triangles) at " + std::to_string(a.torus_poses) +
                  " random poses about torus A (10,000 triangles), voxel 0.02, ALL, both directions";
  return w;
}

std::vector<const ObjectType*> raw(const Workload& w) {
  std::vector<const ObjectType*> out;
  for (const auto& t : w.types) out.push_back(t.get());
  return out;
}

PairCollider collider(const Workload& w, int lanes, int depth, unsigned threads) {
  DeviceConfig cfg;
  cfg.LANES = lanes;
  cfg.depth = depth;
  DeviceOptions opt;
  opt.threads = threads;
  return PairCollider(make_device("cpu", fit_memory(cfg, raw(w)), opt), w.types);
}

void print_scene(const Workload& w) {
  std::printf("{\"kind\": \"scene\", \"scene\": \"%s\", \"pairs\": %zu, \"description\": \"%s\"}\n", w.name.c_str(),
              w.requests.size(), w.description.c_str());
}

// The lookups and cycles of the workload on the device of `lanes` and `depth`, from the timing model.
void print_cycles(const Workload& w, int lanes, int depth) {
  PairCollider col = collider(w, lanes, depth, 0);
  uint64_t lookups = 0, cycles = 0;
  for (const PairResult& r : col.collide(w.requests, w.options)) lookups += r.lookups, cycles += r.device_cycles;
  std::printf("{\"kind\": \"cycles\", \"scene\": \"%s\", \"lanes\": %d, \"depth\": %d, \"lookups\": %llu, "
              "\"cycles\": %llu, \"device\": \"%s\"}\n",
              w.name.c_str(), lanes, depth, (unsigned long long)lookups, (unsigned long long)cycles,
              col.device().config().to_string().c_str());
  std::fflush(stdout);
}

// Median seconds of `repeats` runs of `jobs` on the collider's device: one thread by its CPU time, more by wall time.
double time_jobs(PairCollider& col, const std::vector<Job>& jobs, bool one_thread, int repeats) {
  std::vector<Record> recs;
  col.device().run_into(jobs, recs);  // warm-up
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const double t0 = one_thread ? bench::thread_cpu_seconds() : bench::now_seconds();
    col.device().run_into(jobs, recs);
    t.push_back((one_thread ? bench::thread_cpu_seconds() : bench::now_seconds()) - t0);
    bench::keep(recs);
  }
  return bench::median(t);
}

uint64_t job_points(const std::vector<Job>& jobs) {
  uint64_t n = 0;
  for (const Job& j : jobs) n += j.shell_count;
  return n;
}

// The cpu backend's time for the workload's jobs (the default configuration's: its speed does not depend on LANES or
// depth) on one thread and on every hardware thread.
void print_cpu(const Workload& w, int repeats) {
  PairCollider one = collider(w, 4, 0, 1), all = collider(w, 4, 0, 0);
  const std::vector<Job> jobs = one.jobs(w.requests, w.options);
  const double t1 = time_jobs(one, jobs, true, repeats), tn = time_jobs(all, jobs, false, repeats);
  std::printf("{\"kind\": \"cpu\", \"scene\": \"%s\", \"jobs\": %zu, \"lookups\": %llu, \"one_core_s\": %.9g, "
              "\"all_cores_s\": %.9g, \"threads\": %u, \"repeats\": %d}\n",
              w.name.c_str(), jobs.size(), (unsigned long long)job_points(jobs), t1, tn,
              ThreadPool::available_cpus(), repeats);
  std::fflush(stdout);
}

void run(const Workload& w, const Args& a, bool cycles) {
  print_scene(w);
  if (cycles)
    for (int lanes : a.lanes)
      for (int depth : a.depths) print_cycles(w, lanes, depth);
  print_cpu(w, a.repeats);
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  if (!parse_args(argc, argv, a)) {
    std::fprintf(stderr, "usage: bench_against_cpu [--lanes 4,8,...] [--depths 0,4] [--objects N] [--frames F] "
                         "[--room-poses N] [--torus-poses N] [--repeats R]\n");
    return 2;
  }
  try {
    run(builtin_workload(a), a, false);  // its cycles come from voxcd simulate
    run(room_workload(a), a, true);
    run(torus_workload(a), a, true);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_against_cpu: %s\n", e.what());
    return 1;
  }
  return 0;
}
