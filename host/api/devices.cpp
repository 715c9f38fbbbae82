#include "voxcd/host/api/devices.h"

#include <stdexcept>

#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/size.h"

namespace voxcd {

DeviceSize size_device(const std::string& scene_file, const SizeOptions& options) {
  SizeRequest req;
  req.accuracy = options.accuracy;
  req.contact_accuracy = options.contact_accuracy;
  req.rate = options.rate;
  req.frames = options.frames;
  req.cost = options.cost;
  if (options.clock_mhz != 0) {
    const std::string problem = clock_problem(options.clock_mhz);
    if (!problem.empty()) throw std::invalid_argument("clock_mhz: " + problem);
    req.clock = given_clock(options.clock_mhz, "SizeOptions::clock_mhz");
  }
  const RunConfig f = read_scene_file(scene_file);
  const Scene scene = make_scene(f);
  const SizeReport r = derive_size(f, scene, req);
  DeviceSize d;
  d.config = r.config;
  d.error = r.error;
  d.frame_rate = r.modelled_rate();
  d.text = size_text(r);
  d.json = size_json(r);
  return d;
}

}  // namespace voxcd
