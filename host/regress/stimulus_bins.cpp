#include "voxcd/host/regress/stimulus_bins.h"

#include <fstream>
#include <stdexcept>

#include "voxcd/ref/pipeline.h"

namespace voxcd {

namespace {

const char* const kAxis[3] = {"x", "y", "z"};

// The bins of the configuration itself.
void count_config(const DeviceConfig& c, std::map<std::string, uint64_t>& bins) {
  ++bins["config.lanes." + std::to_string(c.LANES)];
  ++bins["config.depth." + std::to_string(c.depth)];
  ++bins["config.sb." + std::to_string(c.SB)];
  if (c.BANKS > 0) ++bins["config.banks.shared"];
  if (c.BL > 0) ++bins["config.sparse"];
  if (c.brick_lanes()) ++bins["config.brick_lanes"];
  // Widths narrower and wider than the defaults (DeviceConfig{}).
  const DeviceConfig d;
  const int have[] = {c.PW, c.MW, c.TW, c.DW, c.MEMW, c.SAW, c.MAW, c.TAGW};
  const int dflt[] = {d.PW, d.MW, d.TW, d.DW, d.MEMW, d.SAW, d.MAW, d.TAGW};
  bool narrower = false, wider = false;
  for (int i = 0; i < 8; ++i) {
    narrower = narrower || have[i] < dflt[i];
    wider = wider || have[i] > dflt[i];
  }
  if (narrower) ++bins["config.widths.narrower"];
  if (wider) ++bins["config.widths.wider"];
}

// Where a point's index lies against the bounds on each axis, and the floor of a negative coordinate.
void count_point(const DeviceConfig& c, const Job& j, const Transformed& t, const Located& l,
                 std::map<std::string, uint64_t>& bins) {
  const int64_t n[3] = {int64_t(j.nx), int64_t(j.ny), int64_t(j.nz)};
  const int64_t span = int64_t{1} << c.DW;
  for (int a = 0; a < 3; ++a) {
    const std::string axis = kAxis[a];
    const int64_t i = l.index[a];
    if (i == -1) ++bins["face." + axis + ".-1"];
    if (i == 0) ++bins["face." + axis + ".0"];
    if (i == n[a] - 1) ++bins["face." + axis + ".n-1"];
    if (i == n[a]) ++bins["face." + axis + ".n"];
    if ((i < -1 || i > n[a]) && (((i % span) + span) % span) < n[a]) ++bins["far." + axis + ".wraps"];
    const Acc frac = t.acc[a] & ((Acc{1} << c.TF()) - 1);
    if (t.acc[a] < 0 && frac != 0) ++bins["floor." + axis + ".negative"];
  }
}

// Every bin the configuration can have, at 0: an empty bin is reported, not missing. The configuration bins are
// declared by every configuration: a campaign that leaves out a depth or a kind of device shows it empty.
void declare(const DeviceConfig& c, std::map<std::string, uint64_t>& bins) {
  for (int l : {1, 2, 4, 8}) bins["config.lanes." + std::to_string(l)];
  for (int d = 0; d <= kMaxDepth; ++d) bins["config.depth." + std::to_string(d)];
  for (int s : {2, 4, 8, 16}) bins["config.sb." + std::to_string(s)];
  for (const char* k : {"config.banks.shared", "config.sparse", "config.brick_lanes", "config.widths.narrower",
                        "config.widths.wider"})
    bins[k];
  for (const char* a : kAxis) {
    const std::string axis = a;
    for (const char* f : {".-1", ".0", ".n-1", ".n"}) bins["face." + axis + f];
    bins["far." + axis + ".wraps"];
    bins["floor." + axis + ".negative"];
  }
  for (int p = 0; p < c.dense_slot_points(); ++p) bins["first.position." + std::to_string(p)];
  if (c.SB > 2)
    for (const char* d : {"below", "at", "above"}) bins[std::string("distance.") + d];
  bins["job.map.dense"];
  bins["job.shell.dense"];
  for (const char* k : {"job.map.top", "job.shell.top", "job.tag.top", "job.points.max"}) bins[k];
  if (c.BL > 0) {
    bins["job.map.sparse"];
    bins["job.shell.sparse"];
  }
}

}  // namespace

std::map<std::string, uint64_t> stimulus_bins(const VectorFile& f) {
  const DeviceConfig& c = f.config;
  std::map<std::string, uint64_t> bins;
  declare(c, bins);
  count_config(c, bins);
  for (const Job& j : f.jobs) {
    ++bins[std::string("job.map.") + (j.sparse_map() ? "sparse" : "dense")];
    ++bins[std::string("job.shell.") + (j.sparse_shell() ? "sparse" : "dense")];
    // The upper half of each memory and of the tags: their addresses' and tags' top bits.
    if (!j.sparse_map() && j.map_base >= c.map_depth() / 2) ++bins["job.map.top"];
    if (!j.sparse_shell() && uint64_t(j.shell_base) + j.shell_count > c.shell_depth() / 2) ++bins["job.shell.top"];
    if (j.tag > c.max_tag() / 2) ++bins["job.tag.top"];
    if (!j.sparse_shell() && j.shell_count == c.shell_depth()) ++bins["job.points.max"];
    for (const ShellWord& p : job_points(c, f.memory.shell, j)) {
      const Transformed t = transform(c, j, p);
      const Located l = locate(c, j, t);
      count_point(c, j, t, l, bins);
      if (c.SB > 2 && l.inside) {
        const int64_t d = look_up(c, f.memory.map, j, p).dist;
        ++bins[d < j.threshold ? "distance.below" : d == j.threshold ? "distance.at" : "distance.above"];
      }
    }
  }
  // FIRST's hit: its position in the slot (a dense shell's slots start at multiples of the slot's points).
  // The expected stream holds each job's hits, then its completion record, job after job.
  size_t job = 0;
  for (const Record& r : f.expected) {
    if (r.kind == Record::Done) {
      ++job;
    } else if (job < f.jobs.size() && f.jobs[job].mode == Mode::First && !f.jobs[job].sparse_shell()) {
      ++bins["first.position." + std::to_string(r.point % uint32_t(c.dense_slot_points()))];
    }
  }
  return bins;
}

void write_stimulus_bins(const std::string& path, const VectorFile& f) {
  std::ofstream out(path);
  for (const auto& [name, count] : stimulus_bins(f)) out << name << ' ' << count << '\n';
  if (!out) throw std::runtime_error("cannot write the stimulus bins " + path);
}

}  // namespace voxcd
