// bench_energy: the stimulus of bench/energy.sh (docs/hardware.md, "Energy per lookup"): vector files
// (ref/vectors.h) of the jobs real scenes send to the device, each with the device configuration, the memory image
// and the jobs, to run on the rtl backend with a waveform trace. Three scenes:
//   simulate: the built-in scene of `voxcd simulate` (host/scene) at --objects objects, the jobs of --frames frames
//             (the pairs each frame tested on the device, at their poses, through the same PairCollider and options
//             the simulation uses);
//   room:     the room and the robot of bench/room_scene.h, robot poses in the room, both directions;
//   tori:     two tori (host/object/shapes) at random poses about each other (bench/room_scene.h torus_poses).
// Every scene's memories must fit the measured configuration (--config: its SAW and MAW): the scene's voxel is grown
// by 10% steps from its starting value until its shells and voxmaps fit, and the voxel used is printed. The files
// are written in the configuration of the RTL model the rtl backend has (--model: the measured configuration's
// widths with the model's SAW and MAW; the contents are the same, the upper address bits stay 0). Each stream stops
// at --max-lookups shell points looked up (whole frames, whole poses).
// Prints one line per scene: "scene NAME file FILE jobs N lookups L pairs P voxel V shell_words S map_words M frames F"
// (F: the simulate scene's frames, 0 for the others).
// Usage: bench_energy --out DIR [--config "PW 24 ... SAW 12 MAW 12 ..."] [--model "LANES 4 SAW 16 MAW 18"]
//                     [--objects 1024] [--frames 3] [--poses 400] [--max-lookups 200000] [--scenes simulate,room,tori]
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "bench/room_scene.h"
#include "voxcd/host/device/device.h"
#include "voxcd/host/object/object_file.h"
#include "voxcd/host/object/object_type.h"
#include "voxcd/host/object/shapes.h"
#include "voxcd/host/object/voxelize.h"
#include "voxcd/host/pairs/collider.h"
#include "voxcd/host/pairs/image.h"
#include "voxcd/host/scene/run_config.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/ref/vectors.h"

using namespace voxcd;

