// The functional coverage bins that are about the stimulus rather than the RTL (docs/verification.md, "Functional
// coverage"): counted from a vector file with ref/'s own stages, one "NAME COUNT" line each.
#pragma once

#include <cstdint>
#include <map>
#include <string>

#include "voxcd/ref/vectors.h"

namespace voxcd {

// Name -> count: the configuration (config.lanes.N, config.depth.D, config.sb.S, config.banks.shared,
// config.sparse, config.brick_lanes, config.widths.narrower / .wider than the defaults); every point's index at each face of the bounds on each axis (face.x.-1,
// face.x.0, face.x.n-1, face.x.n), far outside where its low DW bits would fall inside (far.x.wraps), and the floor of
// a negative coordinate with a fraction (floor.x.negative); FIRST's hit at each position of its slot
// (first.position.P); a distance job's inside points below, at and above its threshold (distance.below, .at,
// .above); each job's map and shell kind (job.map.dense/sparse, job.shell.dense/sparse); a dense map in the upper half
// of the voxmap memory, a dense shell window reaching the upper half of the shell memory, a tag in the upper half of
// the tags (job.map.top, job.shell.top, job.tag.top: the top bits of addresses and tags), a dense job of every shell
// word (job.points.max: the top bits of point indices and counts). Every bin of the
// configuration is present, hit or not.
std::map<std::string, uint64_t> stimulus_bins(const VectorFile& f);

// Writes stimulus_bins(f) to `path`; std::runtime_error naming the file when it cannot be written.
void write_stimulus_bins(const std::string& path, const VectorFile& f);

}  // namespace voxcd
