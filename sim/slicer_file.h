// A slicer's file, written as PrusaSlicer writes one, for the printer tests
// and the benchmark (tests/sim/test_printcore_heated.cpp, sim/bench_print.cpp).
//
// Contract of write_slicer_file()
//   The file: header comments; the start sequence M107, M104 S<t>, G28,
//   G1 Z5 F5000, M109 S<t>, G21, G90, M82, G92 E0; per layer
//   ;LAYER_CHANGE, G92 E0, the retraction G1 E-2 F2400, the layer's Z, a
//   travel, the unretraction G1 E0, `perimeters` closed perimeters of
//   `segments` chords round (cx, cy), a retract / travel / unretract, then
//   a zig-zag infill inside them (X lines on even layers, Y lines on odd
//   ones), fan changes (M106 from the second layer on); the end sequence
//   (a lift and a park; M400 if `end_m400`; M104 S0, M107, G28 X0, M84);
//   PrusaSlicer's closing comments with
//   `; estimated printing time (normal mode) = 1h 2m 3s`.
//   With `machine_limits` (PrusaSlicer's "emit machine limits to G-code"),
//   a block right after the header: M201 X Y Z E, M203 X Y Z E, M204 P R T,
//   M205 X Y Z E (classic jerk) and M205 J, each word where FileLimits has
//   it (> 0). With `progress`: M73 P<p> R<min> after the header,
//   at each layer change and after the park (P the estimate's share of the
//   timed moves before that line, whole percent rounded down; R the rest in
//   whole minutes, rounded up); M117 `Layer <n> of <N>` at each layer
//   change and `Print done` at the end. With flow_percent > 0: M220 S100 and
//   M221 S<flow> before the first timed move.
//   Coordinates are written with 3 decimals (whole micrometres) and E with
//   5, absolute (M82), so the expected machine positions are exact integers
//   (SlicerFile's, below); no feed above the limits' top rates except the
//   start's G1 Z5 F5000 (the firmware holds it and says so).
//   The estimate: TimeEstimator (print_estimate.h) over the file's moves
//   from the one after M109 to the park (the part a slicer can time: the
//   heat-up and homing it cannot), with `limits` where the file's block sets
//   nothing and the file's figures where it does (apply_file_limits()); the
//   file's comment says it in PrusaSlicer's format, estimate_s holds it
//   unrounded. e_steps follows the firmware's M221 (each move's E steps
//   scaled, half away from zero, from the machine's count).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "print_estimate.h"

namespace sim {

// A file's machine limits (0: not written). Axes X Y Z E in that order.
struct FileLimits {
  double accel[4] = {};         // M201, mm/s^2
  double feed[4] = {};          // M203, mm/s
  double print_accel = 0, retract_accel = 0, travel_accel = 0;  // M204 P R T, mm/s^2
  double jerk[4] = {};          // M205 X Y Z E, mm/s (written; this planner has no jerk)
  double junction_mm = 0;       // M205 J
};
// An i3-style machine's (the printer profile, docs/simulator.md).
FileLimits i3_file_limits();
// `limits` with what `file` sets in its place.
MachineLimits apply_file_limits(const MachineLimits& limits, const FileLimits& file);
// True when `file` sets every axis's rate and acceleration of `limits`'s
// axes: probing the image is then needed for nothing but steps/mm.
bool file_sets_all(const MachineLimits& limits, const FileLimits& file);

struct SlicerOptions {
  int layers = 3;
  int perimeters = 2;
  int segments = 48;                 // chords of a perimeter
  int64_t cx_um = 60000, cy_um = 60000, radius_um = 10000;
  int64_t layer_um = 200;
  int64_t infill_spacing_um = 1000;
  int hotend_c = 200;
  double perimeter_feed = 1800, infill_feed = 2400, travel_feed = 2400;  // mm/min
  bool end_m400 = false;            // M400 after the park (the bench times the print up to its answer)
  bool machine_limits = false;      // the M201..M205 block, from `file_limits`
  FileLimits file_limits;
  bool progress = true;             // M73 and M117 lines
  int flow_percent = 0;             // > 0: M220 S100 and M221 S<flow_percent>
};

struct SlicerFile {
  std::vector<std::string> lines;   // comments included (a host drops them)
  double estimate_s = 0;            // the estimator's time for the moves after M109 up to the park
  int last_progress = -1;           // the last M73's P (-1: none written)
  std::string last_message;         // the last M117's text ("" : none)
  size_t moves = 0;                 // the moves it timed
  // The program position at the end of the print (before the end's G28 X0),
  // X Y Z in micrometres; the extruder's machine position in its steps
  // (every G92 E0 keeps the steps, as the firmware does).
  int64_t x_um = 0, y_um = 0, z_um = 0;
  int64_t e_steps = 0;
  double filament_mm = 0;           // E's net travel as written
  size_t command_lines() const;     // the lines a host sends (not the comments)
};

SlicerFile write_slicer_file(const MachineLimits& limits, const SlicerOptions& options);

// "1h 2m 3s", "2m 3s", "45s" (PrusaSlicer's format; whole seconds, rounded).
std::string slicer_duration(double seconds);
// What a line of the file sends: the text before its `;` comment, trailing
// blanks dropped (empty for a comment line).
std::string command_of(const std::string& line);

// Half away from zero, as the firmware rounds a program position to steps.
int64_t round_half_away(int64_t v, int64_t d);

}  // namespace sim
