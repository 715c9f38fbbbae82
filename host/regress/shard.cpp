#include "voxcd/host/regress/shard.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "voxcd/host/device/conform.h"
#include "voxcd/host/regress/stimulus_bins.h"
#include "voxcd/host/regress/testing_fault.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {

namespace {


// Quotes a word for a POSIX shell when it needs it.
std::string shell_word(const std::string& w) {
  if (!w.empty() && w.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789/._-+=:,") ==
                        std::string::npos)
    return w;
  std::string q = "'";
  for (char ch : w) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

}  // namespace

struct ShardVectors::Cached {
  uint64_t seed = 0;
  std::string config;
  int lanes = 0;
  uint64_t jobs = 0;
  uint64_t lookups = 0;
  VectorFile file;
};

ShardVectors::ShardVectors() = default;
ShardVectors::~ShardVectors() = default;

ShardResult run_shard(const Campaign& c, const Shard& s, ShardVectors& cache, const ShardOptions& so) {
  const auto start = std::chrono::steady_clock::now();
  testing_fault("SHARD", s.index);
  auto& k = cache.cached_;
  if (!k || k->seed != s.seed || k->config != s.config || k->lanes != s.lanes || k->jobs != c.jobs_per_shard) {
    k.reset();
    GenerateOptions g;
    g.seed = s.seed;
    g.jobs = c.jobs_per_shard;
    g.aim = c.aim;
    if (!s.config.empty()) g.config = parse_config_pairs(s.config, "configuration");
    g.config.LANES = s.lanes;
    GeneratedFile info;
    const std::string text = generated_vectors_text(g, s.config, &info);
    auto fresh = std::make_unique<ShardVectors::Cached>();
    fresh->file = parse_vectors(text, reproduce_file_name(c, s));
    fresh->seed = s.seed;
    fresh->config = s.config;
    fresh->lanes = s.lanes;
    fresh->jobs = c.jobs_per_shard;
    fresh->lookups = info.lookups;
    k = std::move(fresh);
  }
  ConformOptions opt;
  opt.backend = s.backend;
  opt.lanes = s.lanes;
  opt.cycles = c.cycles;
  opt.threads = so.threads;
  if (s.backend == "rtl") {
    opt.stall = c.stall;
    opt.stall_seed = s.seed;
    if (!so.coverage.empty()) {
      // Campaigns may share the directory: the file names say the campaign (a digest of it) and the shard.
      char digest[17];
      std::snprintf(digest, sizeof digest, "%016llx",
                    static_cast<unsigned long long>(std::hash<std::string>{}(campaign_json(c))));
      const std::string stem = so.coverage + "/" + digest + "-shard-" + std::to_string(s.index);
      opt.coverage = stem + ".dat";
      write_stimulus_bins(stem + ".bins", k->file);
    }
  }
  const ConformResult r = run_vector_file(k->file, opt);
  ShardResult out;
  out.shard = s.index;
  out.jobs = r.jobs;
  out.lookups = k->lookups;
  out.records = r.stream.size();
  out.cycles = c.cycles;
  out.error = r.error;
  out.differs = r.difference.differs;
  out.job = r.difference.job;
  out.tag = r.difference.tag;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::string reproduce_file_name(const Campaign& c, const Shard& s) {
  const size_t ci = size_t(std::find(c.configs.begin(), c.configs.end(), s.config) - c.configs.begin());
  return "regress-" + std::to_string(s.seed) + "-c" + std::to_string(ci) + "-l" + std::to_string(s.lanes) + ".vec";
}

std::string reproduce_command(const Campaign& c, const Shard& s, const std::string& program,
                              const std::string& vec_file) {
  const std::string p = shell_word(program), f = shell_word(vec_file);
  std::string cmd = p + " conform --generate --seed " + std::to_string(s.seed) + " --jobs " +
                    std::to_string(c.jobs_per_shard) + " --lanes " + std::to_string(s.lanes);
  if (!s.config.empty()) cmd += " --config " + shell_word(s.config);
  if (!c.aim.empty()) {
    std::string aim;
    for (const std::string& a : c.aim) aim += (aim.empty() ? "" : ",") + a;
    cmd += " --aim " + shell_word(aim);
  }
  cmd += " -o " + f + " && " + p + " conform " + f + " --backend " + s.backend + " --lanes " +
         std::to_string(s.lanes);
  if (c.cycles) cmd += " --cycles";
  if (c.stall > 0 && s.backend == "rtl") {
    std::ostringstream stall;
    stall << c.stall;
    cmd += " --stall " + stall.str() + " --stall-seed " + std::to_string(s.seed);
  }
  return cmd;
}

}  // namespace voxcd
