// The G-code path on the real m32 image (firmware/engine/path.h): a polyline
// runs through its vertices, every event of every block falls within half
// an event of the ideal constant-acceleration motion of its planned profile,
// and every axis ends on its rounded target; and what a line costs to parse
// and plan, and how many blocks a second one line in flight delivers.
//
// The plan is replayed on the host with the same look-ahead core
// (core/motion/path_planner.h): the lines here reach the board faster than
// the motion runs, so the firmware takes each block with its ring full (or
// with every remaining block at the end), and the host does the same. The
// ideal motion of a planned block is written out below in closed form,
// independently of the chip's profile generator (core/motion/trapezoid.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "../../core/motion/path_planner.h"
#include "sim_fixture.h"

namespace {

constexpr double kTick = 16000000.0;  // the m32's step timer
constexpr uint8_t kAxes = 4;          // X Y Z E
constexpr uint8_t kRing = 5;          // board::kPathBlocks
constexpr double kStepsPerMm = 1000.0;

using Block = am::PathBlock<kAxes>;

// The m32's axis table as firmware/engine/path.cpp builds it: kMaxStepRate,
// kDefaultAccel (500 mm/s^2).
const am::PathAxis kTable[kAxes] = {
    {1.0f, 40000.0f, 500000.0f, true}, {1.0f, 40000.0f, 500000.0f, true}, {1.0f, 40000.0f, 500000.0f, true},
    {1.0f, 40000.0f, 500000.0f, false}};

struct Line {
  std::string text;
  int32_t steps[kAxes];
  float delta_mm[kAxes];
  float feed;
};

// XY moves in 1/10000 mm, absolute, all at one feed (mm/min).
std::vector<Line> polyline(const std::vector<std::pair<int32_t, int32_t>>& points, int feed) {
  std::vector<Line> out;
  int32_t x = 0, y = 0;
  for (const auto& p : points) {
    Line l{};
    char buf[96];
    std::snprintf(buf, sizeof buf, "G1 X%.4f Y%.4f F%d", p.first / 10000.0, p.second / 10000.0, feed);
    l.text = buf;
    // 1000 steps/mm: a coordinate of 1/10000 mm rounds to steps (half away from zero).
    auto steps = [](int32_t c) { return c < 0 ? -((-c + 5) / 10) : (c + 5) / 10; };
    l.steps[0] = steps(p.first) - steps(x);
    l.steps[1] = steps(p.second) - steps(y);
    l.delta_mm[0] = float(p.first - x) * 1e-4f;
    l.delta_mm[1] = float(p.second - y) * 1e-4f;
    l.feed = float(feed * 10000) * 1e-4f;
    x = p.first;
    y = p.second;
    out.push_back(l);
  }
  return out;
}

// The blocks in the order the firmware takes them, each as planned then.
std::vector<Block> replay(const std::vector<Line>& lines) {
  static am::PathPlanner<kAxes, kRing> plan(kTable, 0.01f, 40000.0f);
  plan.clear();
  std::vector<Block> taken;
  auto take = [&] {
    taken.push_back(*plan.take());
    plan.done();
  };
  for (const Line& l : lines) {
    using Plan = am::PathPlanner<kAxes, kRing>;
    EXPECT_EQ(plan.add(l.steps, l.delta_mm, l.feed, false), Plan::Status::queued);
    if (plan.full()) take();
  }
  while (!plan.empty()) take();
  return taken;
}

// Ideal motion of one block: x(t) in events, t in seconds from its start.
struct Ideal {
  double v0, vp, v1, a, da, dc, t1, t2, T, n;

