// A conformance campaign (`voxcd regress`, docs/regress.md): seeds x configurations x lane counts x backends, one
// shard per combination; from command-line lists or a campaign file (JSON).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/error.h"

namespace voxcd {

// A campaign that cannot be run as given; the message names the option or file, the key and the problem.
struct CampaignError : Error {
  using Error::Error;
};

struct Campaign {
  std::vector<uint64_t> seeds;
  std::vector<std::string> configs = {""};  // NAME VALUE pairs, single-spaced; "" = the default configuration
  std::vector<int> lanes = {4};
  std::vector<std::string> backends = {"cpu"};
  uint64_t jobs_per_shard = 200;
  bool cycles = false;  // also compare the cycles of every completion record
  // Stimulus bins the shards' vectors aim at (GenerateOptions::aim; coverage-directed stimulus, docs/verification.md);
  // none: the random vectors of before.
  std::vector<std::string> aim;
  // rtl: random back-pressure, the probability that each output stream's consumer is not ready in a cycle (seeded by
  // the shard's seed; cycles are then compared net of stalls); 0: none.
  double stall = 0.0;

  uint64_t shards() const;
};

// One shard: the vectors of (seed, config, lanes) run on one backend. Shard index i counts backends fastest, then
// lanes, configurations and seeds.
struct Shard {
  uint64_t index = 0;
  uint64_t seed = 0;
  std::string config;
  int lanes = 0;
  std::string backend;
};

// The shard at `index` (< c.shards()).
Shard shard_at(const Campaign& c, uint64_t index);
// "seed 3, config \"SB 8 WB 8\", lanes 4, backend cpu" (config default for "").
std::string describe(const Shard& s);

// Seeds from "1-16", "1,5,9" or "1-4,10"; CampaignError naming `what` for a malformed list, a reversed range or a
// seed given twice.
std::vector<uint64_t> parse_seeds(const std::string& text, const std::string& what);
// The shortest range text of seeds ("1-4,10"), in their order.
std::string seeds_text(const std::vector<uint64_t>& seeds);
// Stimulus bins from "face.x.n,job.tag.top" (empty items skipped); CampaignError naming `what` for a bin no template
// aims at (aimable_bin of ref/vector_gen.h).
std::vector<std::string> parse_aim(const std::string& text, const std::string& what);
// A configuration as given ("default", "SB 8 WB 8", "SB=8 WB=8") in its single-spaced NAME VALUE form ("" for
// the defaults); CampaignError naming `what` when it is not a valid configuration.
std::string canonical_config(const std::string& text, const std::string& what);

// A campaign from the command line's lists: seeds as parse_seeds; configurations separated by ';'; lanes and
// backends separated by ','. Validated as validate_campaign.
Campaign campaign_from_lists(const std::string& seeds, const std::string& configs, const std::string& lanes,
                             const std::string& backends, uint64_t jobs_per_shard, bool cycles);
// A campaign file (docs/regress.md, "Campaign file"); CampaignError naming the file, the key and the problem.
Campaign read_campaign_file(const std::string& path);
// The campaign as one line of JSON, every key present but "aim" and "stall", which only a campaign that uses them has
// (the results file's header, the message to other ranks).
std::string campaign_json(const Campaign& c);
// Parses campaign_json's form, or a campaign file's text; CampaignError starting with `where`.
Campaign campaign_from_json(const std::string& text, const std::string& where);
// Checks every list is non-empty and free of repeats, every lane count 1..64, every backend in this build, every
// configuration valid and jobs_per_shard 1..10^7; CampaignError starting with `where`.
void validate_campaign(const Campaign& c, const std::string& where);

}  // namespace voxcd
