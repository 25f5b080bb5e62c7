// The lathe image's passes beyond one plain thread: engaging a turning
// spindle with the acceleration bound, a spindle reversal on the same helix,
// multi-start passes on their phases, a pass's end, the limit switch, and
// the lines it refuses (nothing moves).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "lathe_rig.h"

namespace {

using simtest::field;
using simtest::LatheRig;

sim::SpindleParams quadrature(std::vector<sim::RpmPoint> profile) {
  sim::SpindleParams p;
  p.lines = 600;
  p.quadrature = true;
  p.profile = profile;
  return p;
}

sim::ThreadSpec spec(int64_t um, int64_t counts, int starts = 1, int start = 0) {
  sim::ThreadSpec t{um, 1};
  t.counts_per_turn = counts;
  t.starts = starts;
  t.start = start;
  return t;
}

// Sends a pass on the 2400-count encoder, runs `seconds`, checks every count.
sim::PassResult quadrature_pass(LatheRig& rig, const std::string& g33, int64_t um, double seconds) {
  EXPECT_EQ(rig.send(g33), "ok");
  const uint64_t armed = rig.armed_after();
  rig.run_for(seconds);
  return sim::check_pass(*rig.spindle, rig.z(), *rig.step, spec(um, 2400), 0, armed, rig.m->cycles());
}

// The spindle turns at 600 rpm before the pass: the carriage waits for the
// index, then for the target to pass it, catches up at most at the board's
// acceleration (20000 steps/s^2) and locks; from then every count is exact.
TEST(LathePasses, EngagesARunningSpindleWithBoundedAcceleration) {
  LatheRig rig(quadrature({{0, 600}}));
  ASSERT_EQ(rig.send("ENCODER C600 E4"), "ok");
  rig.run_for(0.3);
  const sim::PassResult r = quadrature_pass(rig, "G33 Z-500 K1.5", 1500, 3);
  ASSERT_TRUE(r.index_found);
  ASSERT_TRUE(r.locked);
  EXPECT_EQ(r.mismatches, 0u);
  EXPECT_EQ(r.position, r.expected);
  const uint64_t f = rig.m->f_cpu();
  const uint64_t lock_cycle = r.index_cycle + r.lock_cycles;
  // The paced steps before the lock: none before the index; the speed over
  // 20 ms windows changes by at most the acceleration (plus one step per
  // window of counting error each side).
  const auto& c = rig.z().step_cycles;
  ASSERT_FALSE(c.empty());
  EXPECT_GT(c.front(), r.index_cycle);
  const uint64_t window = f / 50;
  std::vector<double> speed;
  for (uint64_t w = c.front(); w + window <= lock_cycle; w += window) {
    const size_t n = size_t(std::lower_bound(c.begin(), c.end(), w + window) - std::lower_bound(c.begin(), c.end(), w));
    speed.push_back(double(n) * 50);
  }
  ASSERT_GT(speed.size(), 10u);
  double worst = 0;
  for (size_t k = 1; k < speed.size(); ++k) worst = std::max(worst, std::fabs(speed[k] - speed[k - 1]) * 50);
  const double slack = 2 * 50 * 50;  // one step per window, each side
  EXPECT_LE(worst, 20000 + slack);
  std::printf("catch-up: locked %.3f s after the index, %lld steps of lead-in, speed change at most %.0f steps/s^2 "
              "(20 ms windows), every one of %zu counts exact after\n",
              double(r.lock_cycles) / f, (long long)sim::position_at(rig.z(), lock_cycle), worst,
              r.counts - r.locked_after);
  EXPECT_EQ(field(rig.status(), "err"), "0");
}

TEST(LathePasses, SpindleReversalKeepsThePhase) {
  LatheRig rig(quadrature({{0.2, 0}, {0.5, 300}, {2.0, 300}, {2.6, -300}, {4.0, -300}, {4.6, 200}, {5.2, 200}, {5.5, 0}}));
  ASSERT_EQ(rig.send("ENCODER C600 E4"), "ok");
  const sim::PassResult r = quadrature_pass(rig, "G33 Z-200 K2", 2000, 5.8);
  ASSERT_TRUE(r.locked);
  EXPECT_EQ(r.mismatches, 0u);
  EXPECT_EQ(r.position, r.expected);
  // It did go back and forth after the lock: a net count well below the
  // counts walked.
  EXPECT_LT(r.s_end, int64_t(r.counts) / 2);
  const std::string st = rig.status();
  EXPECT_EQ(field(st, "state"), "locked") << st;
  EXPECT_EQ(field(st, "lost"), "0") << st;
  EXPECT_EQ(field(st, "z"), std::to_string(rig.z().position)) << st;
  std::printf("reversal: %zu counts walked, net %lld, carriage %lld = floor(lambda s)\n", r.counts,
              (long long)r.s_end, (long long)r.position);
}

// Three starts of 0.5 mm pitch (1.5 mm lead) on the seed's 40-slot disc
// (the phase 40/3 counts is not a whole count) and on the quadrature
// encoder: each pass returns to the same base and ends 10 mm on, on its own
// helix: floor(-lambda (s - k C / 3)).
TEST(LathePasses, MultiStartPassesLandOnTheirExactPhase) {
  for (const bool quad : {false, true}) {
    sim::SpindleParams p;
    p.lines = quad ? 600 : 40;
    p.quadrature = quad;
    p.profile = {{0, quad ? 200.0 : 120.0}};
    LatheRig rig(p);
    const int64_t counts = quad ? 2400 : 40;
    ASSERT_EQ(rig.send(quad ? "ENCODER C600 E4" : "ENCODER C40 E1"), "ok");
    ASSERT_EQ(rig.send("G0 Z1"), "ok");
    ASSERT_TRUE(rig.wait_idle(2));
    const int64_t base = rig.z().position;
    const int64_t end = base - 2520;  // 10 mm: round(10 x 800 / 3.175)
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(rig.send("G0 Z1"), "ok");
      ASSERT_TRUE(rig.wait_idle(3));
      ASSERT_EQ(rig.z().position, base);
      ASSERT_EQ(rig.send("G33 Z-9 K0.5 D3 E" + std::to_string(k)), "ok");
      const uint64_t armed = rig.armed_after();
      ASSERT_TRUE(rig.wait_idle(20)) << k;
      const sim::PassResult r = sim::check_pass(*rig.spindle, rig.z(), *rig.step, spec(500, counts, 3, k), base,
                                                armed, rig.m->cycles(), &end);
      const std::string what = std::string(quad ? "quadrature" : "seed disc") + " start " + std::to_string(k);
      ASSERT_TRUE(r.locked) << what;
      EXPECT_EQ(r.mismatches, 0u) << what;
      EXPECT_EQ(r.position, end) << what;
      const std::string st = rig.status();
      EXPECT_EQ(field(st, "last"), "length") << st;
      EXPECT_EQ(field(st, "z"), std::to_string(end)) << st;
    }
  }
}

