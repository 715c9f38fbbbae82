// mutation_models: prints the configurations the rtl backend's module offers, family by family, as the tests see
// them ("family|pairs" lines, each configuration as the list CONFIGS writes it when it is one of the list's, else
// in full), so that bench/mutation/run.py can check that a mutant module offers the tests every configuration
// of its list and no other.
//   mutation_models CONFIGS   (VOXCD_RTL_MODULE names the module)
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "voxcd/host/device/detail/rtl.h"
#include "voxcd/ref/vectors.h"

int main(int argc, char** argv) {
  using namespace voxcd;
  if (argc != 2) {
    std::cerr << "usage: mutation_models CONFIGS\n";
    return 2;
  }
  if (!rtl_unavailable().empty()) {
    std::cerr << rtl_unavailable() << "\n";
    return 1;
  }
  // The list's configurations: each is printed as the list names it.
  std::vector<std::pair<DeviceConfig, std::string>> listed;
  std::ifstream in(argv[1]);
  for (std::string line; std::getline(in, line);) {
    const auto bar = line.find('|');
    if (line.empty() || line[0] == '#' || bar == std::string::npos || line.substr(0, bar) == "axi") continue;
    const std::string pairs = line.substr(bar + 1);
    listed.emplace_back(parse_config_pairs(pairs, argv[1]), pairs);
  }
  auto name = [&](const DeviceConfig& c) {
    for (const auto& [cfg, pairs] : listed)
      if (cfg == c) return pairs;
    return c.to_string();
  };
  for (int lanes : rtl_lanes()) {
    DeviceConfig c;
    c.LANES = lanes;
    std::cout << "lanes|" << name(c) << "\n";
  }
  const std::pair<const char*, std::vector<DeviceConfig>> families[] = {
      {"derived", rtl_configs()},  {"distance", rtl_distance_configs()}, {"banked", rtl_banked_configs()},
      {"depth", rtl_depth_configs()}, {"sparse", rtl_sparse_configs()},  {"wide", rtl_wide_configs()}};
  for (const auto& [family, cfgs] : families)
    for (const DeviceConfig& c : cfgs) std::cout << family << "|" << name(c) << "\n";
  return 0;
}
