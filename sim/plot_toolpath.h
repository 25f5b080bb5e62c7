// The XY toolpath row of a run picture (sim/plot.cpp draws the rest): the
// path of a G-code run on equal scales, travel, feed and extrusion apart
// (sim/toolpath.h traces it from the step edges).
#pragma once
#include <ostream>

#include "ticks.h"
#include "toolpath.h"

namespace sim {

constexpr double kPathLegendW = 520;  // room right of the toolpath panel

// The toolpath panel's scales: one tick step on both axes (the grid is
// square), one mm per pixel on both.
struct PathLayout {
  Ticks x, y;
  double margin = 0;  // mm beyond the outermost ticks
  double mm_per_px = 1;
  double cell_w = 0, cell_h = 0;  // the panel's cell, px
};

PathLayout path_layout(const Toolpath& tp);
double path_row_height(const PathLayout& l);
// Draws the panel and its legend with the cell's top at `top`.
void toolpath_row(std::ostream& svg, const Toolpath& tp, const PathLayout& l, double top);

}  // namespace sim
