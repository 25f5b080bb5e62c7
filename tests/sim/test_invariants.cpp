// The step engine's invariants on the real images, swept over distance,
// rate and acceleration on every axis kind (docs/step-engine.md):
//   1. the steps on the pins equal the steps commanded and the position
//      reported (POS), for every accepted move;
//   2. no interval of the schedule is shorter than the rate allows (the
//      requested F, or the axis limit the firmware clamped it to and said so);
//   7. every step of the whole move, ramps included, falls on the core's
//      schedule: exactly on the timer-pulsed axis, within the software-pulse
//      jitter bound elsewhere.
// The moves of one axis run back to back on one machine, each followed by two
// junk lines (answered with errors while the motor moves, so the UART
// interrupts run during the motion) and POS.
//
// This file: one axis at a time, the timer pulse's width, the queue's order
// and top-speed ramps; coordinated blocks: test_invariants_coordinated.cpp;
// the grids and the schedule: invariant_checks.h.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "schedule.h"
#include "sim_fixture.h"
#include "invariant_checks.h"

namespace {

using namespace invtest;

struct Move {
  int32_t steps;
  uint32_t rate, accel;
};

struct AxisCase {
  const char* image;
  char axis;
  const char* mode;      // a MODE line sent first, or nullptr
  int pin_units;         // decoder units per commanded step (coils: half steps)
  int pos_per_step_den;  // commanded steps per full step reported by POS
  int64_t jitter;        // allowed spread of pulse lateness, cycles
};

// A deterministic sample of the whole grid (both directions, extreme
// accelerations), keeping moves short enough to simulate: `count`
// moves of at most `max_seconds` each.
std::vector<Move> sample_moves(uint32_t f_cpu, uint64_t seed, size_t count, double max_seconds) {
  std::vector<Move> out;
  uint64_t state = seed;
  for (size_t tries = 0; out.size() < count && tries < 100000; ++tries) {
    Move m;
    m.steps = kSteps[next_random(state) % 8] * (next_random(state) % 2 ? 1 : -1);
    m.rate = kRates[next_random(state) % 8];
    m.accel = kAccels[next_random(state) % 8];
    const sim::Ramp cfg{f_cpu, std::min(m.rate, f_cpu / 100), m.accel};
    if (seconds(schedule(uint32_t(std::abs(m.steps)), cfg), f_cpu) > max_seconds) continue;
    out.push_back(m);
  }
  return out;
}

void check_axis(const AxisCase& c, uint64_t seed, size_t count) {
  sim::Machine probe(simtest::image(c.image));
  const uint32_t f_cpu = probe.f_cpu();
  const std::vector<Move> moves = sample_moves(f_cpu, seed, count, 0.06);
  ASSERT_EQ(moves.size(), count);

  sim::Machine m(simtest::image(c.image));
  // A step/dir axis's DIR line: every step must follow its last change by
  // the drivers' set-up time (DRV8825: 650 ns).
  const std::vector<sim::PinEdge>* dir = nullptr;
  for (uint8_t i = 0; i < m.board().axis_count; ++i) {
    const am::AxisDescriptor& a = m.board().axes[i];
    if (a.name == c.axis && a.kind == am::AxisKind::step_dir)
      dir = &m.watch_pin(char('A' + (a.pins[1] >> 4)), uint8_t(a.pins[1] & 15));
  }
  if (c.mode) m.serial().add_line(c.mode);
  for (const Move& mv : moves) {
    std::ostringstream line;
    line << "MOVE " << c.axis << mv.steps << " F" << mv.rate << " A" << mv.accel;
    m.serial().add_line(line.str());
    m.serial().add_line("NOP");
    m.serial().add_line("NOP");
    m.serial().add_line("POS");
  }
  double seconds_total = 0;
  for (const Move& mv : moves)
    seconds_total += seconds(schedule(uint32_t(std::abs(mv.steps)),
                                      sim::Ramp{f_cpu, std::min(mv.rate, f_cpu / 100), mv.accel}),
                             f_cpu);
  // Clamped rates make moves longer than planned here: the budget only
  // guards against a hang.
  ASSERT_EQ(m.run_script(uint64_t((seconds_total * 10 + 5) * f_cpu)), sim::RunEnd::done);

  // What the firmware printed, in order: per move its clamp warning (if
  // any), ok, two errors, the position, ok.
  const std::vector<std::string>& got = m.serial().received();
  size_t at = m.serial().banner_lines();
  if (c.mode) {
    ASSERT_EQ(got.at(at), "ok");
    ++at;
  }
  const sim::AxisTrace& trace = *m.axis(c.axis);
  const std::vector<sim::Response>& resp = m.serial().responses();
  size_t stamp = 0;
  int64_t commanded = 0;
  int64_t worst = 0;
  for (size_t k = 0; k < moves.size(); ++k) {
    const Move& mv = moves[k];
    SCOPED_TRACE(testing::Message() << c.image << " " << c.axis << " move " << k << ": MOVE " << mv.steps << " F"
                                    << mv.rate << " A" << mv.accel);
    // The firmware's clamps, each said before the move runs.
    sim::Ramp cfg{f_cpu, mv.rate, mv.accel};
    for (; is_clamp(got.at(at)); ++at) {
      const std::string& w = got[at];
      uint32_t& value = w[5] == 'F' ? cfg.rate : cfg.accel;
      const uint32_t to = uint32_t(std::stoul(w.substr(18)));
      EXPECT_LT(to, value) << w;
      value = to;
    }
    ASSERT_EQ(got.at(at++), "ok");
    ASSERT_TRUE(refused(got, at));
    ASSERT_TRUE(refused(got, at));
    const std::string pos = got.at(at++);
    ASSERT_EQ(got.at(at++), "ok");
    commanded += mv.steps;

    // 1. Pins, command and report agree.
    const size_t script_index = (c.mode ? 1 : 0) + 4 * k;
    const uint64_t end = resp.at(script_index + 3).answer_cycle;
    const size_t first = stamp;
    int64_t moved = 0;
    while (stamp < trace.step_cycles.size() && trace.step_cycles[stamp] <= end) moved += trace.step_deltas[stamp++];
    const size_t pulses = stamp - first;
    EXPECT_EQ(moved, int64_t(mv.steps) * c.pin_units);
    EXPECT_EQ(pulses, size_t(std::abs(mv.steps)));
    EXPECT_DOUBLE_EQ(reported(pos, c.axis), double(commanded) / c.pos_per_step_den);
    if (pulses != size_t(std::abs(mv.steps))) continue;

    // 2 and 7. Every interval on the schedule; none shorter than the rate.
    const std::vector<uint32_t> expected = schedule(uint32_t(std::abs(mv.steps)), cfg);
    const uint32_t shortest = f_cpu / cfg.rate + (f_cpu % cfg.rate != 0);
    for (size_t i = 1; i < pulses; ++i) EXPECT_GE(expected[i], shortest) << "step " << i;
    const sim::Lateness late = sim::lateness(trace.step_cycles, first, pulses, expected);
    worst = std::max(worst, late.spread());
    EXPECT_LE(late.spread(), c.jitter) << "pulses wander " << late.lo << ".." << late.hi << " cycles off the schedule";
  }
  EXPECT_EQ(stamp, trace.step_cycles.size()) << "steps after the last move";
  if (dir) {
    const uint64_t setup = (uint64_t(f_cpu) * 650 + 999999999) / 1000000000;  // cycles, rounded up
    size_t d = 0, changes = 0;
    for (uint64_t step : trace.step_cycles) {
      while (d < dir->size() && (*dir)[d].cycle <= step) ++d;
      changes = d;
      if (d > 0) {
        EXPECT_GE(step - (*dir)[d - 1].cycle, setup) << "a step " << step - (*dir)[d - 1].cycle
                                                     << " cycles after a DIR change";
      }
    }
    EXPECT_GT(changes, moves.size() / 4) << "the sweep reverses often";
  }
  std::printf("%s %c: %zu moves, largest spread %lld cycles, stack %u bytes\n", c.image, c.axis, moves.size(),
              (long long)worst, m.stack_bytes());
}

}  // namespace

