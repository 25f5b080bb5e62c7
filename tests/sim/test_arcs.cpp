// G2/G3 on the real m32-cnc image (1000 steps/mm): full circles both ways, R
// arcs short and long, a helix, an arc in G18 and one with the extruder,
// each separated by a dwell so its steps can be told apart. Every arc ends
// exactly on its end point; every stepped point (the edges of one step
// event taken together) lies within the chords' bound of the programmed
// circle (core/motion/arc_chords.h: half a step for a chord end, the sag of
// a quarter step, half a step of LineDda); a full circle runs at its feed
// from end to end of its cruise, not stop-and-go, with no starvation.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

constexpr double kTick = 16000000.0;
constexpr int kAxes = 4;
const char kNames[kAxes] = {'X', 'Y', 'Z', 'E'};

struct Point {
  uint64_t cycle;
  int64_t at[kAxes];
};

// Every axis's edges merged by time; edges within kEventCycles of the first
// of a group are one step event (a king move is one point, not two).
constexpr uint64_t kEventCycles = 100;
std::vector<Point> path_points(const sim::Machine& m) {
  struct Edge {
    uint64_t cycle;
    int axis, delta;
  };
  std::vector<Edge> edges;
  for (int i = 0; i < kAxes; ++i) {
    const sim::AxisTrace* a = m.axis(kNames[i]);
    for (size_t k = 0; k < a->step_cycles.size(); ++k) edges.push_back({a->step_cycles[k], i, a->step_deltas[k]});
  }
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.cycle < b.cycle; });
  std::vector<Point> out;
  Point p{0, {0, 0, 0, 0}};
  uint64_t group = 0;
  for (size_t k = 0; k < edges.size(); ++k) {
    if (k == 0 || edges[k].cycle - group > kEventCycles) {
      if (k) out.push_back(p);
      group = edges[k].cycle;
      p.cycle = group;
    }
    p.at[edges[k].axis] += edges[k].delta;
  }
  if (!edges.empty()) out.push_back(p);
  return out;
}

// Runs of points separated by a pause of more than 20 ms (the dwells).
std::vector<std::vector<Point>> moves(const std::vector<Point>& pts) {
  std::vector<std::vector<Point>> out;
  for (size_t k = 0; k < pts.size(); ++k) {
    if (k == 0 || pts[k].cycle - pts[k - 1].cycle > uint64_t(0.02 * kTick)) out.emplace_back();
    out.back().push_back(pts[k]);
  }
  return out;
}

struct Arc {
  std::string line;
  int a, b;            // plane axes
  double ca, cb, r;    // centre and radius, steps
  int64_t end[kAxes];  // steps
};

}  // namespace

