// The slicer-side tools of the print tests and the benchmark: the time
// estimator (sim/print_estimate.h) against trapezoids worked out here by
// hand, the limits probed from the m32 image (sim/print_limits.h) against
// the board's documented figures, and the file writer (sim/slicer_file.h):
// PrusaSlicer's start and end sequences, its estimate line, and the
// positions it promises, re-read from its own lines.
#include <gtest/gtest.h>

#include <climits>
#include <cstdio>

#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "print_estimate.h"
#include "print_limits.h"
#include "sim_fixture.h"
#include "slicer_file.h"

namespace {

// Four axes of 1000 steps/mm, 40 mm/s, 500 mm/s^2, E not in the path.
sim::MachineLimits four_axes() {
  sim::MachineLimits l;
  for (const char a : {'X', 'Y', 'Z', 'E'}) l.axes.push_back({a, 1000, 40, 500, a != 'E'});
  l.junction_mm = 0.01;
  return l;
}

double one(const std::vector<std::vector<double>>& moves, double feed) {
  sim::TimeEstimator e(four_axes());
  for (const auto& d : moves) e.move(d, feed);
  return e.seconds();
}

}  // namespace

TEST(PrintEstimate, TrapezoidsTrianglesAxisSharesAndJunctions) {
  // A cruise held at 40 mm/s: 100 / 40 + 40 / 500.
  EXPECT_NEAR(one({{100, 0, 0, 0}}, 6000), 2.58, 1e-12);
  // Too short for the cruise: a triangle peaking at sqrt(a L).
  EXPECT_NEAR(one({{1, 0, 0, 0}}, 2400), 2 * std::sqrt(500.0) / 500, 1e-12);
  // X30 Y40: Y is 0.8 of the path, so the path runs at 50 mm/s, 625 mm/s^2.
  EXPECT_NEAR(one({{30, 40, 0, 0}}, 6000), 50.0 / 50 + 50.0 / 625, 1e-12);
  // An extruder-only retraction: its own path, a triangle.
  EXPECT_NEAR(one({{0, 0, 0, -2}}, 2400), 2 * std::sqrt(1000.0) / 500, 1e-12);
  // Collinear blocks run through: one 20 mm move.
  EXPECT_NEAR(one({{10, 0, 0, 0}, {10, 0, 0, 0}}, 2400), 20.0 / 40 + 40.0 / 500, 1e-12);
  // A square corner: v^2 = a d h / (1 - h) with h = sin 45, a = 500 / cos 45.
  const double h = std::sqrt(0.5), v2 = 500 / std::sqrt(0.5) * 0.01 * h / (1 - h), v = std::sqrt(v2);
  const double block = 40.0 / 500 + (40 - v) / 500 + (10 - 1.6 - (1600 - v2) / 1000) / 40;
  EXPECT_NEAR(one({{10, 0, 0, 0}, {0, 10, 0, 0}}, 2400), 2 * block, 1e-12);
  // A reversal stops; so does an extruder-only block between two moves.
  EXPECT_NEAR(one({{10, 0, 0, 0}, {-10, 0, 0, 0}}, 2400), 2 * (10.0 / 40 + 40.0 / 500), 1e-12);
  EXPECT_NEAR(one({{10, 0, 0, 0}, {0, 0, 0, 1}, {10, 0, 0, 0}}, 2400),
              2 * (10.0 / 40 + 40.0 / 500) + 2 * std::sqrt(500.0) / 500, 1e-12);
  // A rest between collinear moves stops there.
  sim::TimeEstimator e(four_axes());
  e.move({10, 0, 0, 0}, 2400);
  e.rest();
  e.move({10, 0, 0, 0}, 2400);
  EXPECT_NEAR(e.seconds(), 2 * (10.0 / 40 + 40.0 / 500), 1e-12);
  EXPECT_EQ(e.moves(), 2u);
  e.move({0, 0, 0, 0}, 2400);  // no axis: not a move
  EXPECT_EQ(e.moves(), 2u);
}

TEST(PrintEstimate, LimitsProbedFromTheM32ImageAreItsBoardFigures) {
  // docs/gcode.md: the m32 runs every axis at 40000 steps/s (kMaxStepRate)
  // and 500 mm/s^2 (kDefaultAccel), 1000 steps/mm.
  const sim::MachineLimits l = sim::probe_limits(simtest::image("m32"));
  ASSERT_EQ(l.axes.size(), 4u);
  for (const sim::AxisLimit& a : l.axes) {
    EXPECT_EQ(a.steps_per_mm, 1000) << a.name;
    EXPECT_NEAR(a.max_rate_mm_s, 40, 0.04) << a.name;
    EXPECT_NEAR(a.accel_mm_s2, 500, 2.5) << a.name;  // within 0.5 %
    EXPECT_EQ(a.in_path, a.name != 'E');
  }
  std::printf("probed: %s\n", l.describe().c_str());
}