namespace {

struct Stream {
  std::vector<Job> jobs;
  DeviceMemory memory;
  uint64_t lookups = 0;
  uint64_t pairs = 0;
  uint64_t frames = 0;  // simulate: the frames whose jobs the stream holds (0: a scene of poses)
  double voxel = 0;
};

// Whether the image of `types` fits the measured configuration's memories (and the model's); the image's sizes.
bool fits(const DeviceConfig& measured, const DeviceConfig& model, const std::vector<std::shared_ptr<const ObjectType>>& types,
          DeviceMemory* mem) {
  DeviceImage image(model);
  try {
    for (const auto& t : types) image.add(*t, shell_order(model, *t));
  } catch (const CapacityError&) {
    return false;
  }
  *mem = image.memory();
  return mem->shell.size() <= measured.shell_depth() && mem->map.size() <= measured.map_depth();
}

uint64_t lookups_of(const std::vector<Job>& jobs) {
  uint64_t n = 0;
  for (const Job& j : jobs) n += j.shell_count;
  return n;
}

// Appends the pair jobs of `requests` on a collider of `types`, pair by pair, until max_lookups; counts the pairs.
void add_jobs(const PairCollider& col, const std::vector<PairRequest>& requests, const PairOptions& opt, Stream& s,
              uint64_t max_lookups) {
  for (const PairRequest& r : requests) {
    if (s.lookups >= max_lookups) return;
    const std::vector<Job> js = col.jobs({r}, opt);
    s.jobs.insert(s.jobs.end(), js.begin(), js.end());
    s.lookups += lookups_of(js);
    ++s.pairs;
  }
}

std::unique_ptr<PairCollider> collider(const DeviceConfig& model, std::vector<std::shared_ptr<const ObjectType>> types) {
  DeviceOptions dopt;
  dopt.threads = 1;
  return std::make_unique<PairCollider>(make_device("cpu", model, dopt), std::move(types));
}

// The built-in scene of voxcd simulate at `objects` objects, `frames` frames on the cpu backend at the model's
// configuration; each frame's tested pairs at their poses (the response changes only velocities and spins).
Stream simulate_stream(const DeviceConfig& measured, const DeviceConfig& model, uint64_t objects, uint64_t frames,
                       uint64_t max_lookups) {
  RunConfig c;
  c.types[0].count = objects;
  c.backend = "cpu";
  c.lanes = model.LANES;
  c.device = model;
  c.frames = frames;
  c.threads = 1;
  for (int attempt = 0;; ++attempt) {
    check(c);
    Scene scene = make_scene(c);
    Stream s;
    if (!fits(measured, model, scene.types, &s.memory)) {
      if (attempt > 40) throw std::runtime_error("simulate: no voxel makes the scene fit the memories");
      const double v = scene.types[0]->object.voxmap.voxel();
      c.types[0].voxel = v * 1.1;
      c.types[0].resolution = 0;
      continue;
    }
    s.voxel = scene.types[0]->object.voxmap.voxel();
    auto col = collider(model, scene.types);
    PairOptions po;
    po.mode = c.mode;
    po.both_directions = c.both_directions;
    po.cull = c.cull;
    po.margin = c.margin;
    Simulation sim(scene, c);
    for (uint64_t f = 0; f < frames && s.lookups < max_lookups; ++f) {
      sim.step();
      std::vector<PairRequest> requests;
      for (const BodyPair& p : sim.tested_pairs()) {
        const Body &a = sim.scene().bodies[p.first], &b = sim.scene().bodies[p.second];
        PairRequest r;
        r.a = a.type, r.b = b.type, r.pose_a = a.pose, r.pose_b = b.pose;
        requests.push_back(r);
      }
      add_jobs(*col, requests, po, s, max_lookups);
      ++s.frames;
    }
    return s;
  }
}

// Two meshes at voxel `voxel` (grown until they fit), the poses' jobs both directions.
Stream pair_stream(const DeviceConfig& measured, const DeviceConfig& model, const Mesh& a, const Mesh& b, double voxel,
                   const std::vector<PairRequest>& poses, uint64_t max_lookups) {
  for (int attempt = 0; attempt < 60; ++attempt, voxel *= 1.1) {
    ObjectOptions o;
    o.voxel = voxel;
    o.threads = 1;
    auto ta = std::make_shared<const ObjectType>(make_object_type(make_object(a, a.name, 0, o), a.name));
    auto tb = std::make_shared<const ObjectType>(make_object_type(make_object(b, b.name, 0, o), b.name));
    Stream s;
    if (!fits(measured, model, {ta, tb}, &s.memory)) continue;
    s.voxel = voxel;
    auto col = collider(model, {ta, tb});
    PairOptions opt;
    opt.both_directions = true;
    add_jobs(*col, poses, opt, s, max_lookups);
    return s;
  }
  throw std::runtime_error("no voxel makes " + a.name + " and " + b.name + " fit the memories");
}

void write(const std::string& path, const DeviceConfig& model, Stream& s) {
  // Tags in order (the frames' and poses' own tags restart), within TAGW bits.
  for (size_t k = 0; k < s.jobs.size(); ++k) s.jobs[k].tag = uint32_t(k & model.max_tag());
  DeviceOptions dopt;
  dopt.threads = 1;
  auto dev = make_device("cpu", model, dopt);
  dev->load(s.memory);
  const std::vector<Record> records = dev->run(s.jobs);
  std::ofstream f(path);
  write_vectors(f, model, true, s.memory, s.jobs, records);
  if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace

int main(int argc, char** argv) {
  std::string out, scenes = "simulate,room,tori";
  std::string config = "PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 LANES 4 SAW 12 MAW 12 TAGW 16";
  std::string model_pairs;
  uint64_t objects = 1024, frames = 3, poses = 400, max_lookups = 200000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--out") out = next();
    else if (a == "--config") config = next();
    else if (a == "--model") model_pairs = next();
    else if (a == "--objects") objects = std::stoull(next());
    else if (a == "--frames") frames = std::stoull(next());
    else if (a == "--poses") poses = std::stoull(next());
    else if (a == "--max-lookups") max_lookups = std::stoull(next());
    else if (a == "--scenes") scenes = next();
    else {
      std::fprintf(stderr, "usage: bench_energy --out DIR [--config PAIRS] [--model PAIRS] [--objects N] [--frames N] "
                           "[--poses N] [--max-lookups N] [--scenes simulate,room,tori]\n");
      return 2;
    }
  }
  if (out.empty()) {
    std::fprintf(stderr, "bench_energy: --out DIR is required\n");
    return 2;
  }
  try {
    const DeviceConfig measured = parse_config_pairs(config, "--config");
    // The model: the measured widths with the memory sizes of the rtl backend's models (the defaults), or --model.
    DeviceConfig model = measured;
    model.SAW = DeviceConfig{}.SAW;
    model.MAW = DeviceConfig{}.MAW;
    if (!model_pairs.empty()) model = parse_config_pairs(model_pairs, "--model");
    std::stringstream list(scenes);
    for (std::string name; std::getline(list, name, ',');) {
      Stream s;
      if (name == "simulate") {
        s = simulate_stream(measured, model, objects, frames, max_lookups);
      } else if (name == "room") {
        Mesh room = bench::make_room(), robot = bench::make_robot();
        s = pair_stream(measured, model, room, robot, voxel_for_resolution(room, 48), bench::robot_poses(poses, 11),
                        max_lookups);
      } else if (name == "tori") {
        Mesh a = make_torus(1.0, 0.35, 100, 50), b = make_torus(0.8, 0.3, 100, 50);
        a.name = "torus A", b.name = "torus B";
        s = pair_stream(measured, model, a, b, 0.05, bench::torus_poses(poses, 5), max_lookups);
      } else {
        throw std::invalid_argument("--scenes: unknown scene '" + name + "' (simulate, room, tori)");
      }
      const std::string path = out + "/" + name + ".vec";
      write(path, model, s);
      std::printf("scene %s file %s jobs %zu lookups %llu pairs %llu voxel %.6g shell_words %zu map_words %zu "
                  "frames %llu\n",
                  name.c_str(), path.c_str(), s.jobs.size(), (unsigned long long)s.lookups,
                  (unsigned long long)s.pairs, s.voxel, s.memory.shell.size(), s.memory.map.size(),
                  (unsigned long long)s.frames);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_energy: %s\n", e.what());
    return 1;
  }
  return 0;
}
