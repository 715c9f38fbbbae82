#include "voxcd/host/regress/campaign.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "voxcd/host/detail/cross_product.h"
#include "voxcd/host/detail/text_file.h"
#include "voxcd/host/device/device.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {

namespace {

// Splits on `sep`, trimming spaces; empty items are kept (the caller rejects them).
std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, sep)) {
    const size_t a = item.find_first_not_of(" \t"), b = item.find_last_not_of(" \t");
    out.push_back(a == std::string::npos ? "" : item.substr(a, b - a + 1));
  }
  if (!text.empty() && text.back() == sep) out.push_back("");
  return out;
}

// An unsigned decimal that fits uint64_t, or false.
bool parse_u64(const std::string& s, uint64_t& v) {
  if (s.empty() || s.size() > 20 || s.find_first_not_of("0123456789") != std::string::npos) return false;
  try {
    size_t used = 0;
    v = std::stoull(s, &used);
    return used == s.size();
  } catch (const std::exception&) {
    return false;
  }
}

std::vector<int> parse_lanes(const std::string& text, const std::string& what) {
  std::vector<int> out;
  for (const std::string& item : split(text, ',')) {
    uint64_t v = 0;
    if (!parse_u64(item, v) || v > 1000)
      throw CampaignError(what + ": lane count '" + item + "' is not a number 1..64");
    out.push_back(int(v));
  }
  return out;
}

std::string where_key(const std::string& where, const std::string& key) { return where + ": key \"" + key + "\""; }

}  // namespace

uint64_t Campaign::shards() const {
  return uint64_t(seeds.size()) * configs.size() * lanes.size() * backends.size();
}

Shard shard_at(const Campaign& c, uint64_t index) {
  Shard s;
  s.index = index;
  const auto d = detail::cross_product_digits(index, {c.backends.size(), c.lanes.size(), c.configs.size(), c.seeds.size()});
  s.backend = c.backends[d[0]];
  s.lanes = c.lanes[d[1]];
  s.config = c.configs[d[2]];
  s.seed = c.seeds[d[3]];
  return s;
}

std::string describe(const Shard& s) {
  return "seed " + std::to_string(s.seed) + ", config " + (s.config.empty() ? "default" : "\"" + s.config + "\"") +
         ", lanes " + std::to_string(s.lanes) + ", backend " + s.backend;
}

std::vector<uint64_t> parse_seeds(const std::string& text, const std::string& what) {
  std::vector<uint64_t> out;
  std::set<uint64_t> seen;
  for (const std::string& item : split(text, ',')) {
    const size_t dash = item.find('-');
    uint64_t a = 0, b = 0;
    const bool ok = dash == std::string::npos
                        ? parse_u64(item, a) && (b = a, true)
                        : parse_u64(item.substr(0, dash), a) && parse_u64(item.substr(dash + 1), b);
    if (!ok) throw CampaignError(what + ": '" + item + "' is not a seed or a range of seeds (e.g. 1-16)");
    if (b < a) throw CampaignError(what + ": the range '" + item + "' runs backwards");
    if (b - a >= 100000000) throw CampaignError(what + ": the range '" + item + "' holds more than 10^8 seeds");
    for (uint64_t s = a;; ++s) {
      if (!seen.insert(s).second) throw CampaignError(what + ": seed " + std::to_string(s) + " is given twice");
      out.push_back(s);
      if (s == b) break;
    }
  }
  if (out.empty()) throw CampaignError(what + ": no seeds");
  return out;
}

std::string seeds_text(const std::vector<uint64_t>& seeds) {
  std::string out;
  for (size_t i = 0; i < seeds.size();) {
    size_t j = i;
    while (j + 1 < seeds.size() && seeds[j + 1] == seeds[j] + 1) ++j;
    out += (out.empty() ? "" : ",") + std::to_string(seeds[i]);
    if (j > i) out += "-" + std::to_string(seeds[j]);
    i = j + 1;
  }
  return out;
}

std::string canonical_config(const std::string& text, const std::string& what) {
  std::string spaced = text;
  std::replace(spaced.begin(), spaced.end(), '=', ' ');
  std::istringstream in(spaced);
  std::string word, out;
  while (in >> word) out += (out.empty() ? "" : " ") + word;
  if (out == "default") return "";
  try {
    parse_config_pairs(out, what).validate();
  } catch (const std::exception& e) {
    throw CampaignError(std::string(e.what()));
  }
  return out;
}

