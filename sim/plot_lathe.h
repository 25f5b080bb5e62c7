// A picture of one lathe pass, as one plain SVG file: the spindle against
// the leadscrew and the following error, against time.
//
//   left:  the carriage where the helix wants it (lambda times the spindle's
//          angle since the pass's index, from the spindle model, in mm of
//          carriage travel) and where the leadscrew put it (the servo
//          model's position, or the stepper's decoded steps), mm;
//   right: the following error, helix minus carriage in the pass's
//          direction (positive: the carriage lags), um.
// The tests build the series (tests/sim/test_lathe_servo.cpp) and write it
// when AVRMOTION_PLOT_DIR names a directory (docs/lathe.md). Tagged as the
// run pictures are (sim/plot.h): <g class="panel" data-axis="Z"
// data-kind="position|error">, series class="series" data-kind="helix|
// carriage|error".
#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace sim {

struct LathePlotPoint {
  double t_s;
  double helix_mm;     // where the carriage should be
  double carriage_mm;  // where it is
  double error_um;     // helix - carriage, in the pass's direction
};

void write_lathe_plot(std::ostream& svg, const std::string& title, const std::vector<LathePlotPoint>& points);
// false when the file cannot be written.
bool write_lathe_plot(const std::string& path, const std::string& title, const std::vector<LathePlotPoint>& points);

}  // namespace sim
