#include "voxcd/host/api/devices.h"

#include <stdexcept>

#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/size.h"

namespace voxcd {

DeviceSize size_device(const std::string& scene_file, const SizeOptions& options) {
  const std::string problem = options.clock_mhz != 0 ? clock_problem(options.clock_mhz) : "";
  if (!problem.empty()) throw OptionError({"clock_mhz"}, problem);
  SizeRequest req;
  static_cast<SizeOptions&>(req) = options;
  const RunConfig f = read_scene_file(scene_file);
  const SizeReport r = derive_size(f, make_scene(f), req);
  return DeviceSize{r.config, r.error, r.modelled_rate(), size_text(r), size_json(r)};
}

}  // namespace voxcd
