// The m16-servo image (firmware/boards/m16-servo.h): the seed's DC servo on
// the leadscrew, the seed's plant in the simulator (sim/dc_servo.h), the
// spindle model on INT1. What is measured here is the carriage the plant
// model moved, against the helix the test computes itself: every 1024
// cycles (64 us) from the pass's index to its end, ramps included, the
// carriage's continuous position against lambda times the spindle's
// continuous angle (both from the models, not from the firmware).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "lathe_rig.h"

namespace {

using simtest::field;
using simtest::ServoRig;

// 1.00 mm on the seed's machine: 780 counts x 1 mm / 3.175 mm per 40
// spindle counts = 780/127 motor counts per spindle count.
constexpr double kLambda = 780.0 / 127.0;
constexpr int kSigma = -1;  // a right-hand thread towards the chuck: -Z

// The documented bounds (docs/lathe.md, "The m16-servo image").
constexpr double kFollowBound = 6;    // counts (24.4 um) of carriage, either way, every sample of a pass
constexpr double kPhaseBound = 6;     // counts, the second pass against the first's helix
constexpr double kReentryBound = 2;   // counts, the second pass at its index (the retract's slip)
constexpr uint64_t kLimitBound = 2500;  // cycles from the switch to ENABLE low for good

// The spindle's continuous angle in counts at a cycle: its transitions
// (two per line, single channel) interpolated linearly.
double spindle_phase_at(const sim::SpindleEncoder& sp, uint64_t cycle) {
  const auto& log = sp.log();
  auto it = std::lower_bound(log.begin(), log.end(), cycle,
                             [](const sim::SpindleTransition& t, uint64_t c) { return t.cycle < c; });
  if (it == log.begin()) return double(it->phase);
  if (it == log.end()) return double(log.back().phase);
  const auto& b = *it;
  const auto& a = *(it - 1);
  return a.phase + double(cycle - a.cycle) / double(b.cycle - a.cycle) * double(b.phase - a.phase);
}

struct PassFigures {
  bool index_found = false;
  uint64_t index_cycle = 0;
  int64_t index_phase = 0;
  uint64_t end_cycle = 0;        // the count whose target reached the end (0: none)
  size_t samples = 0;
  double max_lag = 0, max_lead = 0;  // carriage behind / ahead of the helix, counts
  double at_index = 0;           // the carriage against the helix at the index (lag, counts)
  double worst = 0;              // max(|lag|, |lead|)
};

// The pass after `armed` on the helix base + sigma lambda s: its index (as
// the firmware finds it), its end (the first count whose target
// floor(sigma lambda s) reaches `end`), and the carriage against the helix
// every servo log entry between the two (or up to `until`).
PassFigures measure(const ServoRig& rig, uint64_t armed, double base, int64_t end, uint64_t until) {
  PassFigures f;
  bool was_high = true;
  for (const auto& t : rig.spindle->log()) {
    if (t.cycle <= armed || !t.count) continue;
    if (!f.index_found) {
      if (t.index && !was_high) {
        f.index_found = true;
        f.index_cycle = t.cycle;
        f.index_phase = t.phase;
      }
      was_high = t.index;
      continue;
    }
    const int64_t s = (t.phase - f.index_phase) / 2;
    const double target = std::floor(kSigma * kLambda * double(s));
    if (target <= double(end) && t.cycle < until) {
      f.end_cycle = t.cycle;
      break;
    }
  }
  if (!f.index_found) return f;
  const uint64_t last = f.end_cycle ? f.end_cycle : until;
  bool first = true;
  for (const auto& e : rig.servo->log()) {
    if (e.cycle < f.index_cycle || e.cycle > last) continue;
    const double s = (spindle_phase_at(*rig.spindle, e.cycle) - double(f.index_phase)) / 2;
    const double lag = kSigma * (base + kSigma * kLambda * s - e.position);
    if (first) f.at_index = lag;
    first = false;
    f.max_lag = std::max(f.max_lag, lag);
    f.max_lead = std::max(f.max_lead, -lag);
    ++f.samples;
  }
  f.worst = std::max(f.max_lag, f.max_lead);
  return f;
}

// The spindle for two passes: from rest to 300 rpm over 1 s, 2 s at speed,
// back to rest over 1 s (15 turns), from t0 and again from t1.
sim::SpindleParams two_runs(double t0, double t1) {
  sim::SpindleParams p;
  p.lines = 40;
  p.profile = {{t0, 0}, {t0 + 1, 300}, {t0 + 3, 300}, {t0 + 4, 0},
               {t1, 0}, {t1 + 1, 300}, {t1 + 3, 300}, {t1 + 4, 0}};
  return p;
}

TEST(LatheServo, ThreadPassFollowsAndTheSecondPassReentersTheHelix) {
  ServoRig rig(two_runs(0.3, 7.0));
  ASSERT_EQ(rig.send("G33 Z-10 K1"), "ok");
  const uint64_t armed1 = rig.last.sent_cycle;
  rig.run_until(4.5);
  ASSERT_TRUE(rig.wait_idle(1));
  const std::string st1 = rig.status();
  // 10 mm: 2457 counts (10000 um x 780 / 3175, rounded).
  const int64_t end = -2457;
  const PassFigures p1 = measure(rig, armed1, 0, end, rig.m->cycles());
  ASSERT_TRUE(p1.index_found);
  ASSERT_NE(p1.end_cycle, 0u) << "the pass did not reach its end";
  const double x_end1 = rig.servo->position_at(p1.end_cycle);
  const double x_rest1 = rig.servo->position();
  std::printf("pass 1: %zu samples, lag <= %.2f, lead <= %.2f counts; at the end %.2f counts behind; %s\n", p1.samples,
              p1.max_lag, p1.max_lead, kSigma * (double(end) - x_end1), st1.c_str());
  EXPECT_EQ(field(st1, "state"), "idle") << st1;
  EXPECT_EQ(field(st1, "last"), "length") << st1;
  EXPECT_LE(p1.worst, kFollowBound);
  // Where the drive stopped, the carriage was on the end's target within the bound.
  EXPECT_LE(std::fabs(double(end) - x_end1), kFollowBound);
  // The firmware's slip is the end's target minus its count, which the
  // motor's own position matches within the encoder's half count.
  const long slip1 = std::atol(field(st1, "slip").c_str());
  EXPECT_NEAR(double(end - slip1), x_rest1, 0.51) << st1;

  // Retract to where the pass began, then the second pass from there.
  ASSERT_EQ(rig.send("G0 Z0"), "ok");
  ASSERT_TRUE(rig.wait_idle(3));
  const std::string st_back = rig.status();
  std::printf("retract: %s, motor at %.2f\n", st_back.c_str(), rig.servo->position());
  EXPECT_EQ(field(st_back, "last"), "done");
  rig.run_until(6.8);
  ASSERT_EQ(rig.send("G33 Z-10 K1"), "ok");
  const uint64_t armed2 = rig.last.sent_cycle;
  rig.run_until(11.2);
  ASSERT_TRUE(rig.wait_idle(1));
  const std::string st2 = rig.status();
  const PassFigures p2 = measure(rig, armed2, 0, end, rig.m->cycles());
  ASSERT_TRUE(p2.index_found);
  ASSERT_NE(p2.end_cycle, 0u);
  std::printf("pass 2: %zu samples, lag <= %.2f, lead <= %.2f counts, %.2f at the index; %s\n", p2.samples,
              p2.max_lag, p2.max_lead, p2.at_index, st2.c_str());
  EXPECT_EQ(field(st2, "last"), "length") << st2;
  // The same helix: the second pass against the first's base (0), with the
  // retract's slip as its initial error.
  EXPECT_LE(p2.worst, kPhaseBound);
  EXPECT_LE(std::fabs(p2.at_index), kReentryBound);
}

}  // namespace
