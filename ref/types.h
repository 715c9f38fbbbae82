// The device's records: shell words, jobs, and the output stream (hit and completion records).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace voxcd {

enum class Mode : uint8_t { All = 0, First = 1, Count = 2 };
enum VoxelState : uint8_t { kEmpty = 0, kSurface = 1, kInterior = 2, kReserved = 3 };

// Default hit mask: surface | interior.
constexpr uint8_t kDefaultHitMask = (1u << kSurface) | (1u << kInterior);

const char* mode_name(Mode m);                   // "ALL", "FIRST", "COUNT"
std::optional<Mode> parse_mode(const std::string& s);

// One shell memory word: a point in the shell object's voxel units, PW-bit signed with PF fraction bits.
struct ShellWord {
  int64_t x = 0, y = 0, z = 0;
  int64_t operator[](int i) const { return i == 0 ? x : i == 1 ? y : z; }
  bool operator==(const ShellWord& o) const { return x == o.x && y == o.y && z == o.z; }
};

// Job::sparse bits: the map is sparse (a table of cells and bricks), the shell is sparse (shell bricks).
constexpr uint8_t kSparseMap = 1, kSparseShell = 2;

// One job: test shell words [shell_base, shell_base + shell_count) against the map at map_base.
struct Job {
  uint32_t tag = 0;
  Mode mode = Mode::All;
  uint8_t hit_mask = kDefaultHitMask;  // bit s set: state s is a hit
  uint32_t shell_base = 0;
  uint32_t shell_count = 0;
  uint32_t map_base = 0;
  uint32_t nx = 1, ny = 1, nz = 1;
  int64_t M[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // MW-bit signed, MF fraction bits
  int64_t t[3] = {0, 0, 0};                             // TW-bit signed, TF = MF + PF fraction bits
  int64_t threshold = 0;  // distance voxmaps: hit when the interpolated distance D <= threshold (IW-bit signed)
  // Sparse devices (DeviceConfig::BL > 0): kSparseMap, kSparseShell; a sparse map's bricks lie from word brick_base,
  // brick_units units of brick memory (ref/sparse.h); both 0 for a dense map.
  uint8_t sparse = 0;
  uint32_t brick_base = 0;
  uint32_t brick_units = 0;

  uint64_t voxels() const { return uint64_t{nx} * ny * nz; }
  bool sparse_map() const { return sparse & kSparseMap; }
  bool sparse_shell() const { return sparse & kSparseShell; }
};

// One record of the output stream. Hits of a job come in ascending point order, then its completion record;
// jobs in submission order.
struct Record {
  enum Kind : uint8_t { Hit, Done } kind = Hit;
  uint32_t tag = 0;
  // Hit: point index relative to shell_base, voxel coordinates and the voxel's state.
  uint32_t point = 0;
  uint32_t x = 0, y = 0, z = 0;
  uint8_t state = 0;   // 0 on a distance voxmap
  int64_t dist = 0;    // the interpolated distance D on a distance voxmap (IW-bit signed), 0 on a 2-bit voxmap
  // Done: number of hits (FIRST: 0 or 1), and the job's cycles where the backend models time.
  uint32_t hits = 0;
  std::optional<uint64_t> cycles;
  // Done, informative only (never compared): points looked up and cycles lost to output back-pressure.
  std::optional<uint64_t> points;
  std::optional<uint64_t> stalls;

  static Record hit(uint32_t tag, uint32_t point, uint32_t x, uint32_t y, uint32_t z, uint8_t state,
                    int64_t dist = 0);
  static Record done(uint32_t tag, uint32_t hits, std::optional<uint64_t> cycles = std::nullopt);
  // Equal as the contract compares them: every field of a hit; tag and hits of a done, plus cycles if asked.
  bool same_as(const Record& o, bool compare_cycles) const;
  // "hit TAG POINT X Y Z STATE" or "done TAG HITS [CYCLES]", the vector file syntax of version 1; with_dist
  // appends the hit's DIST (version 2).
  std::string to_string(bool with_dist = false) const;
};

// The memories as the host loads them through the write port.
struct DeviceMemory {
  std::vector<ShellWord> shell;  // word k = shell address k
  std::vector<uint64_t> map;     // word k = voxmap address k, MEMW bits used
};

}  // namespace voxcd