TEST(Arcs, EveryArcEndsOnItsPointAndEveryStepStaysNearItsCircle) {
  // Start at (10, 0); centres and radii in mm.
  const std::vector<Arc> arcs = {
      {"G2 X10 Y0 I-10 J0 F1200", 0, 1, 0, 0, 10000, {10000, 0, 0, 0}},        // full circle, clockwise
      {"G3 X10 Y0 I-10 J0", 0, 1, 0, 0, 10000, {10000, 0, 0, 0}},              // full circle, counter-clockwise
      {"G3 X0 Y10 R10", 0, 1, 0, 0, 10000, {0, 10000, 0, 0}},                  // quarter, R: the short way
      {"G2 X10 Y0 R-10", 0, 1, 10000, 10000, 10000, {10000, 0, 0, 0}},         // 270 degrees, R < 0: the long way
      {"G2 X20 Y0 Z-1 I5 J0", 0, 1, 15000, 0, 5000, {20000, 0, -1000, 0}},     // half a helix
      {"G18 G3 X23 Z-1 I1.5 K0", 2, 0, -1000, 21500, 1500, {23000, 0, -1000, 0}},  // G18: Z X plane
      {"G17 G3 X20 Y0 I-1.5 J0 E2.5", 0, 1, 21500, 0, 1500, {20000, 0, -1000, 2500}},  // with the extruder
  };
  std::vector<std::string> lines = {"G21 G90 M82 G17", "G0 X10 Y0", "G4 P0.05"};
  for (const Arc& a : arcs) {
    lines.push_back(a.line);
    lines.push_back("G4 P0.05");
  }
  auto m = simtest::run("m32-cnc", lines, 60);
  EXPECT_TRUE(m->serial().errors().empty()) << m->serial().errors().front();
  EXPECT_EQ(m->starvations(), 0);

  const std::vector<std::vector<Point>> runs = moves(path_points(*m));
  ASSERT_EQ(runs.size(), arcs.size() + 1);  // the G0, then one run per arc
  double worst = 0;
  unsigned long points = 0, over_one = 0;
  for (size_t k = 0; k < arcs.size(); ++k) {
    const Arc& a = arcs[k];
    const std::vector<Point>& run = runs[k + 1];
    for (int i = 0; i < kAxes; ++i) EXPECT_EQ(run.back().at[i], a.end[i]) << a.line << " axis " << kNames[i];
    double arc_worst = 0;
    for (const Point& p : run) {
      const double d = std::fabs(std::hypot(p.at[a.a] - a.ca, p.at[a.b] - a.cb) - a.r);
      arc_worst = std::max(arc_worst, d);
      over_one += d > 1;
    }
    points += run.size();
    std::printf("%-28s %6zu events, worst %.3f step from the circle\n", a.line.c_str(), run.size(), arc_worst);
    // Chord end 0.51 + sag 0.25 (a little more: ends half a step along the arc lengthen a
    // chord) + LineDda's minor axis 0.5 (docs/interpolation.md).
    EXPECT_LE(arc_worst, 0.51 + 0.25 * (1 + 2 / std::sqrt(2 * a.r * 0.25)) + 0.5) << a.line;
    worst = std::max(worst, arc_worst);
  }
  std::printf("arcs on the m32-cnc: %lu events, worst %.3f step from the circle, %.3f %% beyond 1 step\n", points, worst,
              100.0 * over_one / points);
  // The R arcs' centre and the chords' float arithmetic are the deepest stack
  // of the G-code path: it must stay clear of the static data.
  std::printf("stack %u of %u free bytes\n", m->stack_bytes(), m->free_ram());
  EXPECT_LT(m->stack_bytes(), m->free_ram());
}

TEST(Arcs, AFullCircleRunsAtItsFeedWithoutStopping) {
  // r = 10 mm at 1200 mm/min: 20 mm/s along the arc, accelerating at
  // 500 mm/s^2 (0.04 s) at both ends. Over every 50 ms window of the
  // cruise, the distance covered (the chord of the window's ends, 0.02 %
  // short of the arc) is the feed within 1 %; the whole circle takes its
  // length over the feed plus one acceleration time, within 1 %.
  auto m = simtest::run("m32-cnc", {"G21 G90 G17", "G2 X0 Y0 I10 J0 F1200"}, 30);
  EXPECT_EQ(m->starvations(), 0);
  const std::vector<Point> pts = path_points(*m);
  ASSERT_GT(pts.size(), 1000u);
  const double total = double(pts.back().cycle - pts.front().cycle) / kTick;
  const double expect = 2 * M_PI * 10 / 20 + 20.0 / 500;
  std::printf("full circle r 10 mm at 20 mm/s: %.4f s (length / feed + v / a = %.4f s)\n", total, expect);
  EXPECT_NEAR(total, expect, expect * 0.01);
  const uint64_t window = uint64_t(0.05 * kTick), begin = pts.front().cycle + uint64_t(0.1 * kTick),
                 end = pts.back().cycle - uint64_t(0.1 * kTick);
  double slowest = 1e9, fastest = 0;
  size_t j = 0;
  for (size_t i = 0; i < pts.size() && pts[i].cycle + window < end; ++i) {
    if (pts[i].cycle < begin) continue;
    while (j < pts.size() && pts[j].cycle < pts[i].cycle + window) ++j;
    const double mm = std::hypot(double(pts[j].at[0] - pts[i].at[0]), double(pts[j].at[1] - pts[i].at[1])) / 1000;
    const double v = mm / (double(pts[j].cycle - pts[i].cycle) / kTick);
    slowest = std::min(slowest, v);
    fastest = std::max(fastest, v);
  }
  std::printf("cruise speed over 50 ms windows: %.3f .. %.3f mm/s\n", slowest, fastest);
  EXPECT_GT(slowest, 20 * 0.99);
  EXPECT_LT(fastest, 20 * 1.01);
  EXPECT_EQ(m->axis('X')->steps(), 0.0);
  EXPECT_EQ(m->axis('Y')->steps(), 0.0);
}

