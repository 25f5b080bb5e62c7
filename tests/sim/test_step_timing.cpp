// Pulse timestamps of the real images against the core's own schedule: the
// step engine must reproduce every interval of SpeedRamp to the cycle (Timer1
// runs at the CPU clock, so one tick is one cycle).
#include <algorithm>
#include <vector>

#include "schedule.h"
#include "sim_fixture.h"

namespace {

constexpr int64_t kJitterBound = 12;    // cycles, peak to peak, software pulses
constexpr int64_t kTimerPulseSpread = 0;  // hardware edges: exact

void expect_schedule(const std::string& image, char axis, uint32_t steps, const sim::Ramp& cfg,
                     int64_t jitter_bound = kJitterBound) {
  const std::string line = std::string("MOVE ") + axis + std::to_string(steps) + " F" + std::to_string(cfg.rate) +
                           " A" + std::to_string(cfg.accel);
  auto m = simtest::run(image, {line}, 20);
  const std::vector<uint32_t> expected = sim::planned_schedule(steps, cfg);
  ASSERT_EQ(expected.size(), steps);
  const std::vector<uint64_t>& stamps = m->axis(axis)->step_cycles;
  ASSERT_EQ(stamps.size(), steps);
  // Pulse k is due at pulse 0 plus the ramp's delays 1..k.
  const sim::Lateness late = sim::lateness(stamps, 0, stamps.size(), expected);
  // The timer fixes every pulse's slot; only interrupt latency (the
  // instruction the main loop is in, a UART interrupt) and data-dependent
  // work before the output moves a pulse within it. The window is the
  // engine's documented jitter bound (docs/step-engine.md); no drift means
  // no lost or extra tick anywhere in the move.
  EXPECT_LE(late.spread(), jitter_bound) << image << ": pulses wander " << late.lo << ".." << late.hi << " cycles";
}

}  // namespace

// The m32's step/dir axes with MOVE's exact ramps: its CNC image (the
// printer's takes G-code only).
TEST(StepTiming, StepDirMoveMatchesTheRampToTheCycle) {
  expect_schedule("m32-direct", 'X', 400, sim::Ramp{16000000, 4000, 8000});
}

TEST(StepTiming, TriangleMatches) {
  expect_schedule("m32-direct", 'Y', 300, sim::Ramp{16000000, 20000, 30000});
}

TEST(StepTiming, ShieldLatchStepsMatchTheRampToTheCycle) {
  expect_schedule("uno", 'X', 400, sim::Ramp{16000000, 600, 1200});
}

TEST(StepTiming, IntervalsLongerThanTheTimerAreExact) {
  // 4 steps/s^2 makes the first interval 16e6 * sqrt(2/4) = 11.3 M cycles,
  // 173 timer periods: the period counting must not lose or add a tick.
  expect_schedule("m16", 'Z', 6, sim::Ramp{16000000, 100, 4});
  // At 1 step/s^2 the first interval (22.6 M cycles) no longer fits a
  // segment (16.8 M): refused.
  auto m = simtest::run("m16", {"MOVE Z6 F100 A1"});
  ASSERT_EQ(m->serial().errors().size(), 1u);
  EXPECT_EQ(m->serial().errors()[0], "error:113");
  EXPECT_EQ(m->serial().reasons()[0], "acceleration too low for the timer");
  EXPECT_TRUE(m->axis('Z')->step_cycles.empty());
}

TEST(StepTiming, EightMegahertzImageRunsOnItsOwnClock) {
  expect_schedule("m16-8mhz", 'Z', 200, sim::Ramp{8000000, 2000, 6000});
}

TEST(StepTiming, TimerPulsedAxisIsExactToTheCycle) {
  // Uno axis Z: the compare match itself raises STEP (OC1A), so interrupt
  // latency cannot move an edge: every pulse on its tick, zero spread. (Needs
  // simavr patch J: stock simavr stamps timer events at the next instruction
  // boundary, 0..3 cycles late.)
  expect_schedule("uno", 'Z', 400, sim::Ramp{16000000, 4000, 8000}, kTimerPulseSpread);
  // A fast move, its ramps in runs of many steps (trapezoid.h).
  expect_schedule("uno", 'Z', 20000, sim::Ramp{16000000, 60000, 200000}, kTimerPulseSpread);
}

TEST(StepTiming, TimerPulseWidthMeetsDriverMinimum) {
  sim::Machine m(simtest::image("uno"));
  const auto& step = m.watch_pin('B', 1);
  m.serial().add_line("MOVE Z500 F60000 A200000");
  ASSERT_EQ(m.run_script(16000000), sim::RunEnd::done);
  uint64_t shortest = ~0ull, longest = 0, rises = 0;
  for (size_t i = 1; i < step.size(); ++i) {
    if (step[i - 1].level && !step[i].level) {
      const uint64_t w = step[i].cycle - step[i - 1].cycle;
      shortest = std::min(shortest, w);
      longest = std::max(longest, w);
    }
    rises += step[i].level;
  }
  EXPECT_EQ(rises, 500u);
  // The board asks for 2 us (32 cycles: a DRV8825 needs 1.9 us, an A4988
  // 1 us); the pulse must also end well before the next step (266 cycles
  // apart at 60 kHz).
  EXPECT_GE(shortest, 32u);
  EXPECT_LE(longest, 64u);
}

TEST(StepTiming, SoftwarePulsesMeetTheDriversTimings) {
  // m32 X: STEP PC0, DIR PC1. A DRV8825 needs STEP high >= 1.9 us (30.4
  // cycles) and DIR stable >= 650 ns (10.4 cycles) before a rising STEP.
  sim::Machine m(simtest::image("m32-direct"));
  const auto& step = m.watch_pin('C', 0);
  const auto& dir = m.watch_pin('C', 1);
  for (const char* line : {"MOVE X300 F40000 A400000", "MOVE X-300 F40000 A400000", "MOVE X5"})
    m.serial().add_line(line);
  ASSERT_EQ(m.run_script(16000000), sim::RunEnd::done);
  uint64_t shortest = ~0ull;
  for (size_t i = 1; i < step.size(); ++i) {
    if (step[i - 1].level && !step[i].level) shortest = std::min(shortest, step[i].cycle - step[i - 1].cycle);
  }
  EXPECT_GE(shortest, 31u);
  // Every DIR change lies at least the set-up time before the next rise.
  size_t checked = 0;
  for (size_t d = 1; d < dir.size(); ++d) {
    for (const sim::PinEdge& e : step) {
      if (e.cycle > dir[d].cycle && e.level) {
        EXPECT_GE(e.cycle - dir[d].cycle, 11u);
        ++checked;
        break;
      }
    }
  }
  EXPECT_EQ(checked, 3u);  // the first move forward, back, forward again
}

TEST(StepTiming, ACruiseLongerThanOneSegmentStaysExact) {
  // 150000 steps at 160 kHz: the cruise is about 86000 steps, more than one
  // segment's 16-bit count, so the planner splits it and the fast path hands
  // over between the parts. Every step still lands on the schedule.
  expect_schedule("uno", 'Z', 150000, sim::Ramp{16000000, 160000, 300000}, kTimerPulseSpread);
}
