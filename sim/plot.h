// Pictures of a run, as one plain SVG file (any browser shows it; no plotting
// library involved).
//
// One row of four panels per axis, each panel with its own scale:
//   position (mm) | velocity (mm/s) | acceleration (mm/s^2)  against time (s)
//   | a histogram of the axis's step intervals (us, log bins, log counts).
// On a board with a simulated hot end (PlotLabel::plant), a row below the
// axes': its temperatures and setpoint | the heater's duty, against time
// (sim/plot_thermal.h).
// When the board has X and Y and both stepped, a last row: the XY toolpath
// (mm, one scale and one 1-2-5 tick step on both axes), travel, feed and
// extrusion drawn apart as sim/toolpath.h classifies them, with a legend and
// the rule that was applied.
// Velocity and acceleration are derived from the decoded step events as
// sim/motion.h describes (a Gaussian window whose width is in the panel
// titles). Ticks are 1-2-5 values (sim/ticks.h). Each axis keeps one colour
// in all its panels; the palette has eight colours that stay distinct.
//
// For tests and tools the SVG is tagged: every panel is a <g class="panel"
// data-axis="X" data-kind="position|velocity|acceleration|intervals">, every
// data series carries class="series" and the same data-axis / data-kind,
// tick labels are <text class="tick" data-dir="x|y"> and axis titles
// <text class="axis-title">. The toolpath is <g class="panel" data-axis="XY"
// data-kind="toolpath">, its path polylines class="series" data-axis="XY"
// data-kind="toolpath" data-move="travel|feed|extrusion" (one per run of a
// kind, in order, each starting where the last ended), the start and end
// <circle class="marker" data-kind="start|end">, and the legend entries
// <g class="move-legend" data-move="...">.
#pragma once
#include <string>

#include "machine.h"
#include "thermal_plant.h"

namespace sim {

// Colours of the series, in order: eight, pairwise distinct.
constexpr int kPaletteSize = 8;
const char* palette_colour(int series);

struct PlotLabel {
  std::string input;  // shown in the title (the command file's name), may be empty
  RunEnd end = RunEnd::done;
  const ThermalPlant* plant = nullptr;  // a hot end's row (sim/plot_thermal.h)
};

void write_run_plot(const std::string& path, Machine& m, const PlotLabel& label = PlotLabel());

}  // namespace sim