TEST(LathePasses, LimitSwitchStopsAtOnce) {
  LatheRig rig(quadrature({{0.2, 0}, {0.4, 600}}));
  ASSERT_EQ(rig.send("ENCODER C600 E4"), "ok");
  ASSERT_EQ(rig.send("G33 Z-500 K1"), "ok");
  rig.run_for(2);
  ASSERT_EQ(field(rig.status(), "state"), "locked");
  // The switch's pin as the image's descriptor names it (PD7).
  const uint8_t limit = rig.m->board().spindle_pins[3];
  ASSERT_NE(limit, am::kNoPin);
  const uint64_t hit = rig.m->cycles();
  rig.m->set_input(am::pin_port(limit), am::pin_bit(limit), false);
  rig.run_for(0.5);
  const auto& c = rig.z().step_cycles;
  const uint64_t last = c.back();
  // No step begun after the first spindle count that saw the switch.
  uint64_t next_count = 0;
  for (const auto& e : rig.spindle->log())
    if (e.cycle > hit && e.count) {
      next_count = e.cycle;
      break;
    }
  EXPECT_LT(last, next_count + 200);
  const std::string st = rig.status();
  EXPECT_EQ(field(st, "state"), "idle") << st;
  EXPECT_EQ(field(st, "last"), "limit") << st;
  EXPECT_EQ(rig.send("G33 Z-500 K1"), "error: limit switch hit");
  EXPECT_EQ(rig.send("G0 Z5"), "error: limit switch hit");
  rig.m->set_input(am::pin_port(limit), am::pin_bit(limit), true);
  EXPECT_EQ(rig.send("G0 Z0"), "ok");
}

TEST(LathePasses, BadLinesAreRefusedAndNothingMoves) {
  LatheRig rig(quadrature({{0, 300}}));
  ASSERT_EQ(rig.send("ENCODER C600 E4"), "ok");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"G33 Z-10", "error: G33 needs Z and K or P"},
      {"G33 K1", "error: G33 needs Z and K or P"},
      {"G33 Z-10 K1 P13", "error: G33 needs Z and K or P"},
      {"G33 Z-10 K0", "error: pitch must be above 0"},
      {"G33 Z-10 K-1", "error: pitch must be above 0"},
      {"G33 Z0 K1", "error: Z is here"},
      {"G33 Z-10 K1 D3 E3", "error: E must be below D"},
      {"G33 Z-10 K1 D0", "error: D must be 1..255"},
      {"G33 Z-10 K1 D1.5", "error: D must be 1..255"},
      {"G33 Z-10 K200", "error: 16 or more steps per count"},
      {"G33 Z-10 K1 F100", "error: word not used here"},
      {"G33 Z-10 K1 L2", "error: unsupported word letter"},
      {"G33 Z-10 K1 K2", "error: word given twice"},
      {"G33 Z-10 Kx", "error: bad number"},
      {"G1 Z5", "error: not a lathe command"},
      {"Z5", "error: not a lathe command"},
      {"G0 Z5 F0", "error: feed must be above 0"},
      {"G0 X5", "error: word not used here"},
      {"ENCODER C0 E4", "error: ENCODER needs C1..16383, E1 or E4"},
      {"ENCODER C600 E2", "error: ENCODER needs C1..16383, E1 or E4"},
      {"G33 Z-999999 K1", "error: number out of range"},
      {std::string("G33 Z-10 K1") + std::string(60, ' '), "error: line too long (max 64)"},
      {"G33 Z-10 K1 (open", "error: comment not closed"},
  };
  for (const auto& c : cases) EXPECT_EQ(rig.send(c.first), c.second) << c.first;
  rig.run_for(0.5);
  EXPECT_TRUE(rig.z().step_cycles.empty());
  EXPECT_EQ(field(rig.status(), "state"), "idle");
  // Busy: a second motion line while a pass runs.
  ASSERT_EQ(rig.send("G33 Z-10 K1"), "ok");
  EXPECT_EQ(rig.send("G0 Z5"), "error: busy");
  EXPECT_EQ(rig.send("G33 Z-10 K1"), "error: busy");
  EXPECT_EQ(rig.send("ENCODER C40 E1"), "error: busy");
  EXPECT_EQ(rig.send("STOP"), "ok");
  EXPECT_EQ(field(rig.status(), "last"), "stopped");
}

}  // namespace
