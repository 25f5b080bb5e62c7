// The printer codes a slicer's file carries, on the real m32 (Marlin)
// image (firmware/services/printer_codes.h, docs/gcode.md): their answers,
// and what each does to the steps on the pins, measured from the pins: M220
// scales the feed, M203 caps an axis's rate, M201 and M204 its and the
// path's acceleration (P for moves that extrude, T for travel, R for the
// extruder alone), M205 J the corner speed, M221 the extruder's steps
// (exactly, with M114 still reporting the program's E). The m32 runs 1000
// steps/mm on every axis at 16 MHz; its own figures: 40 mm/s, 500 mm/s^2.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

constexpr double kHz = 16e6;

// Steps of `steps` within `seconds` of its first one.
size_t steps_within(const std::vector<uint64_t>& steps, double seconds) {
  if (steps.empty()) return 0;
  const uint64_t end = steps.front() + uint64_t(seconds * kHz);
  return size_t(std::upper_bound(steps.begin(), steps.end(), end) - steps.begin());
}

// The most frequent step interval (cycles): a move's cruise.
uint64_t cruise_interval(const std::vector<uint64_t>& steps) {
  std::vector<uint64_t> d;
  for (size_t i = 1; i < steps.size(); ++i) d.push_back(steps[i] - steps[i - 1]);
  std::sort(d.begin(), d.end());
  uint64_t best = 0;
  size_t best_n = 0;
  for (size_t i = 0; i < d.size();) {
    size_t j = i;
    while (j < d.size() && d[j] <= d[i] + 2) ++j;  // within the engine's tick rounding
    if (j - i > best_n) best_n = j - i, best = d[i];
    i = j;
  }
  return best;
}

bool has_message(const sim::SerialHost& host, const std::string& text) {
  const std::vector<std::string> m = host.messages();
  return std::find(m.begin(), m.end(), text) != m.end();
}

}  // namespace

TEST(PrinterCodes, EveryCodeIsAnsweredAsTheDocsSay) {
  const std::vector<std::string> lines = {
      "M73 P42 R17", "M73 Q42 S17", "M117 Hello printer", "M220", "M220 S150", "M220", "M221 S95", "M221",
      "M203 X1000", "M201 E0.001", "M204 P1500 T3000 R1000", "M205 X10 Y10 Z0.4 E4.5 S0 T0 J0.02",
      "M220 S5", "M201 X0", "M303 S200", "M140 S60", "M190 S60", "G29", "M900 K0",
      "M3 S50", "M105", "M5", "M105"};
  auto m = simtest::run("m32", lines, 5);
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), lines.size());
  for (const sim::Response& x : r) {
    std::printf("  > %s\n  < %s\n", x.line.c_str(), x.answer.c_str());
    const bool refused = x.line == "M220 S5" || x.line == "M201 X0";
    if (x.line == "M105") continue;  // below
    if (refused) {
      EXPECT_EQ(x.answer.rfind("Error:M", 0), 0u) << x.line;
    } else {
      EXPECT_EQ(x.answer, "ok") << x.line;
    }
  }
  const sim::SerialHost& h = m->serial();
  for (const char* text :
       {"echo:Progress: 42% 17 min left", "echo:Progress:", "echo:Hello printer", "echo:FR:100%", "echo:FR:150%",
        "echo:E0 Flow: 95%", "echo:X held within the board's limit", "echo:E held within the board's limit",
        "echo:Unknown command: \"M303 S200\"", "echo:Unknown command: \"M140 S60\"",
        "echo:Unknown command: \"M190 S60\"", "echo:Unknown command: \"G29\"", "echo:Unknown command: \"M900 K0\""})
    EXPECT_TRUE(has_message(h, text)) << text;
  EXPECT_EQ(h.errors().size(), 2u);
  // The seed's M3 S50 and M5: the hot end's target on and off (M105's answer).
  EXPECT_EQ(r[r.size() - 3].answer.rfind("ok T:", 0), 0u);
  EXPECT_NE(r[r.size() - 3].answer.find(" /50.00 @:"), std::string::npos) << r[r.size() - 3].answer;
  EXPECT_NE(r.back().answer.find(" /0.00 @:0"), std::string::npos) << r.back().answer;
}

// M220: a feed move's F times the percent; M203: the axis's top rate.
TEST(PrinterCodes, FeedOverrideAndTopRateSetTheCruise) {
  struct Case {
    std::vector<std::string> lines;
    double mm_per_s;
  };
  const Case cases[] = {{{"G91", "M220 S50", "G1 X5 F1200"}, 10},
                        {{"G91", "M220 S200", "G1 X5 F600"}, 20},
                        {{"G91", "M220 S10", "G1 X1 F1200"}, 2},
                        {{"G91", "M203 X5", "G1 X5 F6000"}, 5},
                        {{"G91", "M203 X5", "M220 S500", "G1 X5 F300"}, 5},
                        {{"G91", "G1 X5 F1200"}, 20}};
  for (const Case& c : cases) {
    auto m = simtest::run("m32", c.lines, 10);
    const std::vector<uint64_t>& x = m->axis('X')->step_cycles;
    const double expected = kHz / (c.mm_per_s * 1000);
    const uint64_t got = cruise_interval(x);
    std::printf("%s: cruise %llu cycles a step, %.0f expected\n", c.lines.back().c_str(), (unsigned long long)got,
                expected);
    EXPECT_NEAR(double(got), expected, expected * 0.01) << c.lines[1];
    EXPECT_GE(double(m->axis('X')->min_interval()), expected * 0.99) << c.lines[1];
  }
}

