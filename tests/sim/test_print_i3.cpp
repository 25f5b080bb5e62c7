// The printer profile (the m32-i3 image: 80 steps/mm X Y, 400 Z, 93 E,
// docs/simulator.md) prints a slicer's file that sets an i3's machine
// limits itself (sim/slicer_file.h with `machine_limits`: M201 X1000 Y1000
// Z200 E5000, M203 X200 Y200 Z12 E120, M204 P1000 R1000 T1500, M205 J0.02,
// M221 S95, M73 and M117 lines), one line in flight, hot end at 200 C from
// the start: every line answered `ok`, no limit held by the firmware, no
// starvation; each G28 leaves its axis 1 mm (80/80/400 steps) above its
// switch; every axis ends on the steps the homing and the file give (E with
// the file's M221: each move's steps scaled and rounded as the firmware
// does, sim/slicer_file.cpp); the print's time within 10 % of the file's
// own estimate (from the file's limits); the report's print.progress and
// print.message are what the firmware echoed to the last M73 and M117.
// And the report's two keys on their own: the last M73 with a percent, the
// last M117's text (one that reads like progress is a message), absent
// when the firmware said neither.
#include <gtest/gtest.h>

#include <cstdio>
#include <regex>
#include <sstream>
#include <string>

#include "endstops.h"
#include "machine.h"
#include "print_limits.h"
#include "print_watch.h"
#include "report.h"
#include "sim_fixture.h"
#include "slicer_file.h"
#include "thermal_plant.h"

namespace {

std::string report_of(sim::Machine& m, const sim::ThermalPlant& plant, const sim::PrintWatch& watch) {
  std::ostringstream out;
  sim::write_report(out, m, sim::RunEnd::done, nullptr, &plant, -1, &watch);
  return out.str();
}

std::string print_key(const std::string& json, const std::string& key) {
  std::smatch m;
  const std::regex re("\"print\": \\{[^}]*\"" + key + "\": (\"[^\"]*\"|-?[0-9.]+)");
  return std::regex_search(json, m, re) ? std::string(m[1]) : "<absent>";
}

}  // namespace

TEST(PrintI3, AFileWithAnI3sLimitsPrintsExactlyNearItsEstimate) {
  const std::string image = simtest::image("m32-i3");
  sim::SlicerOptions o;
  o.layers = 2;
  o.segments = 24;
  o.end_m400 = true;
  o.machine_limits = true;
  o.file_limits = sim::i3_file_limits();
  o.flow_percent = 95;
  const sim::MachineLimits board = sim::board_limits(image);
  ASSERT_TRUE(sim::file_sets_all(board, o.file_limits));  // nothing to probe
  const sim::SlicerFile file = sim::write_slicer_file(board, o);
  sim::SlicerOptions full = o;
  full.flow_percent = 0;
  const int64_t unflowed = sim::write_slicer_file(board, full).e_steps;
  ASSERT_GT(unflowed, 0);
  // 95 % of the steps, within each move's rounding.
  EXPECT_NEAR(double(file.e_steps), 0.95 * double(unflowed), double(file.moves)) << unflowed;

  sim::Machine m(image);
  sim::ThermalParams hot;
  hot.initial_c = 200;
  sim::ThermalPlant plant(m, hot);
  sim::Endstops switches(m);
  sim::PrintWatch watch(m, &plant, &switches);
  for (const std::string& l : file.lines)
    if (!sim::command_of(l).empty()) m.serial().add_line(sim::command_of(l));
  const size_t lines = m.serial().lines_pending();
  ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 300), sim::RunEnd::done);

  uint64_t homed = 0, heated = 0, parked = 0;
  const std::vector<sim::Response>& rs = m.serial().responses();
  ASSERT_GE(rs.size(), lines);
  for (size_t i = 0; i < lines; ++i) {
    EXPECT_TRUE(sim::SerialHost::is_ok(rs[i].answer)) << rs[i].line << ": " << rs[i].answer;
    if (rs[i].line == "G28" && !homed) homed = rs[i].answer_cycle;
    if (rs[i].line.rfind("M109 ", 0) == 0 && !heated) heated = rs[i].answer_cycle;
    if (rs[i].line == "M400" && !parked) parked = rs[i].answer_cycle;
  }
  ASSERT_TRUE(homed && heated && parked);
  for (const std::string& l : m.serial().messages())
    EXPECT_EQ(l.find("held within the board's limit"), std::string::npos) << l;
  EXPECT_EQ(m.starvations(), 0);

  // The homing: each axis 1 mm above its switch (at decoded 0).
  const sim::AxisTrace &x = *m.axis('X'), &y = *m.axis('Y'), &z = *m.axis('Z'), &e = *m.axis('E');
  EXPECT_EQ(sim::position_at(x, homed), 80);
  EXPECT_EQ(sim::position_at(y, homed), 80);
  EXPECT_EQ(sim::position_at(z, homed), 400);
  const auto steps = [&](char name, int64_t um) {
    return sim::round_half_away(um * int64_t(board.axes[size_t(board.index(name))].steps_per_mm * 1000), 1000000);
  };
  EXPECT_EQ(x.position, sim::position_at(x, homed));  // G28 X0 at the end
  EXPECT_EQ(y.position, sim::position_at(y, homed) + steps('Y', file.y_um));
  EXPECT_EQ(z.position, sim::position_at(z, homed) + steps('Z', file.z_um));
  EXPECT_EQ(e.position, file.e_steps);

  // The time: from the first step after M109's answer to the last before the M400's.
  uint64_t first, last;
  ASSERT_TRUE(sim::motion_span(m.axes(), heated, parked, first, last));
  const double print_s = double(last - first) / m.f_cpu(), ratio = print_s / file.estimate_s;
  std::printf("i3 print: %zu lines, %.3f s against the estimate's %.3f s: ratio %.3f; E %lld steps (%lld at 100 %%)\n",
              lines, print_s, file.estimate_s, ratio, (long long)file.e_steps, (long long)unflowed);
  EXPECT_NEAR(ratio, 1.0, 0.1);

  // What the firmware echoed, in the report.
  const std::string json = report_of(m, plant, watch);
  EXPECT_EQ(print_key(json, "progress"), std::to_string(file.last_progress)) << json;
  EXPECT_EQ(file.last_progress, 100);
  EXPECT_EQ(print_key(json, "message"), "\"" + file.last_message + "\"") << json;
}

TEST(PrintI3, TheReportSaysTheLastProgressAndMessageOrNeither) {
  sim::Machine m(simtest::image("m32-i3"));
  sim::ThermalPlant plant(m);
  sim::Endstops switches(m);
  sim::PrintWatch watch(m, &plant, &switches);
  m.serial().add_line("M105");
  ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 5), sim::RunEnd::done);
  std::string json = report_of(m, plant, watch);
  EXPECT_EQ(print_key(json, "progress"), "<absent>") << json;
  EXPECT_EQ(print_key(json, "message"), "<absent>") << json;

  for (const char* l : {"M73 P12 R9", "M117 first", "M73 P42 R3", "M73 R2", "M117 Progress: 7% ; a message, not M73's"})
    m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 5), sim::RunEnd::done);
  json = report_of(m, plant, watch);
  EXPECT_EQ(print_key(json, "progress"), "42") << json;
  EXPECT_EQ(print_key(json, "message"), "\"Progress: 7% \"") << json;  // up to the comment, its space kept
  m.serial().add_line("M117 done");
  ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 5), sim::RunEnd::done);
  EXPECT_EQ(print_key(report_of(m, plant, watch), "message"), "\"done\"");
}
