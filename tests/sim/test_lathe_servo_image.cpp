// The m16-servo image's outputs and size: a limit switch stops the PWM at
// once and the bridge brakes, PWM zero is truly off, a stop brakes the motor, the front end refuses what it cannot run, and
// the image leaves 10 % of the flash and stack headroom. The thread passes
// themselves: test_lathe_servo.cpp; the pass's figures: servo_pass.h.
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

#include "servo_pass.h"

namespace {

using simtest::field;
using simtest::ServoRig;
using namespace servotest;

// The spindle from rest (at t0) to 300 rpm over 1 s, then at speed.
sim::SpindleParams running_from(double t0) {
  sim::SpindleParams p;
  p.lines = 40;
  p.profile = {{t0, 0}, {t0 + 1, 300}};
  return p;
}

// The bridge from its three pins (ENABLE, IN1, IN2) replayed in cycle
// order: driven while ENABLE is high with IN1 != IN2, braking while it is
// high with IN1 = IN2 = 0. Over [from, to): the cycles driven, the drives
// begun, the cycle the last one ended (from if none did); and the state at
// `to`.
struct Bridge {
  uint64_t driven = 0, last_drive_end = 0;
  size_t drives_begun = 0;
  bool braking_at_end = false, driven_at_end = false;
};
Bridge bridge(const ServoRig& rig, uint64_t from, uint64_t to) {
  struct Ev {
    uint64_t cycle;
    int pin;
    bool level;
  };
  std::vector<Ev> ev;
  const std::vector<sim::PinEdge>* pins[] = {rig.enable, rig.in1, rig.in2};
  for (int k = 0; k < 3; ++k)
    for (const sim::PinEdge& e : *pins[k]) ev.push_back({e.cycle, k, e.level});
  std::stable_sort(ev.begin(), ev.end(), [](const Ev& a, const Ev& b) { return a.cycle < b.cycle; });
  Bridge b;
  b.last_drive_end = from;
  bool level[3] = {false, false, false};
  bool driven = false;
  uint64_t since = from;
  for (size_t i = 0; i <= ev.size(); ++i) {
    const uint64_t c = i < ev.size() ? std::min(std::max(ev[i].cycle, from), to) : to;
    if (driven) b.driven += c - since;
    since = c;
    if (i == ev.size()) break;
    level[ev[i].pin] = ev[i].level;
    if (i + 1 < ev.size() && ev[i + 1].cycle == ev[i].cycle) continue;  // one cycle's changes together
    const bool now = level[0] && level[1] != level[2];
    if (ev[i].cycle >= from && ev[i].cycle < to) {
      if (now && !driven) ++b.drives_begun;
      if (!now && driven) b.last_drive_end = ev[i].cycle;
    }
    if (ev[i].cycle < to) {
      driven = now;
      b.driven_at_end = now;
      b.braking_at_end = level[0] && !level[1] && !level[2];
    }
  }
  return b;
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
  // The drive's last end after the switch within the bound, and from then
  // the brake: ENABLE high, IN1 = IN2 = 0.
  const Bridge b = bridge(rig, hit, rig.m->cycles());
  EXPECT_FALSE(b.driven_at_end) << "the bridge still drives";
  EXPECT_TRUE(b.braking_at_end) << "the bridge does not brake";
  const uint64_t stop_cycles = b.last_drive_end - hit;
  const size_t rises_after = b.drives_begun;
  std::printf("limit switch: the drive off for good %llu cycles (%.1f us) after it, %zu drives begun after it, "
              "then %s; the motor ran down %.1f counts\n",
              (unsigned long long)stop_cycles, stop_cycles * 1e6 / rig.m->f_cpu(), rises_after,
              b.braking_at_end ? "braking" : "not braking", std::fabs(rig.servo->position() - x_hit));
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
  const Bridge after_stop = bridge(rig, stopped + 1024, rig.m->cycles());
  const uint64_t after = after_stop.driven;
  std::printf("PWM: armed 0.9 s (%llu periods at duty 0), %llu cycles high; the pass: %llu pulses, the shortest "
              "%llu cycles, %llu whole periods at duty 0 between them; after STOP %llu cycles driven, %s\n",
              (unsigned long long)no_width, (unsigned long long)armed_high, (unsigned long long)pulses,
              (unsigned long long)shortest, (unsigned long long)zero_periods, (unsigned long long)after,
              after_stop.braking_at_end ? "braking" : "not braking");
  EXPECT_GT(pulses, 1000u);
  EXPECT_GT(zero_periods, 0u) << "the pass never asked for duty 0";
  EXPECT_EQ(after, 0u);
  EXPECT_TRUE(after_stop.braking_at_end);
  // The motor's own account: driven only while the pass ran, as the pins say.
  EXPECT_EQ(rig.servo->driven_cycles(), bridge(rig, armed, pass_end + 1024).driven);
  EXPECT_EQ(rig.servo->driven_cycles(), high_cycles(e, armed, pass_end + 1024));
  EXPECT_GT(rig.servo->brake_cycles(), uint64_t(0.5 * rig.m->f_cpu()));
}

// The brake at a pass's end: a motor that runs on ten times longer when
// free (the model's coast_pole = pole / 10) stops within the identified
// plant's w tau, as the shorted motor does, not w 10 tau.
TEST(LatheServo, BrakeStopsTheMotorAtThePassEnd) {
  sim::ServoParams sp;
  sp.coast_pole = 74.29 / 10;
  ServoRig rig(running_from(0.2), sp);
  ASSERT_EQ(rig.send("G33 Z-10 K1"), "ok");
  rig.run_until(4.0);
  ASSERT_TRUE(rig.wait_idle(1));
  const std::string st = rig.status();
  EXPECT_EQ(field(st, "last"), "length") << st;
  const Bridge b = bridge(rig, 0, rig.m->cycles());
  EXPECT_FALSE(b.driven_at_end);
  EXPECT_TRUE(b.braking_at_end) << "the bridge does not brake";
  const uint64_t end = b.last_drive_end;
  double w = 0;  // the motor's speed where the drive ended: the log's entry at or after it
  for (const sim::ServoSample& x : rig.servo->log())
    if (x.cycle >= end) {
      w = std::fabs(x.speed);
      break;
    }
  const double ran = std::fabs(rig.servo->position() - rig.servo->position_at(end));
  const double braked = w / sp.pole, free_running = w / sp.coast_pole;
  std::printf("brake: %.0f counts/s where the drive ended; ran down %.1f counts (w tau braked %.1f, free running "
              "%.1f); %s\n",
              w, ran, braked, free_running, st.c_str());
  EXPECT_GT(w, 1000.0);  // 300 rpm, 1 mm: 1228 counts/s
  EXPECT_LE(ran, 1.2 * braked + 1);
  // The next pass, armed from the brake: the bridge is not driven at all
  // until the index locks it (the brake released before OC1A takes the pin).
  ASSERT_EQ(rig.send("G33 Z-20 K1"), "ok");
  const uint64_t armed = rig.last.sent_cycle;
  rig.run_until(double(rig.m->cycles()) / rig.m->f_cpu() + 0.5);
  uint64_t index = 0;
  bool was = true;
  for (const sim::SpindleTransition& t : rig.spindle->log()) {
    if (t.cycle > armed && t.index && !was) {
      index = t.cycle;
      break;
    }
    if (t.cycle > armed) was = t.index;
  }
  ASSERT_GT(index, armed);
  const Bridge armed_bridge = bridge(rig, armed, index);
  std::printf("armed from the brake: %.1f ms to the index, %llu cycles driven\n",
              (index - armed) * 1e3 / rig.m->f_cpu(), (unsigned long long)armed_bridge.driven);
  EXPECT_EQ(armed_bridge.driven, 0u);
  EXPECT_GT(bridge(rig, index, rig.m->cycles()).driven, 0u);
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

// The image within the ATmega16's flash with 10 % to spare, and its stack
// on the deepest line the front end takes (a three-start 13 TPI G33: the
// ratio's 128-bit set-up) with the servo's vectors running under it; that
// pass followed at 60 rpm and stopped (overspeed) at 300.
TEST(LatheServo, ImageLeavesTenPercentOfTheFlashAndStackHeadroom) {
  const simtest::ImageSize size = simtest::avr_size("m16-servo", "atmega16");
  const unsigned long flash = size.flash, ram = size.ram;
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