  explicit Ideal(const Block& b) : a(b.accel), n(b.events) {
    const double vc = kTick / std::ceil(kTick / double(b.cruise));  // whole-tick cruise
    v0 = std::min<double>(b.entry, vc);
    v1 = std::min<double>(b.exit, vc);
    if (v0 * v0 > v1 * v1 + 2 * a * n) v1 = std::sqrt(v0 * v0 - 2 * a * n);
    if (v1 * v1 > v0 * v0 + 2 * a * n) v1 = std::sqrt(v0 * v0 + 2 * a * n);
    vp = std::min(vc, std::sqrt(a * n + (v0 * v0 + v1 * v1) / 2));
    vp = std::max(vp, std::max(v0, v1));
    da = (vp * vp - v0 * v0) / (2 * a);
    dc = std::max(0.0, n - da - (vp * vp - v1 * v1) / (2 * a));
    t1 = (vp - v0) / a;
    t2 = t1 + dc / vp;
    T = t2 + (vp - v1) / a;
  }
  double x(double t) const {
    if (t <= t1) return v0 * t + a * t * t / 2;
    if (t <= t2) return da + vp * (t - t1);
    if (t <= T) {
      const double u = t - t2;
      return da + dc + vp * u - a * u * u / 2;
    }
    return n + v1 * (t - T);
  }
};

int dominant(const Block& b) {
  int d = 0;
  for (int i = 1; i < kAxes; ++i)
    if (std::abs(b.steps[i]) > std::abs(b.steps[d])) d = i;
  return d;
}

struct Check {
  double worst = 0;      // |e - x(t_e)|, events
  double min_vertex = 1e9;  // slowest inner vertex: events/s of the block after it, from its first interval
};

// Walks the recorded steps block by block: every event against its block's
// ideal motion, anchored at the previous block's last event (the first
// block at its own first event).
Check check_blocks(const sim::Machine& m, const std::vector<Block>& blocks, double slack_cycles) {
  Check c;
  const char names[kAxes] = {'X', 'Y', 'Z', 'E'};
  size_t used[kAxes] = {};
  double anchor = -1;
  for (size_t k = 0; k < blocks.size(); ++k) {
    const Block& b = blocks[k];
    const int d = dominant(b);
    const std::vector<uint64_t>& st = m.axis(names[d])->step_cycles;
    EXPECT_GE(st.size(), used[d] + b.events);
    if (st.size() < used[d] + b.events) return c;
    const Ideal ideal(b);
    // The first block starts from rest: its first event is sqrt(2 / a) in.
    if (anchor < 0) anchor = double(st[used[d]]) - std::sqrt(2.0 / ideal.a) * kTick;
    // The speed through the vertex, from the edges: the first interval.
    if (k > 0 && k + 1 < blocks.size()) c.min_vertex = std::min(c.min_vertex, kTick / (double(st[used[d]]) - anchor));
    for (uint32_t e = 1; e <= b.events; ++e) {
      const double t = (double(st[used[d] + e - 1]) - anchor) / kTick;
      // The edges' latency spread, in events at the block's top speed.
      const double err = std::fabs(double(e) - ideal.x(t)) - slack_cycles / kTick * ideal.vp;
      c.worst = std::max(c.worst, err);
    }
    anchor = double(st[used[d] + b.events - 1]);
    for (int i = 0; i < kAxes; ++i) used[i] += size_t(std::abs(b.steps[i]));
  }
  return c;
}

// A circle of `n` chords of radius `r` (1/10000 mm) around (-r, 0), from
// and back to the origin.
std::vector<std::pair<int32_t, int32_t>> circle(int n, int32_t r) {
  std::vector<std::pair<int32_t, int32_t>> pts;
  for (int k = 1; k <= n; ++k) {
    const double a = 2 * M_PI * k / n;
    pts.push_back({int32_t(std::lround(r * std::cos(a) - r)), int32_t(std::lround(r * std::sin(a)))});
  }
  return pts;
}

// Runs the polyline on the m32, checks every event against its planned
// profile and the end on the start point, and returns the figures.
Check run_polyline(const std::vector<Line>& lines, double budget_s, double& motion_s) {
  std::vector<std::string> text;
  for (const Line& l : lines) text.push_back(l.text);
  auto m = simtest::run("m32", text, budget_s);
  const std::vector<Block> blocks = replay(lines);
  EXPECT_EQ(blocks.size(), lines.size());
  const Check c = check_blocks(*m, blocks, 48);
  EXPECT_EQ(m->axis('X')->steps(), 0.0);
  EXPECT_EQ(m->axis('Y')->steps(), 0.0);
  const auto& x = m->axis('X')->step_cycles;
  const auto& y = m->axis('Y')->step_cycles;
  motion_s = x.empty() || y.empty() ? 0 : double(std::max(x.back(), y.back()) - std::min(x[0], y[0])) / kTick;
  // The lines arrive faster than the motion needs them: the queue never
  // runs dry under a block.
  EXPECT_EQ(m->starvations(), 0);
  std::printf("stack %u bytes\n", m->stack_bytes());
  return c;
}

}  // namespace

TEST(Path, APolylineRunsThroughItsVerticesOnItsExactProfile) {
  // A 60-gon of radius 4.8 mm (0.5 mm chords) at 600 mm/min.
  double motion_s = 0;
  const Check c = run_polyline(polyline(circle(60, 48000), 600), 30, motion_s);
  std::printf("60-gon: worst event error %.3f, slowest inner vertex %.0f events/s\n", c.worst, c.min_vertex);
  EXPECT_LE(c.worst, 0.5);
  EXPECT_GT(c.min_vertex, 1000.0);
}

