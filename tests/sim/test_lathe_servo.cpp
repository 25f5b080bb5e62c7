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
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "lathe_rig.h"
#include "plot_lathe.h"

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
constexpr double kStopLeadBound = kFollowBound + kLambda;  // counts (49.4 um) ahead, a spindle slowing to rest mid-pass
constexpr double kOffModelBound = 8;  // counts (32.6 um): a motor whose gain or time constant is off the model's
constexpr double kRunningStartBound = 10;  // counts (40.7 um): a pass armed while the spindle turns at 300 rpm
// Cycles from the switch to ENABLE low for good: the switch is read every
// PWM period (1024 cycles) at its BOTTOM, behind at most one other vector
// (INT1 343, INT0 268, the UART 172 cycles at most, as the test prints
// them), plus the overflow vector's own entry; the test closes it at the
// worst moment, just after a BOTTOM.
constexpr uint64_t kLimitBound = 1600;

// The spindle's continuous angle in encoder phases (two per line, single
// channel) at increasing times: the model's rpm profile integrated (it is
// linear between its points: the trapezoid rule on 10 us steps is exact but
// for the steps that hold a point), from the model's start, mid-phase 0 at
// t = 0 (sim/spindle_encoder.h); a transition is the angle crossing a whole
// phase, so this agrees with the model's log and is right between
// transitions too, and at rest.
class SpindleAngle {
 public:
  explicit SpindleAngle(const sim::SpindleEncoder& sp) : sp_(sp) {}
  double at(uint64_t cycle, double f_cpu) {
    const double t = double(cycle) / f_cpu;
    constexpr double kStep = 1e-5;
    while (t_ < t) {
      const double dt = std::min(kStep, t - t_);
      angle_ += 0.5 * (sp_.rpm_at(t_) + sp_.rpm_at(t_ + dt)) / 60 * sp_.phases_per_turn() * dt;
      t_ += dt;
    }
    return angle_;
  }

 private:
  const sim::SpindleEncoder& sp_;
  double t_ = 0, angle_ = 0.5;
};

struct PassFigures {
  bool index_found = false;
  uint64_t index_cycle = 0;
  int64_t index_phase = 0;
  uint64_t end_cycle = 0;        // the count whose target reached the end (0: none)
  size_t samples = 0;
  double max_lag = 0, max_lead = 0;  // carriage behind / ahead of the helix, counts
  double at_index = 0;           // the carriage against the helix at the index (lag, counts)
  double worst = 0;              // max(|lag|, |lead|)
  std::vector<sim::LathePlotPoint> plot;  // every servo log entry from the index to the end
};

constexpr double kMmPerCount = 3.175 / 780;

// The pass after `armed` on the helix base + sigma lambda s: its index (as
// the firmware finds it), its end (the first count whose target
// floor(sigma lambda s) reaches `end`), and the carriage against the helix
// every servo log entry between the two (or up to `until`).
PassFigures measure(const ServoRig& rig, uint64_t armed, double base, int64_t end, uint64_t until,
                    int sigma = kSigma) {
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
    const double target = std::floor(sigma * kLambda * double(s));
    if ((sigma < 0 ? target <= double(end) : target >= double(end)) && t.cycle < until) {
      f.end_cycle = t.cycle;
      break;
    }
  }
  if (!f.index_found) return f;
  const uint64_t last = f.end_cycle ? f.end_cycle : until;
  bool first = true;
  SpindleAngle angle(*rig.spindle);
  for (const auto& e : rig.servo->log()) {
    if (e.cycle < f.index_cycle || e.cycle > last) continue;
    const double s = (angle.at(e.cycle, rig.m->f_cpu()) - double(f.index_phase)) / 2;
    const double helix = base + sigma * kLambda * s;
    const double lag = sigma * (helix - e.position);
    f.plot.push_back({double(e.cycle) / rig.m->f_cpu(), helix * kMmPerCount, e.position * kMmPerCount,
                      lag * kMmPerCount * 1000});
    if (first) f.at_index = lag;
    first = false;
    f.max_lag = std::max(f.max_lag, lag);
    f.max_lead = std::max(f.max_lead, -lag);
    ++f.samples;
  }
  f.worst = std::max(f.max_lag, f.max_lead);
  return f;
}

