// Conformance vector files (docs/conformance.md is the normative description):
//   voxcd-vectors 1 | 2 | 3
//   config PW 24 PF 8 MW 18 MF 16 TW 48 DW 10 MEMW 64 [LANES 4] [SAW 16] [MAW 18] [TAGW 16] [BANKS 4] [DEPTH 2]
//          [SB 8 WB 8 (v2)] [BL 3 (v3)]
//   shell N      then N lines "x y z"
//   map N        then N lines of one hex word
//   job TAG MODE MASK SHELL_BASE SHELL_COUNT MAP_BASE NX NY NZ M00 .. M22 T0 T1 T2 [THRESHOLD (v2)]
//       [SPARSE BRICK_BASE BRICK_UNITS (v3)]
//   hit TAG POINT X Y Z STATE [DIST (v2)]
//   done TAG HITS [CYCLES]
#pragma once

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "voxcd/ref/error.h"
#include "voxcd/ref/config.h"
#include "voxcd/ref/types.h"

namespace voxcd {

struct VectorFile {
  std::string path;
  int version = 1;  // the header's format version
  DeviceConfig config;
  bool has_lanes = false;  // the config line named LANES
  bool has_banks = false;  // the config line named BANKS
  bool has_depth = false;  // the config line named DEPTH (absent: 0, the depth of every file before it existed)
  DeviceMemory memory;
  std::vector<Job> jobs;
  std::vector<int> job_lines;
  std::vector<Record> expected;  // hit and done records in stream order
  std::vector<int> expected_lines;
};

// Parses a whole file. Throws VectorError naming the file, the line and what is wrong: an unknown record, a
// missing or extra field, a number that does not parse or does not fit its format under the file's config, a
// section shorter than its count, a job that reads memory the file does not load.
VectorFile parse_vectors(const std::string& text, const std::string& name);
VectorFile read_vectors(const std::string& path);

// Parses "NAME VALUE ..." pairs as a config line would have them (defaults for names not given). Throws
// VectorError naming `what` and the problem.
DeviceConfig parse_config_pairs(const std::string& pairs, const std::string& what);

// The format version a file of cfg is written in: 1 for a 2-bit device (the files of version 1 stay byte for
// byte what they were), 2 for a distance device, 3 for a sparse device (BL > 0).
int vector_version(const DeviceConfig& cfg);

// Writes config, memories, then each job followed by its records from `records` (a stream as run_stream gives;
// its done records split it into jobs). Done records carry CYCLES when the record has them.
void write_vectors(std::ostream& os, const DeviceConfig& cfg, bool write_lanes, const DeviceMemory& mem,
                   const std::vector<Job>& jobs, const std::vector<Record>& records);
// One job line in the file syntax of `version` (2 adds THRESHOLD).
std::string job_line(const Job& job, int version = 1);

// Where a backend's stream first departs from a file's expectations.
struct StreamDifference {
  bool differs = false;
  size_t job = 0;       // index of the job the first differing record belongs to (jobs.size(): after the last)
  uint32_t tag = 0;     // that job's tag (0 after the last job)
  size_t record = 0;    // index of the first differing record in the stream
  std::string message;  // as compare_streams returns it
};

// The first difference between a backend's stream and the file's expectations (differs false when equal).
StreamDifference first_difference(const VectorFile& file, const std::vector<Record>& got, bool compare_cycles);
// Compares a backend's stream with the file's expectations. Returns "" when equal, else the first difference:
// the job (tag and line), the point, what was expected and what came.
std::string compare_streams(const VectorFile& file, const std::vector<Record>& got, bool compare_cycles);

}  // namespace voxcd