void validate_campaign(const Campaign& c, const std::string& where) {
  auto no_repeats = [&](const auto& list, const std::string& key) {
    if (list.empty()) throw CampaignError(where_key(where, key) + ": the list is empty");
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = 0; j < i; ++j)
        if (list[i] == list[j]) {
          std::ostringstream s;
          s << where_key(where, key) << ": ";
          if constexpr (std::is_same_v<std::decay_t<decltype(list[i])>, std::string>)
            s << "'" << (list[i].empty() ? "default" : list[i]) << "'";
          else
            s << list[i];
          s << " is given twice";
          throw CampaignError(s.str());
        }
  };
  no_repeats(c.seeds, "seeds");
  no_repeats(c.configs, "configs");
  no_repeats(c.lanes, "lanes");
  no_repeats(c.backends, "backends");
  for (int l : c.lanes)
    if (l < 1 || l > 64)
      throw CampaignError(where_key(where, "lanes") + ": " + std::to_string(l) + " is not a lane count 1..64");
  const std::vector<BackendStatus> have = backend_status();
  for (const std::string& b : c.backends) {
    const auto it = std::find_if(have.begin(), have.end(), [&](const BackendStatus& s) { return s.name == b; });
    if (it == have.end()) {
      std::string list;
      for (const auto& h : have) list += (list.empty() ? "" : ", ") + h.name;
      throw CampaignError(where_key(where, "backends") + ": backend '" + b + "' is not a backend (the backends: " +
                          list + ")");
    }
    if (!it->ready)
      throw CampaignError(where_key(where, "backends") + ": backend '" + b + "' cannot run here: " + it->why_not);
  }
  for (const std::string& cfg : c.configs)
    if (canonical_config(cfg, where_key(where, "configs")) != cfg)
      throw CampaignError(where_key(where, "configs") + ": '" + cfg + "' is not in NAME VALUE form");
  if (c.jobs_per_shard < 1 || c.jobs_per_shard > 10000000)
    throw CampaignError(where_key(where, "jobs_per_shard") + ": " + std::to_string(c.jobs_per_shard) +
                        " is not 1..10000000");
  if (!(c.stall >= 0 && c.stall < 1))
    throw CampaignError(where_key(where, "stall") + ": " + std::to_string(c.stall) + " is not in [0, 1)");
  if (!c.aim.empty()) no_repeats(c.aim, "aim");  // none: a campaign that aims at nothing
  for (const std::string& a : c.aim)
    if (!aimable_bin(a))
      throw CampaignError(where_key(where, "aim") + ": no template aims at the stimulus bin '" + a +
                          "' (docs/verification.md, \"Coverage-directed stimulus\")");
}

std::vector<std::string> parse_aim(const std::string& text, const std::string& what) {
  std::vector<std::string> out;
  for (const std::string& bin : split(text, ',')) {
    if (bin.empty()) continue;
    if (!aimable_bin(bin))
      throw CampaignError(what + ": no template aims at the stimulus bin '" + bin + "' (docs/verification.md)");
    out.push_back(bin);
  }
  return out;
}

Campaign campaign_from_lists(const std::string& seeds, const std::string& configs, const std::string& lanes,
                             const std::string& backends, uint64_t jobs_per_shard, bool cycles) {
  Campaign c;
  c.seeds = parse_seeds(seeds, "--seeds");
  c.configs.clear();
  for (const std::string& cfg : split(configs, ';')) c.configs.push_back(canonical_config(cfg, "--configs"));
  c.lanes = parse_lanes(lanes, "--lanes");
  c.backends = split(backends, ',');
  c.jobs_per_shard = jobs_per_shard;
  c.cycles = cycles;
  validate_campaign(c, "the command line");
  return c;
}

std::string campaign_json(const Campaign& c) {
  nlohmann::ordered_json j;
  j["seeds"] = seeds_text(c.seeds);
  j["configs"] = nlohmann::json::array();
  for (const std::string& cfg : c.configs) j["configs"].push_back(cfg.empty() ? "default" : cfg);
  j["lanes"] = c.lanes;
  j["backends"] = c.backends;
  j["jobs_per_shard"] = c.jobs_per_shard;
  j["cycles"] = c.cycles;
  if (!c.aim.empty()) j["aim"] = c.aim;  // only when used: other campaigns keep their text (results files)
  if (c.stall > 0) j["stall"] = c.stall;
  return j.dump();
}

