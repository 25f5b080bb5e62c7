// A slicer's file prints start to finish on the simulated printer (issue
// 13): sim/slicer_file.h writes a PrusaSlicer-style print of three layers
// (M107, M104 S200, G28, G1 Z5 F5000, M109 S200, G21, G90, M82, G92 E0, the
// layers, M104 S0, G28 X0, M84), printrun's printcore streams it through
// avrmotion-sim --pty to the m32 image, whose simulated hot end heats from
// 25 C at its own pace (not sped up) and whose switches sit at each axis's
// 0. What the simulator measured from the pins and the plant (the report's
// "print" object, sim/print_watch.h) says the rest: the hot end was at its
// target before the first extrusion and off at the end, every switch was
// reached (two homings of X, one of Y and Z), every driver disabled after
// M84; every line got one `ok` and no error, and every axis ended exactly
// where the homing and the file put it; the report's print.progress and
// print.message are the file's last M73 P and M117 text.
#include <cstdio>
#include <fstream>
#include <string>

#include "board_info.h"
#include "print_limits.h"
#include "printcore_run.h"
#include "pty_client.h"
#include "sim_fixture.h"
#include "slicer_file.h"

namespace {

using printcore_run::summary_number;
using ptytest::report_number;
using ptytest::report_string;

// The m32's homing (firmware/boards/common/m32_wiring.h, docs/homing.md):
// a homed axis is at its program 0 `pull_off` steps above the switch's trip
// point, the switch at the axis's decoded 0.
constexpr int64_t kPullOffSteps = 1000;
// M109 S waits until the reading is at least the target - 1 C (docs/heater.md).
constexpr double kTarget = 200, kWindow = 1;

}  // namespace

TEST(Printcore, AHeatedSlicerPrintRunsStartToFinishAndEndsCold) {
  const std::string image = simtest::image("m32");
  sim::SlicerOptions options;
  options.layers = 3;
  const sim::SlicerFile print = sim::write_slicer_file(sim::probe_limits(image), options);
  const size_t sent_lines = print.command_lines();
  ASSERT_GE(sent_lines, 300u);
  const std::string file = simtest::temp_path("heated.gcode"), report = simtest::temp_path("heated.json");
  {
    std::ofstream out(file);
    for (const std::string& l : print.lines) out << l << "\n";
  }
  // printcore opens the port, closes it and opens it again (its parity
  // workaround for Arduino boards): --linger 0 could end the run between the
  // two, and printcore would wait on a port nobody serves.
  ptytest::SimProcess sim({"--board", "m32", "--pty", "--speed", "max", "--linger", "1", "--max-seconds", "600",
                           "--report", report});
  const std::string port = sim.pty_path();
  ASSERT_FALSE(port.empty()) << sim.stderr_text();
  const std::string summary = printcore_run::stream(port, file, "--guard 400");
  std::printf("printcore: %s\n", summary.c_str());
  ASSERT_EQ(sim.wait_exit(), 0) << sim.stderr_text();
  const std::string json = simtest::slurp(report);
  std::remove(file.c_str());
  std::remove(report.c_str());

  // printcore's side: no refusal, no resend; every line it sent (the
  // file's, its two M110, our M400) got exactly one ok.
  EXPECT_NE(summary.find("\"errors\": []"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"resends\": []"), std::string::npos) << summary;
  EXPECT_EQ(summary_number(summary, "sent"), long(sent_lines) + 2 + 1) << summary;
  EXPECT_EQ(summary_number(summary, "oks"), summary_number(summary, "sent")) << summary;

  // The printer's side: every line that arrived answered, none refused, no
  // starvation.
  const long m105_lost = summary_number(summary, "m105_sent") - summary_number(summary, "m105_oks");
  EXPECT_EQ(long(report_number(json, "", "lines_answered")), long(report_number(json, "", "lines_sent")) - m105_lost)
      << json;
  EXPECT_EQ(long(report_number(json, "", "lines_ok")), long(report_number(json, "", "lines_answered")));
  EXPECT_EQ(report_string(json, "errors"), "[]");
  EXPECT_EQ(report_number(json, "", "starvations"), 0);

  // The heat: at the first extrusion (E past every position it had) the
  // thermistor read at least the target less M109's window; at the end the
  // heater pin low, no high time in the last 100 ms, the setpoint 0.
  const double first_extrusion_s = report_number(json, "print", "first_extrusion_s");
  EXPECT_GT(first_extrusion_s, 0) << json;
  EXPECT_GE(report_number(json, "print", "hotend_c_at_first_extrusion"), kTarget - kWindow) << json;
  EXPECT_LT(report_number(json, "print", "hotend_c_at_first_extrusion"), kTarget + 5) << json;
  EXPECT_GE(report_number(json, "thermal", "peak_c"), kTarget - kWindow);
  EXPECT_EQ(report_number(json, "print", "heater_pin_at_end"), 0) << json;
  EXPECT_EQ(report_number(json, "print", "heater_duty_last_100ms"), 0) << json;
  EXPECT_EQ(report_number(json, "print", "target_c_at_end"), 0) << json;
  // The motors: every driver's enable pin at its inactive level after M84.
  EXPECT_EQ(report_string(json, "drivers_enabled_at_end"), "\"\"") << json;
  // What the firmware echoed to the last M73 and M117 (printcore numbers
  // the lines: `N<n> M117 Print done*<sum>`).
  EXPECT_EQ(report_number(json, "print", "progress"), print.last_progress) << json;
  EXPECT_EQ(report_string(json, "message"), "\"" + print.last_message + "\"") << json;
  // The homing: each G28 closes a switch twice (the seek, or the switch
  // closed at the start, and the locate); X homes at the start and at the end.
  EXPECT_EQ(report_number(json, "print", "switch_closes_X"), 4) << json;
  EXPECT_EQ(report_number(json, "print", "switch_closes_Y"), 2) << json;
  EXPECT_EQ(report_number(json, "print", "switch_closes_Z"), 2) << json;

  // The positions: X back on its homed position, Y and Z that plus the
  // file's last targets, E the file's steps (G92 E0 keeps the steps).
  const am::BoardDescriptor b = sim::read_board_descriptor(image);
  const auto steps = [&](char axis, int64_t um) {
    for (uint8_t i = 0; i < b.axis_count; ++i)
      if (b.axes[i].name == axis) return double(sim::round_half_away(um * int64_t(b.axes[i].steps_per_m), 1000000));
    return -1e9;
  };
  EXPECT_EQ(report_number(json, "X", "steps"), double(kPullOffSteps)) << json;
  EXPECT_EQ(report_number(json, "Y", "steps"), kPullOffSteps + steps('Y', print.y_um));
  EXPECT_EQ(report_number(json, "Z", "steps"), kPullOffSteps + steps('Z', print.z_um));
  EXPECT_EQ(report_number(json, "E", "steps"), double(print.e_steps));
  EXPECT_DOUBLE_EQ(report_number(json, "motion", "filament_mm"), double(print.e_steps) / steps('E', 1000));
  std::printf("heated print: %zu lines, %.1f s simulated (first extrusion at %.1f s, %.2f C) in %.1f s wall\n",
              sent_lines, report_number(json, "", "seconds"), first_extrusion_s,
              report_number(json, "print", "hotend_c_at_first_extrusion"), report_number(json, "pty", "wall_seconds"));
}