TEST(Path, ShortChordsStreamWithoutStoppingAtAVertex) {
  // 314 chords of 0.1 mm (a circle of radius 5 mm) at 480 mm/min: 80
  // blocks/s, within what one line in flight at 115200 baud with its parse
  // and plan delivers (about 120 blocks/s: a faster feed runs at that pace,
  // its look-ahead dry). Every event on its profile, no vertex a stop.
  double motion_s = 0;
  const Check c = run_polyline(polyline(circle(314, 50000), 480), 60, motion_s);
  std::printf("0.1 mm chords: %.0f blocks/s, worst event error %.3f, slowest inner vertex %.0f events/s\n",
              314 / motion_s, c.worst, c.min_vertex);
  EXPECT_LE(c.worst, 0.5);
  // A stop would start its next block from rest: sqrt(a / 2) = 500 events/s
  // for its first interval.
  EXPECT_GT(c.min_vertex, 2000.0);
}

TEST(Path, ParseAndPlanCyclesPerSlicerLine) {
  // Five lines of a slicer's kind on an idle m32 (the ring of 5 holds them all,
  // the first block waits for its start): the time from a line's first byte
  // to its answer, less the bytes' own time on the wire (the line, its end,
  // and "ok\n"), is what the firmware spends parsing and planning it.
  const std::vector<std::string> lines = {"G1 X110.956 Y98.211 E2.0151 F1800", "G1 X111.402 Y98.705 E2.0372",
                                          "G1 X111.953 Y99.012 E2.0593", "G1 X112.361 Y99.668 E2.0814",
                                          "G1 X112.617 Y100.150 E2.1035"};
  auto m = simtest::run("m32", lines, 30);
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), lines.size());
  const double byte_cycles = 10.0 * m->f_cpu() / 115200;
  std::vector<double> cycles;
  for (const sim::Response& x : r) {
    ASSERT_EQ(x.answer, "ok") << x.line;
    cycles.push_back(double(x.answer_cycle - x.sent_cycle) - (x.line.size() + 4) * byte_cycles);
  }
  std::sort(cycles.begin(), cycles.end());
  std::printf("parse + plan of a slicer line: %.0f cycles (median of %zu; %.0f..%.0f), %.0f lines/s of CPU\n",
              cycles[cycles.size() / 2], cycles.size(), cycles.front(), cycles.back(),
              m->f_cpu() / cycles[cycles.size() / 2]);
  EXPECT_GT(cycles.front(), 0.0);
  // The motion afterwards: X to 112.617 mm at 1000 steps/mm.
  EXPECT_EQ(m->axis('X')->steps(), 112617.0);
}

TEST(Path, AFeedBeyondTheStreamRunsAtTheStreamsPace) {
  // The same 0.1 mm chords at 2400 mm/min need 400 blocks/s: more than one
  // line in flight at 115200 baud delivers with the motion running. The
  // look-ahead runs dry and the path slows to what arrives (each block
  // planned to stop where its successor has not arrived yet); every step is
  // still made and the circle closes.
  std::vector<std::string> text;
  for (const Line& l : polyline(circle(314, 50000), 2400)) text.push_back(l.text);
  auto m = simtest::run("m32", text, 60);
  const auto& x = m->axis('X')->step_cycles;
  ASSERT_FALSE(x.empty());
  const double motion_s = double(x.back() - x.front()) / kTick;
  std::printf("0.1 mm chords asked at 400 blocks/s: %.0f blocks/s, %d starvations\n", 314 / motion_s,
              m->starvations());
  EXPECT_TRUE(m->serial().errors().empty());
  // Dry, but never dead: no block that ends at speed finds the queue empty.
  EXPECT_EQ(m->starvations(), 0);
  EXPECT_EQ(m->axis('X')->steps(), 0.0);
  EXPECT_EQ(m->axis('Y')->steps(), 0.0);
}