TEST(PrintEstimate, TheFileIsPrusaSlicersShapeAndKeepsItsPromises) {
  sim::SlicerOptions o;
  o.layers = 4;
  const sim::SlicerFile f = sim::write_slicer_file(four_axes(), o);
  std::vector<std::string> cmd;  // the commands, comments off
  for (const std::string& l : f.lines) {
    const std::string c = l.substr(0, l.find(" ;"));
    if (!c.empty() && c[0] != ';') cmd.push_back(c);
  }
  ASSERT_EQ(cmd.size(), f.command_lines());
  const std::vector<std::string> start = {"M73 P0 R" + std::to_string(long(std::ceil(f.estimate_s / 60))),
                                          "M107", "M104 S200", "G28", "G1 Z5 F5000", "M109 S200",
                                          "G21",  "G90",       "M82", "G92 E0"};
  ASSERT_GE(cmd.size(), start.size() + 4);
  EXPECT_EQ(std::vector<std::string>(cmd.begin(), cmd.begin() + long(start.size())), start);
  EXPECT_EQ(std::vector<std::string>(cmd.end() - 4, cmd.end()),
            (std::vector<std::string>{"M104 S0", "M107", "G28 X0", "M84"}));
  EXPECT_EQ(f.lines.back(), "; estimated printing time (normal mode) = " + sim::slicer_duration(f.estimate_s));
  EXPECT_EQ(sim::slicer_duration(3723.4), "1h 2m 3s");
  EXPECT_EQ(sim::slicer_duration(59.6), "1m 0s");

  // Re-read: the modal position, G92 E0, every layer's literal retraction,
  // the fan; E's machine steps as the firmware counts them (to 1/10000 mm,
  // then to steps, half away from zero), and the moves the estimate timed.
  std::map<char, double> at;
  int64_t e_offset = 0, e_steps = 0;
  int g92 = 0, retractions = 0, fans = 0;
  size_t moves = 0;
  bool timing = false;
  for (const std::string& c : cmd) {
    if (c == "G92 E0") {
      ++g92;
      e_offset = e_steps;
      at['E'] = 0;
      timing = true;
    }
    retractions += c == "G1 E-2 F2400";
    fans += c.rfind("M106 S", 0) == 0;
    if (c.rfind("G1 ", 0) != 0) continue;
    std::istringstream words(c.substr(3));
    bool moved = false;
    for (std::string w; words >> w;) {
      if (w[0] == 'F') continue;
      const double v = std::atof(w.c_str() + 1);
      moved |= at[w[0]] != v;
      at[w[0]] = v;
      if (w[0] == 'E') {
        const int64_t e4 = std::llround(v * 10000);
        e_steps = e_offset + (e4 >= 0 ? (e4 + 5) / 10 : -((-e4 + 5) / 10));
      }
    }
    moves += timing && moved;
  }
  EXPECT_EQ(g92, o.layers + 1);
  EXPECT_EQ(retractions, o.layers);
  EXPECT_EQ(fans, o.layers - 1);
  EXPECT_EQ(moves, f.moves);
  EXPECT_EQ(std::llround(at['X'] * 1000), f.x_um);
  EXPECT_EQ(std::llround(at['Y'] * 1000), f.y_um);
  EXPECT_EQ(std::llround(at['Z'] * 1000), f.z_um);
  EXPECT_EQ(e_steps, f.e_steps);
  EXPECT_EQ(f.z_um, o.layers * o.layer_um + 1000);  // the last layer and the lift
  EXPECT_GT(f.estimate_s, 0);

  // Progress: M73 at the start, at each layer, after the park, P never
  // going back and R never up; M117 at each layer and at the end.
  int last_p = -1, m73 = 0, m117 = 0;
  long last_r = LONG_MAX;
  for (const std::string& c : cmd) {
    m117 += c.rfind("M117 ", 0) == 0;
    if (c.rfind("M73 P", 0) != 0) continue;
    ++m73;
    int p = -1;
    long r = -1;
    ASSERT_EQ(std::sscanf(c.c_str(), "M73 P%d R%ld", &p, &r), 2) << c;
    EXPECT_GE(p, last_p) << c;
    EXPECT_LE(r, last_r) << c;
    last_p = p, last_r = r;
  }
  EXPECT_EQ(m73, o.layers + 2);
  EXPECT_EQ(m117, o.layers + 1);
  EXPECT_EQ(last_p, 100);
  EXPECT_EQ(last_r, 0);
  EXPECT_EQ(f.last_progress, 100);
  EXPECT_EQ(f.last_message, "Print done");
}

// The machine-limits block: PrusaSlicer's lines, and an estimate that uses
// them (a slower file's limits make a longer estimate; M204's caps count).
TEST(PrintEstimate, TheFileWritesItsMachineLimitsAndTimesWithThem) {
  sim::SlicerOptions o;
  o.layers = 2;
  o.machine_limits = true;
  o.file_limits = sim::i3_file_limits();
  const sim::SlicerFile f = sim::write_slicer_file(four_axes(), o);
  std::vector<std::string> block;
  for (const std::string& l : f.lines)
    if (l.rfind("M20", 0) == 0) block.push_back(l.substr(0, l.find(" ;")));
  EXPECT_EQ(block, (std::vector<std::string>{"M201 X1000 Y1000 Z200 E5000", "M203 X200 Y200 Z12 E120",
                                              "M204 P1000 R1000 T1500", "M205 X8 Y8 Z0.4 E4.5", "M205 J0.02"}));
  EXPECT_TRUE(sim::file_sets_all(four_axes(), o.file_limits));
  sim::SlicerOptions slower = o;
  slower.file_limits.print_accel = 100;  // the perimeters and the infill
  const double slow = sim::write_slicer_file(four_axes(), slower).estimate_s;
  EXPECT_GT(slow, f.estimate_s * 1.2) << f.estimate_s;
  sim::SlicerOptions none = o;
  none.machine_limits = false;  // four_axes()'s own limits
  EXPECT_NE(sim::write_slicer_file(four_axes(), none).estimate_s, f.estimate_s);
  std::printf("estimates: %.3f s with the i3 block, %.3f s with M204 P100\n", f.estimate_s, slow);
}