// From rest at constant acceleration a (steps/s^2), step n comes at
// sqrt(2 n / a): t seconds after the first step, n = a (t + sqrt(2 / a))^2
// / 2 (each run is checked where it still accelerates).
TEST(PrinterCodes, AccelerationLimitsShapeTheRamp) {
  struct Case {
    std::vector<std::string> lines;
    char axis;
    double accel, t;  // mm/s^2, s
  };
  const Case cases[] = {
      {{"G91", "G1 X10 F2400"}, 'X', 500, 0.07},                      // the board's own
      {{"G91", "M201 X100", "G1 X10 F2400"}, 'X', 100, 0.3},          // the axis's
      {{"G91", "M204 T250", "G1 X10 F2400"}, 'X', 250, 0.15},         // travel
      {{"G91", "M204 P100 T400", "G1 X10 E1 F2400"}, 'X', 100, 0.3},  // print: P
      {{"G91", "M204 P100 T400", "G1 X10 F2400"}, 'X', 400, 0.09},    // travel: T
      {{"G91", "M204 S150", "G1 X10 E1 F2400"}, 'X', 150, 0.25},      // S: print
      {{"G91", "M204 P300 R50", "G1 E2 F2400"}, 'E', 50, 0.2},        // the extruder alone: R
      {{"G91", "M201 X100", "M204 S400", "G1 X10 F2400"}, 'X', 100, 0.3},  // the lower of the two
  };
  for (const Case& c : cases) {
    auto m = simtest::run("m32", c.lines, 10);
    const size_t n = steps_within(m->axis(c.axis)->step_cycles, c.t);
    const double a = c.accel * 1000, t = c.t + std::sqrt(2 / a);
    const double expected = 0.5 * a * t * t;
    std::printf("%s after %s: %zu steps in %.2f s, %.0f at %.0f mm/s^2\n", c.lines.back().c_str(),
                c.lines[c.lines.size() - 2].c_str(), n, c.t, expected, c.accel);
    EXPECT_NEAR(double(n), expected, expected * 0.01) << c.lines.back() << " after " << c.lines[1];
  }
}

// M205 J: a right angle's corner speed. The junction's acceleration is
// 500 sqrt(2) mm/s^2 (each axis's 500 over its share of the turn), and
// v^2 = a J (2 sqrt(S) + S) / sqrt(D) with S = D = 2 (core/motion/
// path_planner.h): 1.55 mm/s at J 0.001 mm, 4.9 at 0.01, the feed (40) at 1.
// The slowest step around the corner (X's last 20, Y's first 20) runs at
// the corner speed, within the step generator's runs of equal intervals.
TEST(PrinterCodes, JunctionDeviationSetsTheCornerSpeed) {
  for (const double j : {0.001, 0.01, 1.0}) {
    char code[24];
    std::snprintf(code, sizeof code, "M205 J%g", j);
    auto m = simtest::run("m32", {code, "G91", "G1 X10 F2400", "G1 Y10"}, 10);
    const std::vector<uint64_t>& x = m->axis('X')->step_cycles;
    const std::vector<uint64_t>& y = m->axis('Y')->step_cycles;
    ASSERT_EQ(x.size(), 10000u);
    ASSERT_EQ(y.size(), 10000u);
    uint64_t slowest = y.front() - x.back();
    for (size_t i = x.size() - 20; i < x.size(); ++i) slowest = std::max(slowest, x[i] - x[i - 1]);
    for (size_t i = 1; i < 20; ++i) slowest = std::max(slowest, y[i] - y[i - 1]);
    const double measured = kHz / double(slowest) / 1000;
    const double v = std::min(40.0, std::sqrt(500 * std::sqrt(2.0) * j * (2 * std::sqrt(2.0) + 2) / std::sqrt(2.0)));
    std::printf("%s: the slowest step at the corner %.2f mm/s, the junction's %.2f\n", code, measured, v);
    EXPECT_NEAR(measured, v, v * 0.25) << code;
  }
}

// M221: each E move's steps are its distance's times the flow, rounded half
// away from zero; the program position (M114's E) stays the program's.
TEST(PrinterCodes, FlowScalesTheExtruderStepsExactly) {
  auto m = simtest::run("m32", {"M221 S95", "G1 E10 F600", "M221 S133", "G1 E10.0015", "M221 S100", "G1 E20",
                                "M83", "M221 S250", "G1 E-0.4005", "M400", "M114"},
                        20);
  // The unflowed steps of each move: 10000; round(10001.5) - 10000 = 2;
  // 20000 - 10002 = 9998; round(19599.5) - 20000 = -400 (E at 19.5995 mm).
  // Flowed: 9500; round(2.66) = 3; 9998; -1000.
  const long e = 9500 + 3 + 9998 - 1000;
  EXPECT_EQ(long(m->axis('E')->steps()), e);
  const std::vector<std::string> msgs = m->serial().messages();
  ASSERT_FALSE(msgs.empty());
  EXPECT_NE(msgs.back().find("E:19.5995"), std::string::npos) << msgs.back();
  EXPECT_NE(msgs.back().find("Count X:0 Y:0 Z:0 E:" + std::to_string(e)), std::string::npos) << msgs.back();
}