TEST(Invariants, UnoTimerPulsedAxis) { check_axis({"uno", 'Z', nullptr, 1, 1, 0}, 1, 120); }
TEST(Invariants, UnoShieldTwoPhase) { check_axis({"uno", 'X', "MODE X1", 2, 1, kSoftwareJitter}, 2, 80); }
TEST(Invariants, UnoShieldHalfStep) { check_axis({"uno", 'Y', "MODE Y2", 1, 2, kSoftwareJitter}, 3, 80); }
// The m32's direct controls are on its CNC image (the printer's takes G-code only).
TEST(Invariants, M32StepDir) { check_axis({"m32-direct", 'X', nullptr, 1, 1, kSoftwareJitter}, 5, 120); }
TEST(Invariants, M32StepDirE) { check_axis({"m32-direct", 'E', nullptr, 1, 1, kSoftwareJitter}, 6, 80); }
// The m1284 with X's direction line inverted ($3=1): every step on the pins
// the other way, the same schedule, the report the commanded count.
TEST(Invariants, M1284StepDirInverted) { check_axis({"m1284", 'X', "$3=1", -1, 1, kSoftwareJitter}, 11, 120); }
TEST(Invariants, M16StepDir) { check_axis({"m16", 'Z', nullptr, 1, 1, kSoftwareJitter}, 8, 80); }
TEST(Invariants, M16Uln2003) { check_axis({"m16", 'U', nullptr, 2, 1, kSoftwareJitter}, 9, 80); }
TEST(Invariants, M16At8MHzStepDir) { check_axis({"m16-8mhz", 'Z', nullptr, 1, 1, kSoftwareJitter}, 10, 80); }

