// The testing aids of the test build's tool (build/voxcd_testing; docs/regress.md, docs/sweep.md and docs/scale.md,
// "Testing aids"): environment variables that plant a difference in a device or make a rank fail, hang or exit, read
// here and set as the library's hooks before main runs. The shipped library and tool have none of this.
//   VOXCD_TESTING_PLANT=BACKEND:LANES:SEED     a device's first record differs on seed SEED's generated jobs
//   VOXCD_TESTING_FAULT=KIND:SHARD             the rank that runs shard SHARD fails, hangs or exits
//   VOXCD_TESTING_SWEEP_FAULT=KIND:POINT       the rank that runs sweep point POINT fails, hangs or exits
//   VOXCD_TESTING_FRAME_FAULT=KIND:RANK:FRAME  rank RANK fails, hangs or exits at frame FRAME
#include <chrono>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "voxcd/host/device/detail/planted.h"
#include "voxcd/host/mpi/frame_exchange.h"
#include "voxcd/host/regress/testing_fault.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {
namespace {

constexpr const char* kPlantVariable = "VOXCD_TESTING_PLANT";

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

// A device whose first record differs (a hit's x plus one, or a done's hits plus one) on seed's generated jobs.
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

std::unique_ptr<Device> plant(std::unique_ptr<Device> dev, const std::string& backend) {
  const char* text = std::getenv(kPlantVariable);
  if (!text || !*text) return dev;
  const Plant p = parse_plant(text);
  if (p.backend != backend || p.lanes != dev->config().LANES) return dev;
  return std::make_unique<PlantedDevice>(std::move(dev), p.seed);
}

[[noreturn]] void hang() {
  for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
}

// The variable of `unit` (SHARD: VOXCD_TESTING_FAULT, POINT: VOXCD_TESTING_SWEEP_FAULT) = KIND:ITEM: when ITEM is
// `item`, "fail" throws std::runtime_error, "hang" never returns, "exit" ends the process with code 3. A value not of
// that form throws std::runtime_error naming the variable and the form.
void fault(const std::string& unit, uint64_t item) {
  const std::string variable = unit == "POINT" ? "VOXCD_TESTING_SWEEP_FAULT" : "VOXCD_TESTING_FAULT";
  const char* text = std::getenv(variable.c_str());
  if (!text || !*text) return;
  const std::string t = text;
  const size_t colon = t.find(':');
  const std::string kind = t.substr(0, colon);
  uint64_t at = 0;
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no item");
    size_t used = 0;
    at = std::stoull(t.substr(colon + 1), &used);
    if (used != t.size() - colon - 1 || (kind != "fail" && kind != "hang" && kind != "exit"))
      throw std::invalid_argument("bad");
  } catch (const std::exception&) {
    throw std::runtime_error(variable + " is '" + t + "', expected fail:" + unit + ", hang:" + unit + " or exit:" + unit);
  }
  if (at != item) return;
  if (kind == "fail") throw std::runtime_error("planted fault (" + variable + "=" + t + ")");
  if (kind == "exit") std::_Exit(3);
  hang();
}

// VOXCD_TESTING_FRAME_FAULT=KIND:RANK:FRAME: rank RANK, at frame FRAME, fails (throws), exits at once, or hangs
// instead of exchanging.
void frame_fault(int rank, uint64_t frame) {
  const char* text = std::getenv("VOXCD_TESTING_FRAME_FAULT");
  if (!text || !*text) return;
  const std::string t = text;
  const size_t c1 = t.find(':'), c2 = c1 == std::string::npos ? c1 : t.find(':', c1 + 1);
  const std::string kind = t.substr(0, c1);
  int r = -1;
  uint64_t f = 0;
  try {
    if (c2 == std::string::npos || (kind != "fail" && kind != "hang" && kind != "exit"))
      throw std::invalid_argument("bad");
    size_t used = 0;
    r = std::stoi(t.substr(c1 + 1, c2 - c1 - 1), &used);
    if (used != c2 - c1 - 1) throw std::invalid_argument("bad");
    f = std::stoull(t.substr(c2 + 1), &used);
    if (used != t.size() - c2 - 1) throw std::invalid_argument("bad");
  } catch (const std::exception&) {
    throw std::runtime_error("VOXCD_TESTING_FRAME_FAULT is '" + t + "', expected fail|hang|exit:RANK:FRAME");
  }
  if (r != rank || f != frame) return;
  if (kind == "fail") throw std::runtime_error("planted fault (VOXCD_TESTING_FRAME_FAULT=" + t + ")");
  if (kind == "exit") std::_Exit(3);
  hang();
}

// Sets the hooks before main.
const bool installed = [] {
  set_device_testing_hook(&plant);
  set_fault_testing_hook(&fault);
  mpi::set_frame_fault_testing_hook(&frame_fault);
  return true;
}();

}  // namespace
}  // namespace voxcd