TEST(Arcs, AnArcFasterThanItsChordsArriveSlowsDownWithoutStarving) {
  // r = 1 mm at 3000 mm/min needs about 1100 chords a second (45 um each
  // at a quarter step of sag): more than the main loop computes and plans.
  // The path runs at the pace they come, its look-ahead dry, the queue
  // never empty under a block that ends at speed, and the circle closes.
  auto m = simtest::run("m32-cnc", {"G21 G90 G17", "G2 X0 Y0 I1 J0 F3000"}, 30);
  EXPECT_EQ(m->starvations(), 0);
  EXPECT_TRUE(m->serial().errors().empty());
  const std::vector<Point> pts = path_points(*m);
  ASSERT_GT(pts.size(), 100u);
  const double seconds = double(pts.back().cycle - pts.front().cycle) / kTick;
  std::printf("full circle r 1 mm asked at 50 mm/s: %.3f s, %.1f mm/s\n", seconds, 2 * M_PI / seconds);
  EXPECT_EQ(m->axis('X')->steps(), 0.0);
  EXPECT_EQ(m->axis('Y')->steps(), 0.0);
}

TEST(Arcs, IllFormedArcsAreRefusedAndChangeNothing) {
  // Each refusal answered once (the reason, then grbl's number), nothing
  // moves, the two reports agree; the printer's image (m32) has no arcs at
  // all.
  struct Bad {
    std::string line, reason, answer;
  };
  const std::vector<Bad> bad = {
      {"G2 X3 Y2 I5 J0", "arc end point not on the circle", "error:33"},
      {"G3 X3 Y2", "arc needs R or the plane's I/J/K", "error:35"},
      {"G2 X1 Y2 R3", "R arc cannot end where it starts", "error:33"},
      {"G2 X1 Y2 I0 J0", "arc radius is zero", "error:34"},
  };
  std::vector<std::string> lines = {"G21 G90", "G1 X1 Y2 F600", "WAIT", "M114"};
  for (const Bad& b : bad) lines.push_back(b.line);
  lines.push_back("M114");
  auto m = simtest::run("m32-cnc", lines, 20);
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), lines.size());
  for (size_t i = 0; i < bad.size(); ++i) {
    EXPECT_EQ(r[4 + i].answer, bad[i].answer) << bad[i].line;
    EXPECT_EQ(r[4 + i].reason, bad[i].reason) << bad[i].line;
  }
  std::vector<std::string> msgs;  // the reports (each refusal's reason is a line too)
  for (const std::string& l : m->serial().messages())
    if (l.rfind("X:", 0) == 0) msgs.push_back(l);
  ASSERT_EQ(msgs.size(), 2u);
  EXPECT_EQ(msgs[0], msgs[1]);
  EXPECT_EQ(m->axis('X')->steps(), 1000.0);
  auto printer = simtest::run("m32", {"G2 X3 Y2 I1 J0 F600"}, 5);
  EXPECT_EQ(printer->serial().responses().at(0).answer, "Error:G2/G3 arcs are not in this board's image");
}
