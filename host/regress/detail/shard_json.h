// Internal to host/regress (results_file.cpp, report.cpp): the keys that name a shard in JSON.
#pragma once

#include <nlohmann/json.hpp>

#include "voxcd/host/regress/campaign.h"

namespace voxcd::detail {

// A JSON object that starts with shard s's number, seed, configuration ("default" for none), lanes and backend.
inline nlohmann::ordered_json shard_json(const Shard& s) {
  nlohmann::ordered_json j;
  j["shard"] = s.index;
  j["seed"] = s.seed;
  j["config"] = s.config.empty() ? "default" : s.config;
  j["lanes"] = s.lanes;
  j["backend"] = s.backend;
  return j;
}

}  // namespace voxcd::detail