// The spindle for two passes: from rest to 300 rpm over 1 s, `hold` s at
// speed, back to rest over 1 s (5 hold + 5 turns), from t0 and again from t1.
sim::SpindleParams two_runs(double t0, double t1, double hold = 2) {
  sim::SpindleParams p;
  p.lines = 40;
  p.profile = {{t0, 0}, {t0 + 1, 300}, {t0 + 1 + hold, 300}, {t0 + 2 + hold, 0},
               {t1, 0}, {t1 + 1, 300}, {t1 + 1 + hold, 300}, {t1 + 2 + hold, 0}};
  return p;
}

TEST(LatheServo, ThreadPassFollowsAndTheSecondPassReentersTheHelix) {
  // 25 mm of a 1 mm thread: 25 spindle turns after the index (1000 counts),
  // 6142 motor counts (25000 um x 780 / 3175, rounded); the spindle turns
  // 30 (1 s up to 300 rpm, 5 s at speed, 1 s down), the pass ends at speed.
  ServoRig rig(two_runs(0.3, 12.5, 5));
  ASSERT_EQ(rig.send("G33 Z-25 K1"), "ok");
  const uint64_t armed1 = rig.last.sent_cycle;
  rig.run_until(7.5);
  ASSERT_TRUE(rig.wait_idle(1));
  const std::string st1 = rig.status();
  const int64_t end = -6142;
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

  // The picture (docs/lathe.md): written where AVRMOTION_PLOT_DIR says.
  {
    std::ostringstream svg;
    sim::write_lathe_plot(svg, "m16-servo: G33 Z-25 K1, pass 1 (300 rpm, 40-slot spindle, DC servo)", p1.plot);
    EXPECT_NE(svg.str().find("data-kind='carriage'"), std::string::npos);
    EXPECT_NE(svg.str().find("data-kind='error'"), std::string::npos);
    if (const char* dir = std::getenv("AVRMOTION_PLOT_DIR")) {
      const std::string path = std::string(dir) + "/lathe-servo-pass.svg";
      EXPECT_TRUE(sim::write_lathe_plot(path, "m16-servo: G33 Z-25 K1, pass 1 (300 rpm, 40-slot spindle, DC servo)",
                                        p1.plot))
          << path;
    }
  }

  // Retract to where the pass began, then the second pass from there.
  ASSERT_EQ(rig.send("G0 Z0"), "ok");
  ASSERT_TRUE(rig.wait_idle(5));
  const std::string st_back = rig.status();
  std::printf("retract: %s, motor at %.2f\n", st_back.c_str(), rig.servo->position());
  EXPECT_EQ(field(st_back, "last"), "done");
  rig.run_until(12.3);
  ASSERT_EQ(rig.send("G33 Z-25 K1"), "ok");
  const uint64_t armed2 = rig.last.sent_cycle;
  rig.run_until(19.7);
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

namespace {

// The spindle from rest (at t0) to 300 rpm over 1 s, then at speed.
sim::SpindleParams running_from(double t0) {
  sim::SpindleParams p;
  p.lines = 40;
  p.profile = {{t0, 0}, {t0 + 1, 300}};
  return p;
}

TEST(LatheServo, LimitSwitchStopsThePwmAtOnce) {
  ServoRig rig(running_from(0.2));
  ASSERT_EQ(rig.send("G33 Z-30 K1"), "ok");
  rig.run_until(2.0);
  const std::string running = rig.status();
  EXPECT_EQ(field(running, "state"), "locked") << running;
  // The status line's following error: the follower's target (a staircase
  // up to lambda behind the interpolated one) minus the count.
  const long err = std::atol(field(running, "err").c_str());
  EXPECT_LE(std::labs(err), long(kFollowBound + kLambda + 1)) << running;
  ASSERT_GT(rig.enable->size(), 100u) << "the PWM never ran";

  // The worst moment: just after a period's BOTTOM (where the inverting PWM
  // clears ENABLE and the overflow vector reads the switch): the period's
  // pulse at its end is still to come, and the switch is read again only at
  // the next BOTTOM.
  const size_t before = rig.enable->size();
  rig.m->run([&rig, before] { return rig.enable->size() > before + 1 && !rig.enable->back().level; },
             rig.m->f_cpu() / 100);
  ASSERT_FALSE(rig.enable->back().level);
  rig.m->run([] { return false; }, 200);  // the overflow vector has read the switch open
  ASSERT_FALSE(rig.enable->back().level);
  const uint64_t hit = rig.m->cycles();
  const double x_hit = rig.servo->position();
  rig.m->hold_input('D', 7, false);
  rig.run_until(double(hit) / rig.m->f_cpu() + 0.1);
  // ENABLE's last edge after the switch must be a fall, within the bound,
  // and nothing after it.
  uint64_t off = hit;
  size_t rises_after = 0;
  for (const auto& e : *rig.enable) {
    if (e.cycle < hit) continue;
    if (e.level) ++rises_after;
    else off = e.cycle;
  }
  const auto& edges = *rig.enable;
  ASSERT_FALSE(edges.empty());
  EXPECT_FALSE(edges.back().level) << "ENABLE left high";
  const uint64_t stop_cycles = off - hit;
  std::printf("limit switch: ENABLE low for good %llu cycles (%.1f us) after it, %zu rises after it; "
              "the motor coasted %.1f counts\n",
              (unsigned long long)stop_cycles, stop_cycles * 1e6 / rig.m->f_cpu(), rises_after,
              std::fabs(rig.servo->position() - x_hit));
  EXPECT_LE(stop_cycles, kLimitBound);
  // The vectors' longest runs (entry to RETI): the switch is read every
  // overflow (1024 cycles), so the worst case is a period plus the longest
  // vector it may wait behind.
  for (const auto& v : rig.m->isr_stats())
    std::printf("  vector %d: %llu entries, longest %llu cycles\n", v.first, (unsigned long long)v.second.count,
                (unsigned long long)v.second.max_cycles);
  std::printf("  stack: %u B of %u B free\n", rig.m->stack_bytes(), rig.m->free_ram());
  EXPECT_LE(rises_after, 1u);  // at most the pulse of the period already begun when the switch closed
  ASSERT_TRUE(rig.wait_idle(1));
  const std::string st = rig.status();
  EXPECT_EQ(field(st, "last"), "limit") << st;
  EXPECT_EQ(rig.send("G33 Z-30 K1"), "error: limit switch hit");
  EXPECT_EQ(rig.send("G0 Z5"), "error: limit switch hit");
  rig.m->hold_input('D', 7, true);
  EXPECT_EQ(rig.send("G0 Z-1"), "ok");
}

// The time ENABLE was high in [from, to), cycles, and the rises of no width
// in it (a rise and a fall in the same cycle: simavr running the compare
// match and the BOTTOM action of a period at OCR1A = TOP together, which
// the datasheet calls a constant level; no time high, it moves no motor).
uint64_t high_cycles(const std::vector<sim::PinEdge>& e, uint64_t from, uint64_t to, uint64_t* no_width = nullptr) {
  uint64_t high = 0;
  bool level = false;
  uint64_t since = from;
  for (size_t i = 0; i < e.size(); ++i) {
    const uint64_t c = std::min(std::max(e[i].cycle, from), to);
    if (level) high += c - since;
    if (no_width && e[i].level && i + 1 < e.size() && e[i + 1].cycle == e[i].cycle && e[i].cycle >= from &&
        e[i].cycle < to)
      ++*no_width;
    level = e[i].level;
    since = c;
  }
  if (level) high += to - since;
  return high;
}

TEST(LatheServo, PwmZeroIsTrulyOff) {
  sim::SpindleParams p;
  p.lines = 40;
  p.profile = {{1.0, 0}, {2.0, 300}, {3.0, 300}, {4.0, 0}};  // 10 turns
  ServoRig rig(p);
  ASSERT_EQ(rig.send("G33 Z-30 K1"), "ok");
  const uint64_t armed = rig.m->cycles();
  rig.run_until(0.9);
  EXPECT_EQ(field(rig.status(), "state"), "armed");
  // Armed, the spindle at rest: the bridge is connected to the PWM at duty 0
  // (OCR1A = TOP) for 0.9 s, 14000 periods; ENABLE must never be high.
  // (Non-inverting fast PWM at OCR1A = 0 would be high one cycle a period:
  // simavr models that spike.)
  uint64_t no_width = 0;
  const uint64_t armed_high = high_cycles(*rig.enable, 0, rig.m->cycles(), &no_width);
  EXPECT_EQ(armed_high, 0u);
  EXPECT_GT(no_width, 10000u) << "the PWM did not run at duty 0 while armed";
  // The spindle turns 10 turns and stops: the pass follows it to rest (the
  // carriage ahead of the target while the spindle slows: duty 0), then STOP.
  rig.run_until(4.6);
  const std::string st = rig.status();
  EXPECT_EQ(field(st, "state"), "locked") << st;
  const uint64_t pass_end = rig.m->cycles();
  // The same pass against the helix, from the index through the spindle's
  // ramp up, 1 s at speed, its ramp down and 0.6 s at rest (the carriage
  // ends up to a spindle count's worth ahead of where the spindle stopped
  // between two counts: the interpolation runs on to the next one).
  const PassFigures f = measure(rig, armed, 0, -100000, pass_end);
  std::printf("pass through the ramp down to rest: lag <= %.2f, lead <= %.2f counts\n", f.max_lag, f.max_lead);
  EXPECT_LE(f.max_lag, kFollowBound);
  EXPECT_LE(f.max_lead, kStopLeadBound);
  ASSERT_EQ(rig.send("STOP"), "ok");
  const uint64_t stopped = rig.m->cycles();
  ASSERT_TRUE(rig.wait_idle(1));
  rig.run_until(5.5);
  // The pass: the pulses (of some width) and the whole periods between
  // them with ENABLE low (the samples at duty 0).
  const auto& e = *rig.enable;
  uint64_t pulses = 0, zero_periods = 0, shortest = ~0ull, last_fall = 0;
  for (size_t i = 1; i < e.size(); ++i) {
    if (e[i].cycle < armed || e[i].cycle > pass_end) continue;
    if (e[i - 1].level && !e[i].level && e[i].cycle > e[i - 1].cycle) {
      ++pulses;
      shortest = std::min<uint64_t>(shortest, e[i].cycle - e[i - 1].cycle);
      if (last_fall) zero_periods += (e[i - 1].cycle - last_fall) / 1024 - ((e[i - 1].cycle - last_fall) >= 1024);
      last_fall = e[i].cycle;
    }
  }
  const uint64_t after = high_cycles(e, stopped + 1024, rig.m->cycles());
  std::printf("PWM: armed 0.9 s (%llu periods at duty 0), %llu cycles high; the pass: %llu pulses, the shortest "
              "%llu cycles, %llu whole periods at duty 0 between them; after STOP %llu cycles high\n",
              (unsigned long long)no_width, (unsigned long long)armed_high, (unsigned long long)pulses,
              (unsigned long long)shortest, (unsigned long long)zero_periods, (unsigned long long)after);
  EXPECT_GT(pulses, 1000u);
  EXPECT_GT(zero_periods, 0u) << "the pass never asked for duty 0";
  EXPECT_EQ(after, 0u);
  ASSERT_FALSE(e.empty());
  EXPECT_FALSE(e.back().level);
  // The motor's own account: ENABLE high only while the pass ran.
  EXPECT_EQ(rig.servo->enable_high_cycles(), high_cycles(e, armed, pass_end + 1024));
}

TEST(LatheServo, FrontEndRefusals) {
  ServoRig rig(running_from(10));
  EXPECT_EQ(rig.send("ENCODER C600 E4"), "error: E4 needs INT0, the servo's");
  EXPECT_EQ(rig.send("ENCODER C40 E1"), "ok");
  EXPECT_EQ(rig.send("G33 Z-10 K1100"), "error: 64 or more counts per count");
  EXPECT_EQ(rig.send("G33 Z0 K1"), "error: Z is here");
  const std::string st = rig.status();
  EXPECT_EQ(field(st, "state"), "idle") << st;
  EXPECT_EQ(field(st, "slip"), "0") << st;
  EXPECT_EQ(field(st, "lost"), "0") << st;
}

}  // namespace

namespace {

// The same pass on the m16-lathe's stepper leadscrew, for the picture
// beside the servo's (docs/lathe.md): 800 steps a leadscrew turn, lambda =
// 800/127 steps per spindle count. Its following error against the
// continuous helix is the follower's staircase: 0 to lambda steps behind,
// never ahead, once locked.
TEST(LatheServo, StepperPassForThePicture) {
  simtest::LatheRig rig(two_runs(0.3, 100));
  ASSERT_EQ(rig.send("G33 Z-10 K1"), "ok");
  const uint64_t armed = rig.armed_after();
  rig.run_for(4.5);
  ASSERT_TRUE(rig.wait_idle(1));
  constexpr double kSteps = 800.0 / 127.0, kMmPerStep = 3.175 / 800;
  // The index as the firmware finds it.
  bool was_high = true, found = false;
  int64_t index_phase = 0;
  uint64_t index_cycle = 0;
  for (const auto& t : rig.spindle->log()) {
    if (t.cycle <= armed || !t.count) continue;
    if (t.index && !was_high) {
      found = true;
      index_phase = t.phase;
      index_cycle = t.cycle;
      break;
    }
    was_high = t.index;
  }
  ASSERT_TRUE(found);
  const uint64_t end = rig.z().step_cycles.empty() ? 0 : rig.z().step_cycles.back();
  std::vector<sim::LathePlotPoint> pts;
  std::vector<double> lags;
  SpindleAngle angle(*rig.spindle);
  for (uint64_t c = index_cycle; c <= end; c += 1024) {
    const double s = (angle.at(c, rig.m->f_cpu()) - double(index_phase)) / 2;
    const double helix = -kSteps * s, at = double(sim::position_at(rig.z(), c));
    const double lag = -(helix - at);
    pts.push_back({double(c) / rig.m->f_cpu(), helix * kMmPerStep, at * kMmPerStep, lag * kMmPerStep * 1000});
    lags.push_back(lag);
  }
  ASSERT_FALSE(lags.empty());
  // The catch-up (the carriage waits for the target to pass it, then chases
  // it), then locked: the follower's staircase, up to lambda steps (one
  // spindle count) behind, ahead only by the interpolation between two
  // transitions of the spindle.
  size_t lock = 0;
  for (size_t i = 0; i < lags.size(); ++i)
    if (lags[i] > kSteps + 1 || lags[i] < -1) lock = i + 1;
  double catch_max = 0, lag_max = 0, lead_max = 0;
  for (size_t i = 0; i < lags.size(); ++i) {
    if (i < lock) catch_max = std::max(catch_max, std::fabs(lags[i]));
    else {
      lag_max = std::max(lag_max, lags[i]);
      lead_max = std::max(lead_max, -lags[i]);
    }
  }
  std::printf("stepper pass: %zu samples; catch-up %.3f s, up to %.1f steps; then lag <= %.2f, lead <= %.2f steps\n",
              lags.size(), lock * 1024.0 / rig.m->f_cpu(), catch_max, lag_max, lead_max);
  EXPECT_LT(lock, lags.size() / 4) << "locked late";
  EXPECT_LE(lag_max, kSteps + 1);
  EXPECT_LE(lead_max, 1.0);
  if (const char* dir = std::getenv("AVRMOTION_PLOT_DIR")) {
    const std::string path = std::string(dir) + "/lathe-stepper-pass.svg";
    EXPECT_TRUE(sim::write_lathe_plot(path, "m16-lathe: G33 Z-10 K1 (300 rpm, 40-slot spindle, stepper 800 steps/turn)",
                                      pts))
        << path;
  }
}

}  // namespace

namespace {

// The image within the ATmega16's flash with 10 % to spare, and its stack
// on the deepest line the front end takes (a three-start 13 TPI G33: the
// ratio's 128-bit set-up) with the servo's vectors running under it; that
// pass followed at 60 rpm and stopped (overspeed) at 300.
TEST(LatheServo, ImageLeavesTenPercentOfTheFlashAndStackHeadroom) {
  const std::string cmd = "avr-size -C --mcu=atmega16 " + simtest::image("m16-servo");
  FILE* out = popen(cmd.c_str(), "r");
  ASSERT_NE(out, nullptr);
  unsigned long flash = 0, ram = 0;
  char line[256];
  while (fgets(line, sizeof line, out)) {
    std::sscanf(line, "Program: %lu", &flash);
    std::sscanf(line, "Data: %lu", &ram);
  }
  pclose(out);
  ASSERT_GT(flash, 0u);
  // 13 TPI, three starts: a 5.86 mm lead, lambda = 36 counts per spindle
  // count. At 60 rpm (1440 counts/s) the servo follows it; at 300 rpm (7200
  // counts/s, above the motor's 2134) the pass stops with overspeed once
  // the carriage is kServoMaxLag (64) counts behind.
  sim::SpindleParams sp;
  sp.lines = 40;
  sp.profile = {{0.2, 0}, {1.2, 60}, {3.5, 60}, {4.5, 300}};
  ServoRig rig(sp);
  ASSERT_EQ(rig.send("G33 Z-150 P13 D3 E2"), "ok");
  rig.run_until(3.0);  // locked, the PID running
  const std::string st = rig.status();
  EXPECT_EQ(field(st, "state"), "locked") << st;
  EXPECT_LE(std::labs(std::atol(field(st, "err").c_str())), 36 + long(kFollowBound)) << st;
  rig.run_until(5.0);
  ASSERT_TRUE(rig.wait_idle(1));
  const std::string over = rig.status();
  EXPECT_EQ(field(over, "last"), "overspeed") << over;
  std::printf("13 TPI x 3 starts: at 60 rpm %s; spindle to 300 rpm: %s\n", st.c_str(), over.c_str());
  ASSERT_EQ(rig.send("G0 Z0"), "ok");
  ASSERT_TRUE(rig.wait_idle(30));
  const unsigned stack = rig.m->stack_bytes(), free_ram = rig.m->free_ram();
  std::printf("m16-servo: %lu B of flash (limit 14745 B, 90 %% of 16384), %lu B of RAM (.data + .bss), "
              "stack %u B of the %u B above them: %u B to spare\n",
              flash, ram, stack, free_ram, free_ram - stack);
  EXPECT_LE(flash, 14745u);
  EXPECT_LE(ram, 1024u);
  EXPECT_LE(stack + 64, free_ram) << "less than 64 B of stack to spare";
}

}  // namespace

namespace {

// A left-hand thread (the pass towards +Z, IN1 driven). The firmware's
// feedforward and gains are for the seed's plant; a motor
// that is not it (gain and time constant off by the factors below) is
// followed by the PID alone for what the model does not predict. And a
// pass armed while the spindle already turns at 300 rpm: the motor starts
// from rest at the index (the stepper's catch-up has no counterpart here:
// the PID takes the step in speed).
TEST(LatheServo, PlantsOffTheModelAndARunningStart) {
  struct Case {
    const char* what;
    double gain, pole;
    bool running;
    double bound;  // counts
  };
  const Case cases[] = {
      {"left hand (+Z)", 2.0866, 74.29, false, kFollowBound},
      {"gain x 0.7", 2.0866 * 0.7, 74.29, false, kOffModelBound},
      {"gain x 1.4", 2.0866 * 1.4, 74.29, false, kOffModelBound},
      {"time constant x 2", 2.0866, 74.29 / 2, false, kOffModelBound},
      {"time constant x 0.5", 2.0866, 74.29 * 2, false, kOffModelBound},
      {"running start", 2.0866, 74.29, true, kRunningStartBound},
  };
  for (const Case& c : cases) {
    sim::ServoParams sp;
    sp.gain = c.gain;
    sp.pole = c.pole;
    sim::SpindleParams p;
    p.lines = 40;
    p.profile = c.running ? std::vector<sim::RpmPoint>{{0, 300}} : std::vector<sim::RpmPoint>{{0.3, 0}, {1.3, 300}};
    ServoRig rig(p, sp);
    const bool left = &c == &cases[0];  // towards +Z: a left-hand thread, the bridge's other direction
    ASSERT_EQ(rig.send(left ? "G33 Z10 K1" : "G33 Z-10 K1"), "ok") << c.what;
    const uint64_t armed = rig.last.sent_cycle;
    rig.run_until(4.0);
    ASSERT_TRUE(rig.wait_idle(1)) << c.what;
    const std::string st = rig.status();
    const PassFigures f = measure(rig, armed, 0, left ? 2457 : -2457, rig.m->cycles(), left ? 1 : -1);
    ASSERT_TRUE(f.index_found) << c.what;
    std::printf("%s: lag <= %.2f, lead <= %.2f counts; %s\n", c.what, f.max_lag, f.max_lead, st.c_str());
    EXPECT_EQ(field(st, "last"), "length") << c.what << ": " << st;
    EXPECT_LE(f.worst, c.bound) << c.what;
  }
}

}  // namespace