namespace {

// The key "seeds": a string such as "1-16,20" or an array of seeds.
std::vector<uint64_t> json_seeds(const nlohmann::json& seeds, const std::string& where) {
  if (seeds.is_string()) return parse_seeds(seeds.get<std::string>(), where_key(where, "seeds"));
  if (!seeds.is_array())
    throw CampaignError(where_key(where, "seeds") + ": expected a string such as \"1-16\" or an array of seeds");
  std::string list;
  for (const auto& s : seeds) {
    if (!s.is_number_unsigned()) throw CampaignError(where_key(where, "seeds") + ": " + s.dump() + " is not a seed");
    list += (list.empty() ? "" : ",") + std::to_string(s.get<uint64_t>());
  }
  return parse_seeds(list, where_key(where, "seeds"));
}

// j[key], when present, as an array of strings into out.
void json_strings(const nlohmann::json& j, const std::string& key, const std::string& where,
                  std::vector<std::string>& out) {
  if (!j.contains(key)) return;
  const auto& v = j[key];
  if (!v.is_array()) throw CampaignError(where_key(where, key) + ": expected an array of strings");
  out.clear();
  for (const auto& s : v) {
    if (!s.is_string()) throw CampaignError(where_key(where, key) + ": " + s.dump() + " is not a string");
    out.push_back(s.get<std::string>());
  }
}

// The keys with a number or a flag: lanes, jobs_per_shard, cycles.
void json_counts(const nlohmann::json& j, const std::string& where, Campaign& c) {
  if (j.contains("lanes")) {
    const auto& v = j["lanes"];
    if (!v.is_array()) throw CampaignError(where_key(where, "lanes") + ": expected an array of lane counts");
    c.lanes.clear();
    for (const auto& l : v) {
      if (!l.is_number_integer())
        throw CampaignError(where_key(where, "lanes") + ": " + l.dump() + " is not a lane count");
      c.lanes.push_back(l.get<int>());
    }
  }
  if (j.contains("jobs_per_shard")) {
    const auto& v = j["jobs_per_shard"];
    if (!v.is_number_unsigned())
      throw CampaignError(where_key(where, "jobs_per_shard") + ": expected a positive integer");
    c.jobs_per_shard = v.get<uint64_t>();
  }
  if (j.contains("cycles")) {
    if (!j["cycles"].is_boolean()) throw CampaignError(where_key(where, "cycles") + ": expected true or false");
    c.cycles = j["cycles"].get<bool>();
  }
}

}  // namespace

Campaign campaign_from_json(const std::string& text, const std::string& where) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw CampaignError(where + ": not JSON: " + e.what());
  }
  if (!j.is_object()) throw CampaignError(where + ": not a JSON object");
  static const std::set<std::string> known = {"seeds",          "configs", "lanes", "backends",
                                              "jobs_per_shard", "cycles",  "aim",   "stall"};
  for (const auto& [key, value] : j.items())
    if (!known.count(key))
      throw CampaignError(where + ": unknown key \"" + key +
                          "\" (the keys: seeds, configs, lanes, backends, jobs_per_shard, cycles, aim, stall)");
  if (!j.contains("seeds")) throw CampaignError(where + ": the key \"seeds\" is missing");
  Campaign c;
  c.seeds = json_seeds(j["seeds"], where);
  json_strings(j, "configs", where, c.configs);
  for (std::string& cfg : c.configs) cfg = canonical_config(cfg, where_key(where, "configs"));
  json_strings(j, "backends", where, c.backends);
  json_counts(j, where, c);
  json_strings(j, "aim", where, c.aim);
  if (j.contains("stall")) {
    if (!j["stall"].is_number()) throw CampaignError(where_key(where, "stall") + ": expected a number in [0, 1)");
    c.stall = j["stall"].get<double>();
  }
  validate_campaign(c, where);
  return c;
}

Campaign read_campaign_file(const std::string& path) {
  const std::optional<std::string> text = detail::read_text_file(path);
  if (!text) throw CampaignError(path + ": cannot open the campaign file");
  return campaign_from_json(*text, path);
}

}  // namespace voxcd