TEST(Path, MinorAxesAreSmoothedAtLowRates) {
  // G1 X1 Y0.7 at 12 mm/min: X at about 164 steps/s, Y at 115. Without
  // smoothing Y could step only on X's events, up to one X interval after
  // the straight line crosses its step. Smoothed (core/motion/amass.h: level
  // 3 at this rate, 8 events per X step) every Y step k comes at the first
  // event after the line's Y reaches k: never early, at most 1/8 of an X
  // interval late. Measured over the cruise, every step.
  auto m = simtest::run("m32-cnc", {"G1 X1 Y0.7 F12"}, 30);
  const auto& x = m->axis('X')->step_cycles;
  const auto& y = m->axis('Y')->step_cycles;
  ASSERT_EQ(x.size(), 1000u);
  ASSERT_EQ(y.size(), 700u);
  // The cruise: X steps 200..800, every interval the same.
  const double dominant = double(x[800] - x[200]) / 600;
  // Every X interval the cruise's, within the software edges' spread (48 cycles).
  for (size_t k = 201; k <= 800; ++k) ASSERT_NEAR(double(x[k] - x[k - 1]), dominant, 48.0) << "X step " << k;
  double earliest = 1, latest = -1;
  uint64_t shortest = ~0ull, longest = 0;
  for (size_t k = 150; k < 550; ++k) {
    // Y's step k + 1 is due where the line's Y is k + 1: X position
    // (k + 1) * 1000 / 700, X's step e being x[e - 1].
    const double due = double(x[200]) + ((k + 1) * 1000.0 / 700.0 - 201) * dominant;
    const double late = (double(y[k]) - due) / dominant;
    earliest = std::min(earliest, late);
    latest = std::max(latest, late);
    shortest = std::min(shortest, y[k + 1] - y[k]);
    longest = std::max(longest, y[k + 1] - y[k]);
  }
  std::printf("minor axis at %.0f steps/s on a dominant at %.0f: %.3f..%.3f dominant intervals behind the line; "
              "intervals %.2f..%.2f ms (the line's: %.2f)\n",
              16e6 / dominant * 0.7, 16e6 / dominant, earliest, latest, shortest / 16000.0, longest / 16000.0,
              dominant / 0.7 / 16000.0);
  EXPECT_GE(earliest, -0.001);  // 0.001 interval: 98 cycles, twice the software edges' spread
  EXPECT_LT(latest, 0.126);
  EXPECT_EQ(m->axis('X')->steps(), 1000.0);
  EXPECT_EQ(m->axis('Y')->steps(), 700.0);
}

TEST(Path, DirectionsFlipAtSpeedWithTheDriversSetUpTime) {
  // A zig-zag: X runs on while Y reverses at every vertex, at the junction
  // speed (a 23 degree turn), so Y's DIR line changes with the machine
  // moving. Every Y step must follow its DIR change by a DRV8825's 650 ns,
  // no step of either axis may come faster than the board's 40 kHz (less
  // the software edges' spread of 48 cycles), and the path ends on its
  // target.
  std::vector<std::pair<int32_t, int32_t>> pts;
  for (int k = 1; k <= 40; ++k) pts.push_back({k * 10000, (k % 2) * 2000});
  std::vector<std::string> text;
  for (const Line& l : polyline(pts, 2400)) text.push_back(l.text);
  sim::Machine m(simtest::image("m32"));
  const auto& dir = m.watch_pin('C', 3);  // Y's DIR
  for (const std::string& l : text) m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(30) * m.f_cpu()), sim::RunEnd::done);
  const auto& y = m.axis('Y')->step_cycles;
  const uint64_t setup = (uint64_t(m.f_cpu()) * 650 + 999999999) / 1000000000;
  size_t d = 0, flips_under_way = 0;
  uint64_t least = ~0ull;  // shortest DIR change to step, cycles
  for (size_t k = 0; k < y.size(); ++k) {
    while (d < dir.size() && dir[d].cycle <= y[k]) ++d;
    if (d > 0) {
      EXPECT_GE(y[k] - dir[d - 1].cycle, setup) << "Y step " << k;
      least = std::min(least, y[k] - dir[d - 1].cycle);
    }
    // A flip between two steps less than 2 ms apart: made at speed.
    if (k > 0 && d > 0 && dir[d - 1].cycle > y[k - 1] && y[k] - y[k - 1] < m.f_cpu() / 500) ++flips_under_way;
  }
  std::printf("zig-zag: %zu of 39 Y reversals made at speed, DIR set %.1f us before the next step at least\n",
              flips_under_way, least / 16.0);
  EXPECT_GE(flips_under_way, 30u);
  for (char axis : {'X', 'Y'}) {
    const auto& st = m.axis(axis)->step_cycles;
    for (size_t k = 1; k < st.size(); ++k) ASSERT_GE(st[k] - st[k - 1], 400u - 48u) << axis << " step " << k;
  }
  EXPECT_EQ(m.axis('X')->steps(), 40000.0);
  EXPECT_EQ(m.axis('Y')->steps(), 0.0);
  EXPECT_EQ(m.starvations(), 0);
}