TEST(Invariants, TimerPulseWidthStaysWithinItsBoundsUnderTraffic) {
  // The hardware pulse rises on the match and ends in the step vector, 38
  // cycles later on the Uno (the board asks for 32), 51 at a segment's last
  // step (it ends after the next segment's period is set), later by whatever
  // holds the vector off: here the UART handlers, answering junk lines
  // during every move. It must end early enough before the next match at
  // 160 kHz (100 cycles) to leave an A4988 its 1 us (16 cycles) of low time.
  sim::Machine m(simtest::image("uno"));
  const auto& step = m.watch_pin('B', 1);
  uint64_t state = 11;
  size_t commanded = 0;
  for (int k = 0; k < 40; ++k) {
    const uint32_t steps = 200 + uint32_t(next_random(state) % 3000);
    const uint32_t rate = kRates[4 + next_random(state) % 4];
    m.serial().add_line("MOVE Z" + std::to_string(k % 2 ? -int32_t(steps) : int32_t(steps)) + " F" +
                        std::to_string(rate) + " A300000");
    for (int j = 0; j < 4; ++j) m.serial().add_line("NOP");
    commanded += steps;
  }
  ASSERT_EQ(m.run_script(uint64_t(30) * m.f_cpu()), sim::RunEnd::done);
  uint64_t shortest = ~0ull, longest = 0;
  size_t rises = 0;
  for (size_t i = 1; i < step.size(); ++i) {
    if (step[i - 1].level && !step[i].level) {
      shortest = std::min(shortest, step[i].cycle - step[i - 1].cycle);
      longest = std::max(longest, step[i].cycle - step[i - 1].cycle);
    }
    rises += step[i].level;
  }
  std::printf("uno Z pulse width: %llu..%llu cycles over %zu pulses\n", (unsigned long long)shortest,
              (unsigned long long)longest, rises);
  EXPECT_EQ(rises, commanded);
  EXPECT_GE(shortest, 32u);
  EXPECT_LE(longest, 84u);  // docs/step-engine.md
}

TEST(Invariants, AMoveOnAnotherAxisWaitsForTheRunningOne) {
  // MOVE X arrives while Z cruises at 160 kHz: it starts (and energises its
  // coils through the latch, interrupts off) only once Z has stopped, so Z
  // keeps its schedule to the cycle.
  auto m = simtest::run("uno", {"MOVE Z30000 F160000 A300000", "MOVE X10 F400", "POS"});
  const auto& z = m->axis('Z')->step_cycles;
  const auto& x = m->axis('X')->step_cycles;
  ASSERT_EQ(z.size(), 30000u);
  ASSERT_EQ(x.size(), 10u);
  EXPECT_GT(x.front(), z.back());
  const std::vector<uint32_t> expected = schedule(30000, sim::Ramp{16000000, 160000, 300000});
  uint64_t due = z[0];
  for (size_t i = 1; i < z.size(); ++i) {
    due += expected[i];
    ASSERT_EQ(z[i], due) << "step " << i;
  }
}

TEST(Invariants, TopSpeedRampsAtTheAccelerationLimitStayExact) {
  // The planner's hardest case: a ramp of tens of thousands of steps up to
  // 160 kHz at the board's acceleration limit, where the step interrupt
  // leaves the main loop a third of the CPU to plan runs in. Every step on
  // its tick, ramps included.
  for (uint32_t accel : {300000u, 200000u}) {
    const std::string line = "MOVE Z64000 F160000 A" + std::to_string(accel);
    auto m = simtest::run("uno", {line, "NOP", "NOP", "NOP"}, 60);
    const auto& z = m->axis('Z')->step_cycles;
    ASSERT_EQ(z.size(), 64000u) << line;
    const std::vector<uint32_t> expected = schedule(64000, sim::Ramp{16000000, 160000, accel});
    uint64_t due = z[0];
    for (size_t i = 1; i < z.size(); ++i) {
      due += expected[i];
      ASSERT_EQ(z[i], due) << line << ": step " << i;
    }
  }
}

