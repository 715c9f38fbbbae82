// The picture of a sweep (`voxcd sweep --plot`): contact error bound against cycles per frame, both on log axes
// with a line at every power of ten, the Pareto front's points in red and the others in grey-blue.
#pragma once

#include <string>

#include "voxcd/host/object/png.h"
#include "voxcd/host/sizing/sweep/sweep_table.h"

namespace voxcd {

struct SweepPlot {
  Image image{640, 480};
  double x_lo = 1, x_hi = 10;  // the axes' ranges: whole powers of ten around the feasible rows
  double y_lo = 1, y_hi = 10;
  std::string caption() const;  // what the axes are and their ranges, for the tool's output
};

// Draws the table's feasible rows (none: empty axes).
SweepPlot sweep_plot(const SweepTable& t);

}  // namespace voxcd
