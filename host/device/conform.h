// Conformance vector files on a backend (`voxcd conform`, docs/conformance.md): run a file and compare the backend's
// stream with its expectations, or write a file of generated vectors with expectations from ref/.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"
#include "voxcd/ref/vector_gen.h"
#include "voxcd/ref/vectors.h"

namespace voxcd {

struct ConformOptions {
  std::string backend = "ref";
  std::optional<int> lanes;  // the device's LANES instead of the file's
  std::optional<int> banks;  // the device's BANKS instead of the file's (0: a voxmap copy per lane)
  std::optional<int> depth;  // the device's pipeline depth instead of the file's DEPTH (0 when it names none)
  bool cycles = false;       // also compare the cycles of every completion record
  std::string trace;         // rtl: write an FST waveform here ("" = none)
  unsigned threads = 0;      // cpu: worker threads (0 = one per hardware thread)
  // rtl: the probability that each output stream's consumer is not ready in a cycle (random back-pressure, seeded
  // by stall_seed); completion records then carry cycles = the file's cycles + their stalls (docs/contract.md),
  // which is what --cycles compares.
  double stall = 0.0;
  uint64_t stall_seed = 1;
  std::string coverage;      // rtl: run on the coverage models and write their counts here (docs/verification.md)
};

struct ConformResult {
  std::string file;
  // "" when the backend's stream equals the file's; else why not, starting with the file: a malformed file (its
  // line), a backend that cannot run it, or the first difference (the job, the point, expected and got).
  std::string error;
  size_t jobs = 0;             // in the file
  size_t expected = 0;         // hit and done records the file expects
  int version = 1;             // the file's format version (2: hit records carry DIST)
  std::vector<Record> stream;  // the backend's output, in order
  StreamDifference difference; // the first difference, when the streams were compared and differ
  bool ok() const { return error.empty(); }
};

// Runs a vector file on a fresh device of the file's configuration (opt.lanes, banks and depth overriding LANES,
// BANKS and DEPTH; with opt.cycles a file naming other LANES, or of other BANKS or DEPTH, is refused, as is a
// backend that does not model cycles). With compare false the stream is
// only produced (`voxcd conform --print`). Never throws for the file or the backend: the reason is in `error`.
ConformResult run_conformance(const std::string& path, const ConformOptions& opt, bool compare = true);
// The same for a file already parsed (`file.path` names it in messages).
ConformResult run_vector_file(const VectorFile& file, const ConformOptions& opt, bool compare = true);

// What write_generated_vectors wrote.
struct GeneratedFile {
  size_t jobs = 0, shell_words = 0, map_words = 0, lookups = 0;
  DeviceConfig config;
};

// generate_vectors(g) with the stream ref/ gives for them (and its timing model's cycles) as the text of a vector
// file, after a comment naming the seed, jobs, LANES and `config_text`: the bytes write_generated_vectors writes.
std::string generated_vectors_text(const GenerateOptions& g, const std::string& config_text = "",
                                   GeneratedFile* info = nullptr);

// generate_vectors(g) with the stream ref/ gives for them (and its timing model's cycles), written to `path` through
// a temporary file renamed into place, after a comment naming the seed, jobs, LANES and `config_text` (the
// configuration as given, "" = the defaults). std::runtime_error naming the file when it cannot be written whole
// (nothing is left behind).
GeneratedFile write_generated_vectors(const std::string& path, const GenerateOptions& g,
                                      const std::string& config_text = "");

}  // namespace voxcd
