// A design-space sweep of a scene file (`voxcd sweep`, docs/sweep.md): the cross product of lane counts, pipeline
// depths, voxel scales, distance bits and accuracies, each point derived and measured with the sizing steps of size.h and
// contact_measure.h: widths, memories, predicted and measured contact error, cycles per frame, memory and cost.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "voxcd/host/mesh/mesh.h"
#include "voxcd/host/scene/scene.h"
#include "voxcd/host/scene/scene_file.h"
#include "voxcd/host/sizing/size.h"
#include "voxcd/ref/error.h"

namespace voxcd {

// A sweep that cannot be used: the message starts with where (the sweep file or the option) and the key at fault.
struct SweepError : Error {
  using Error::Error;
};

struct SweepSpec {
  std::string scene;                  // the scene file
  std::vector<int> lanes;             // powers of two, 1 to 64
  std::vector<int> depths = {0};      // pipeline depths the device offers (depth.h); a results file without: {0}
  std::vector<double> voxel_scales;   // factors on every type's voxel, > 0
  std::vector<int> distance_bits;     // 0 (2-bit states), 4, 8 or 16 (distance voxmaps with the scene's band)
  std::vector<double> accuracies;     // the fixed-point path's accuracy, world units, > 0
  uint64_t frames = 0;                // frames measured per point (0: the scene file's)
  uint64_t sample_frames = 4;         // of those, frames whose contacts are checked against the meshes
  // MHz, given by --clock, the sweep file's "clock" or the scene file's; 0: each point at its own configuration's
  // clock (clock_for: measured for it, or an estimate that says so; SweepRow::clock_*).
  double clock = 0;
  // Where clock comes from (DeviceClock::source): "given by --clock", "given by <sweep file>'s \"clock\"" or
  // "given by <scene file>'s \"clock\""; "" with clock 0.
  std::string clock_source;
  bool cost = false;                  // yosys per point
  std::string rtl_dir;                // the RTL for cost ("" = the package's)
  uint64_t points() const {
    return lanes.size() * depths.size() * voxel_scales.size() * distance_bits.size() * accuracies.size();
  }
};

// One design point: the index-th of the cross product, lanes outermost, then depth, accuracy innermost.
struct SweepPoint {
  uint64_t index = 0;
  int lanes = 1;
  int depth = 0;
  double voxel_scale = 1;
  int distance_bits = 0;
  double accuracy = 0;
  std::string text() const;  // "lanes 2, depth 1, voxel x0.5, distance bits 8, accuracy 0.01"
};
SweepPoint point_at(const SweepSpec& s, uint64_t index);

// A comma-separated list of numbers ("1,2,4"); SweepError naming `what` and the item that is not a number.
std::vector<double> parse_number_list(const std::string& text, const std::string& what);

// Checks every list and value (SweepError naming `where` and the key): lists not empty, lanes powers of two up to
// 64, depths the device offers, distance bits 0, 4, 8 or 16, scales and accuracies positive and finite, sample_frames <= frames.
void check_sweep(const SweepSpec& s, const std::string& where);

// The sweep file (docs/sweep.md): a JSON object with the lists "lanes", "depth", "voxel_scale", "distance_bits",
// "accuracy" and the numbers "frames", "sample_frames", "clock" and the flag "cost"; the scene comes from the
// command line. Keys it leaves out keep their value in `base`. SweepError naming the file and the key for malformed
// JSON, an unknown key, a wrong type or a value out of range.
SweepSpec parse_sweep_file(const std::string& text, const std::string& where, SweepSpec base);
SweepSpec read_sweep_file(const std::string& path, SweepSpec base);

// The sweep as canonical JSON (the results file's header and what rank 0 sends the other ranks), and back.
std::string sweep_json(const SweepSpec& s);
SweepSpec sweep_from_json(const std::string& text, const std::string& where);

// One point's row of the table. Everything but rank and seconds is the same on every run of the point.
struct SweepRow {
  SweepPoint point;
  std::string status = "ok";  // or "infeasible: " and the constraint that no device of the point meets
  std::string config;         // DeviceConfig::to_string
  double error_bound = 0;     // the fixed-point path's, world units (size_error_bound)
  double contact_bound = 0;   // how far outside the other surface a contact can lie, world units (contact_error_bound)
  double contact_measured = 0;  // the farthest checked contact lies outside the other mesh, world units (>= 0)
  uint64_t contacts_checked = 0;
  // Distance voxmaps: the contacts in or next to conservative cells (a surface the nodes do not resolve), checked
  // apart against the 2-bit voxmap's bound (docs/pairs.md), world units; all 0 on a 2-bit row.
  uint64_t contacts_conservative = 0;
  double contact_measured_conservative = 0, contact_bound_conservative = 0;
  int latency = 0;            // cycles from a job's acceptance to its first record (latency_cycles, depth.h)
  uint64_t max_cycles = 0;    // device cycles of the largest frame
  double mean_cycles = 0;
  double rate = 0;            // frames per second at the row's clock for the largest frame
  // The row's clock: the sweep's when it gives one, else its configuration's (clock_for). Rows of results files made
  // before rows had their own clock have none (clock_mhz 0): the sweep's clock is theirs.
  double clock_mhz = 0;
  std::string clock_source;
  bool clock_estimate = false;
  uint64_t shell_bits = 0, map_bits = 0;
  std::optional<YosysCost> cost;
  bool pareto = false;        // set by the table (sweep_table.h)
  int rank = 0;               // timing: where and how long, not part of the table
  double seconds = 0;
  bool ok() const { return status == "ok"; }
  uint64_t memory_bits() const { return shell_bits + map_bits; }
};

// A row as one line of JSON (no newline): the results file's line and the message between ranks; and back
// (SweepError starting with `where` for a malformed line).
std::string sweep_row_line(const SweepRow& r);
SweepRow parse_sweep_row(const std::string& line, const std::string& where);

// Runs points of a sweep, keeping what points share (the scene file, each voxel scale's and distance bits' scene,
// the types' meshes and convexity) between them.
class SweepRunner {
 public:
  // Reads the scene file and makes its scene (SceneFileError, MeshError).
  explicit SweepRunner(const SweepSpec& s);
  // The point's row. A point no device meets (SizeError) or whose voxels the scene file cannot take
  // (SceneFileError) is a row with an "infeasible: ..." status; anything else throws.
  SweepRow run(uint64_t index);
  uint64_t frames() const { return frames_; }

 private:
  const Scene& scene_for(const RunConfig& f, double scale, int bits);
  DeviceClock clock_of(const DeviceConfig& cfg) const;  // the sweep's clock, else cfg's (clock_for)
  SweepSpec spec_;
  RunConfig file_;
  std::vector<double> voxels_;  // each type's voxel in the scene file's own scene
  std::vector<bool> convex_;
  std::vector<Mesh> meshes_;
  uint64_t frames_ = 0;
  std::map<std::pair<double, int>, std::shared_ptr<const Scene>> scenes_;
};

}  // namespace voxcd
