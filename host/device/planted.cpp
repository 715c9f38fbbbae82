// The planted difference of VOXCD_TESTING_PLANT (detail/planted.h): a device that flips one record of one
// generated stream.
#include "voxcd/host/device/detail/planted.h"

#include <cstdlib>
#include <sstream>

#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {

namespace {

struct Plant {
  std::string backend;
  int lanes = 0;
  uint64_t seed = 0;
};

// Parses "BACKEND:LANES:SEED"; DeviceError naming the variable and what is wrong.
Plant parse_plant(const std::string& text) {
  const size_t a = text.find(':'), b = a == std::string::npos ? a : text.find(':', a + 1);
  Plant p;
  bool ok = a != std::string::npos && b != std::string::npos && a > 0;
  if (ok) {
    p.backend = text.substr(0, a);
    std::istringstream l(text.substr(a + 1, b - a - 1)), s(text.substr(b + 1));
    ok = (l >> p.lanes) && l.eof() && (s >> p.seed) && s.eof() && p.lanes > 0;
  }
  if (!ok)
    throw DeviceError(std::string(kPlantVariable) + " is '" + text + "', expected BACKEND:LANES:SEED (e.g. cpu:4:3)");
  return p;
}

// True when `jobs` are the ones generated for seed on cfg (same count, same lines).
bool generated_for(const DeviceConfig& cfg, uint64_t seed, const std::vector<Job>& jobs) {
  GenerateOptions g;
  g.seed = seed;
  g.jobs = jobs.size();
  g.config = cfg;
  const GeneratedVectors v = generate_vectors(g);
  if (v.jobs.size() != jobs.size()) return false;
  for (size_t i = 0; i < jobs.size(); ++i)
    if (job_line(v.jobs[i], 2) != job_line(jobs[i], 2)) return false;
  return true;
}

class PlantedDevice final : public Device {
 public:
  PlantedDevice(std::unique_ptr<Device> dev, uint64_t seed) : dev_(std::move(dev)), seed_(seed) {}
  std::string name() const override { return dev_->name(); }
  const DeviceConfig& config() const override { return dev_->config(); }
  bool models_cycles() const override { return dev_->models_cycles(); }
  void load(const DeviceMemory& mem) override { dev_->load(mem); }
  std::vector<Record> run(const std::vector<Job>& jobs) override {
    std::vector<Record> out = dev_->run(jobs);
    if (!out.empty() && generated_for(dev_->config(), seed_, jobs)) {
      Record& r = out.front();
      if (r.kind == Record::Hit) ++r.x;
      else ++r.hits;
    }
    return out;
  }

 private:
  std::unique_ptr<Device> dev_;
  uint64_t seed_;
};

}  // namespace

std::unique_ptr<Device> plant_from_environment(std::unique_ptr<Device> dev, const std::string& backend) {
  const char* text = std::getenv(kPlantVariable);
  if (!text || !*text) return dev;
  const Plant p = parse_plant(text);
  if (p.backend != backend || p.lanes != dev->config().LANES) return dev;
  return std::make_unique<PlantedDevice>(std::move(dev), p.seed);
}

}  // namespace voxcd
