// M114 while the motors move (planner::positions_now, firmware/engine/
// odometer.h): every count it reports is where the pins had the motor
// between the moment the line went out and the moment its answer came back,
// for one-axis moves, coordinated blocks (the interpolator's closed form),
// a polyline of chained blocks and the Uno's timer-pulsed axis, whose fast
// path switches segments by itself. The old report, the position at the end
// of everything queued, lies outside that window until the motion ends.
#include <cstdio>
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

// Steps on the pins up to `cycle`, from the decoded edges (full steps for a
// coil-driven axis, whose decoder counts half steps).
double steps_at(const sim::AxisTrace& a, uint64_t cycle) {
  return double(sim::position_at(a, cycle)) / a.units_per_step;
}

// The "Count X:<n> ..." numbers of an M114 report, in the board's order.
std::vector<double> counts(const std::string& report, const std::string& axes) {
  std::vector<double> out;
  const size_t at = report.find("Count");
  for (char a : axes) {
    const size_t k = report.find(std::string(" ") + a + ":", at);
    out.push_back(k == std::string::npos ? -1e18 : std::stod(report.substr(k + 3)));
  }
  return out;
}

// Runs `lines`; every M114 answer must lie, axis by axis, between the pins'
// positions when the line was sent and when its ok came (a monotonic
// motion). Returns how many reports fell strictly inside a move.
int check_reports(const std::string& image, const std::vector<std::string>& lines, const std::string& axes) {
  auto m = simtest::run(image, lines, 60);
  const std::vector<sim::Response>& r = m->serial().responses();
  const std::vector<std::string> msgs = m->serial().messages();
  EXPECT_EQ(r.size(), lines.size());
  size_t report = 0;
  int moving = 0;
  for (const sim::Response& x : r) {
    if (x.line != "M114") continue;
    EXPECT_LT(report, msgs.size());
    if (report >= msgs.size()) break;
    const std::vector<double> c = counts(msgs[report++], axes);
    bool inside = false;
    for (size_t i = 0; i < axes.size(); ++i) {
      const sim::AxisTrace& a = *m->axis(axes[i]);
      const double lo = steps_at(a, x.sent_cycle), hi = steps_at(a, x.answer_cycle);
      EXPECT_GE(c[i], std::min(lo, hi)) << axes[i] << " in " << msgs[report - 1];
      EXPECT_LE(c[i], std::max(lo, hi)) << axes[i] << " in " << msgs[report - 1];
      inside = inside || (c[i] != steps_at(a, UINT64_MAX) && c[i] != 0);
    }
    moving += inside;
  }
  return moving;
}

std::vector<std::string> with_reports(std::vector<std::string> lines, int reports) {
  for (int i = 0; i < reports; ++i) lines.push_back("M114");
  return lines;
}

}  // namespace

TEST(PositionNow, OneAxisMoveReportsWhereThePinsAre) {
  const int moving = check_reports("m32-cnc", with_reports({"G21 G90", "G1 X20 F1200"}, 40), "XYZE");
  std::printf("one axis: %d of 40 reports inside the move\n", moving);
  EXPECT_GE(moving, 20);
}

TEST(PositionNow, CoordinatedBlocksReportEveryAxisOnItsLine) {
  const int moving =
      check_reports("m32-cnc", with_reports({"G21 G90 M82", "G1 X12 Y-7.5 Z0.25 E3 F900"}, 40), "XYZE");
  std::printf("coordinated: %d of 40 reports inside the move\n", moving);
  EXPECT_GE(moving, 20);
}

TEST(PositionNow, APolylineReportsAcrossItsBlocks) {
  // Monotonic in X and Y, so the window check holds across vertices.
  std::vector<std::string> lines = {"G21 G90"};
  for (int k = 1; k <= 12; ++k)
    lines.push_back("G1 X" + std::to_string(k) + " Y" + std::to_string(2 * k + k % 2) + " F1500");
  const int moving = check_reports("m32-cnc", with_reports(lines, 40), "XY");
  std::printf("polyline: %d of 40 reports inside the motion\n", moving);
  EXPECT_GE(moving, 10);
}

TEST(PositionNow, TheUnosTimerPulsedAxisCountsThroughItsFastPath) {
  // Z at 400 steps/mm, pulsed by the timer; its cruise runs in the assembly
  // fast path, which takes chained segments without the C handler.
  const int moving = check_reports("uno", with_reports({"G21 G90", "G1 Z30 F6000"}, 60), "Z");
  std::printf("Uno Z: %d of 60 reports inside the move\n", moving);
  EXPECT_GE(moving, 20);
}

TEST(PositionNow, TheUnosShieldAxesCountInFullSteps) {
  // X and Y on the shield's latch, 25 full steps per mm, in half steps
  // (M350 2) so a count between full steps shows its decimals.
  // 60 reports: the first of them come in the 50 ms before the move starts
  // (firmware/engine/path.h), and a report of two shield axes and Z is short.
  const int moving = check_reports("uno", with_reports({"G21 G90", "M350 X2 Y2", "G1 X6 Y4 F300"}, 60), "XY");
  std::printf("Uno X Y: %d of 60 reports inside the move\n", moving);
  EXPECT_GE(moving, 20);
}
