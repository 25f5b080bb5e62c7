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
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "schedule.h"
#include "sim_fixture.h"

namespace {

// A clamp the firmware says before a move runs: `[MSG:F clamped to 20000]`.
bool is_clamp(const std::string& l) { return l.rfind("[MSG:", 0) == 0 && l.find(" clamped to ") == 6; }

// A refused line's two lines at `at`, its reason and grbl's `error:N`.
bool refused(const std::vector<std::string>& got, size_t& at) {
  const bool ok = got.at(at).rfind("[MSG:", 0) == 0 && got.at(at + 1).rfind("error:", 0) == 0;
  at += 2;
  return ok;
}

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

constexpr uint32_t kRates[] = {50, 400, 4000, 20000, 40000, 100000, 160000, 250000};
constexpr uint32_t kAccels[] = {4, 800, 20000, 400000, 4000000, 20000000, 1000000000, 2147483647};
constexpr int32_t kSteps[] = {1, 2, 3, 7, 18, 100, 1000, 4000};

uint64_t next_random(uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return state >> 33;
}

std::vector<uint32_t> schedule(uint32_t steps, const sim::Ramp& cfg) {
  const std::vector<uint32_t> out = sim::planned_schedule(steps, cfg);
  EXPECT_EQ(out.size(), steps);
  return out;
}

double seconds(const std::vector<uint32_t>& iv, uint32_t f_cpu) {
  double t = 0;
  for (uint32_t i : iv) t += i;
  return t / f_cpu;
}

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

// "pos X:1 Y:-2.5 ..." -> the value of `axis`, in full steps.
double reported(const std::string& pos, char axis) {
  const std::string key = std::string(" ") + axis + ":";
  const size_t at = pos.find(key);
  EXPECT_NE(at, std::string::npos) << pos;
  return at == std::string::npos ? 0 : std::atof(pos.c_str() + at + key.size());
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
      if (d > 0) EXPECT_GE(step - (*dir)[d - 1].cycle, setup) << "a step " << step - (*dir)[d - 1].cycle
                                                             << " cycles after a DIR change";
    }
    EXPECT_GT(changes, moves.size() / 4) << "the sweep reverses often";
  }
  std::printf("%s %c: %zu moves, largest spread %lld cycles, stack %u bytes\n", c.image, c.axis, moves.size(),
              (long long)worst, m.stack_bytes());
}

// Software pulses trail their match by the latency of the step interrupt:
// 6 cycles of spread on a quiet line (test_step_timing.cpp), up to about 30
// with the UART receiving and answering during the motion (the UART
// handlers' prologues, before they re-enable interrupts).
constexpr int64_t kSoftwareJitter = 48;  // docs/step-engine.md

}  // namespace

TEST(Invariants, UnoTimerPulsedAxis) { check_axis({"uno", 'Z', nullptr, 1, 1, 0}, 1, 120); }
TEST(Invariants, UnoShieldTwoPhase) { check_axis({"uno", 'X', "MODE X1", 2, 1, kSoftwareJitter}, 2, 80); }
TEST(Invariants, UnoShieldHalfStep) { check_axis({"uno", 'Y', "MODE Y2", 1, 2, kSoftwareJitter}, 3, 80); }
// The m32's direct controls are on its CNC image (the printer's takes G-code only).
TEST(Invariants, M32StepDir) { check_axis({"m32-direct", 'X', nullptr, 1, 1, kSoftwareJitter}, 5, 120); }
TEST(Invariants, M32StepDirE) { check_axis({"m32-direct", 'E', nullptr, 1, 1, kSoftwareJitter}, 6, 80); }
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

namespace {

// Several axes in one MOVE: a coordinated block. Every axis ends on its
// target (pins = command = POS) and every step of every axis falls on the
// block's schedule, computed here from the documented rules:
//   - its smoothing level L (core/motion/amass.h): the largest L <= 3 with
//     F 2^L within a quarter of the board's step-rate limit and
//     N 2^L <= 2^24
//     (F the rate after the clamps the firmware reported);
//   - its N 2^L events on the core's trapezoid for F 2^L and A 2^L;
//   - at L = 0 the dominant axis (most steps) at every event and every
//     other axis's k-th step on event ceil((k N - h) / n), h = floor(N / 2)
//     (Bresenham, core/motion/line_dda.h); at L > 0 every axis's k-th step
//     on event ceil(k N 2^L / n), the dominant's on event k 2^L.
struct CoordinatedCase {
  const char* image;
  const char* axes;      // the letters taking part
  const int* pin_units;  // per letter: decoder units per step
  int64_t jitter;        // allowed spread of an axis's lateness, cycles
  uint32_t max_step_rate;  // the board's kMaxStepRate
};

// Rates that reach every smoothing level on every board (events up to a
// quarter of the limit: 10000/s on the m32, 5000/s on the Uno and the m16)
// and the clamp.
constexpr uint32_t kCoordinatedRates[] = {50, 400, 1000, 2000, 4000, 8000, 20000, 100000};


void check_coordinated(const CoordinatedCase& c, uint64_t seed, size_t count) {
  sim::Machine m(simtest::image(c.image));
  const uint32_t f_cpu = m.f_cpu();
  const size_t n_axes = std::strlen(c.axes);
  struct Coordinated {
    std::vector<int32_t> steps;
    uint32_t rate, accel;
  };
  std::vector<Coordinated> moves;
  uint64_t state = seed;
  while (moves.size() < count) {
    Coordinated mv;
    size_t moving = 0;
    for (size_t a = 0; a < n_axes; ++a) {
      const bool on = next_random(state) % 4 != 0;
      const int32_t n = on ? kSteps[next_random(state) % 7] * (next_random(state) % 2 ? 1 : -1) : 0;
      mv.steps.push_back(n);
      moving += n != 0;
    }
    if (moving < 2) continue;
    mv.rate = kCoordinatedRates[next_random(state) % 8];
    mv.accel = kAccels[1 + next_random(state) % 7];
    uint32_t dominant = 0;
    for (int32_t n : mv.steps) dominant = std::max(dominant, uint32_t(std::abs(n)));
    const sim::Ramp cfg{f_cpu, std::min(mv.rate, 20000u), std::min(mv.accel, 400000u)};
    if (seconds(schedule(dominant, cfg), f_cpu) > 0.05) continue;
    moves.push_back(mv);
  }
  for (const Coordinated& mv : moves) {
    std::string line = "MOVE";
    for (size_t a = 0; a < n_axes; ++a) line += std::string(" ") + c.axes[a] + std::to_string(mv.steps[a]);
    line += " F" + std::to_string(mv.rate) + " A" + std::to_string(mv.accel);
    m.serial().add_line(line);
    m.serial().add_line("NOP");
    m.serial().add_line("POS");
  }
  ASSERT_EQ(m.run_script(uint64_t(60) * f_cpu), sim::RunEnd::done);

  const std::vector<std::string>& got = m.serial().received();
  const std::vector<sim::Response>& resp = m.serial().responses();
  size_t at = m.serial().banner_lines();
  int64_t worst = 0;
  int levels[4] = {};
  std::vector<size_t> stamp(n_axes, 0);
  std::vector<int64_t> commanded(n_axes, 0);
  for (size_t k = 0; k < moves.size(); ++k) {
    const Coordinated& mv = moves[k];
    SCOPED_TRACE(testing::Message() << c.image << " move " << k << ": " << resp.at(3 * k).line);
    sim::Ramp cfg{f_cpu, mv.rate, mv.accel};
    for (; is_clamp(got.at(at)); ++at) {
      const std::string& w = got[at];
      uint32_t& value = w[5] == 'F' ? cfg.rate : cfg.accel;
      value = uint32_t(std::stoul(w.substr(18)));
    }
    ASSERT_EQ(got.at(at++), "ok");
    ASSERT_TRUE(refused(got, at));
    const std::string pos = got.at(at++);
    ASSERT_EQ(got.at(at++), "ok");
    const uint64_t end = resp.at(3 * k + 2).answer_cycle;

    // Each axis's pulses of this move.
    uint32_t events = 0;
    size_t dominant = 0;
    std::vector<std::vector<uint64_t>> pulses(n_axes);
    for (size_t a = 0; a < n_axes; ++a) {
      const sim::AxisTrace& trace = *m.axis(c.axes[a]);
      int64_t moved = 0;
      while (stamp[a] < trace.step_cycles.size() && trace.step_cycles[stamp[a]] <= end) {
        pulses[a].push_back(trace.step_cycles[stamp[a]]);
        moved += trace.step_deltas[stamp[a]++];
      }
      commanded[a] += mv.steps[a];
      EXPECT_EQ(moved, int64_t(mv.steps[a]) * c.pin_units[a]) << c.axes[a];
      EXPECT_EQ(pulses[a].size(), size_t(std::abs(mv.steps[a]))) << c.axes[a];
      EXPECT_DOUBLE_EQ(reported(pos, c.axes[a]), double(commanded[a])) << c.axes[a];
      if (uint32_t(std::abs(mv.steps[a])) > events) {
        events = uint32_t(std::abs(mv.steps[a]));
        dominant = a;
      }
    }
    bool counts_ok = true;
    for (size_t a = 0; a < n_axes; ++a) counts_ok = counts_ok && pulses[a].size() == size_t(std::abs(mv.steps[a]));
    if (!counts_ok) continue;

    // The block's events and their times, from its first event on.
    const uint8_t level = sim::smoothing_level(events, cfg.rate, c.max_step_rate);
    levels[level] += 1;
    const uint32_t fine = events << level;
    const std::vector<uint32_t> expected = sim::smoothed_events(events, cfg, level);
    ASSERT_EQ(expected.size(), fine);
    std::vector<uint64_t> at_event(fine + 1, 0);  // ticks after event 1
    for (uint32_t e = 2; e <= fine; ++e) at_event[e] = at_event[e - 1] + expected[e - 1];
    // No step of the dominant axis faster than F allows.
    for (uint32_t k = 2; k <= events; ++k)
      EXPECT_GE(at_event[k << level] - at_event[(k - 1) << level], f_cpu / cfg.rate) << "step " << k;
    // Every axis's steps on their events, the dominant's first as the anchor.
    const uint64_t anchor = pulses[dominant][0] - at_event[uint32_t(1) << level];
    for (size_t a = 0; a < n_axes; ++a) {
      const uint64_t n = uint64_t(std::abs(mv.steps[a]));
      if (n == 0) continue;
      int64_t lo = INT64_MAX, hi = INT64_MIN;
      for (uint64_t k = 1; k <= n; ++k) {
        const uint64_t event = level ? (k * fine + n - 1) / n : (k * events - events / 2 + n - 1) / n;
        const int64_t late = int64_t(pulses[a][k - 1]) - int64_t(anchor + at_event[event]);
        lo = std::min(lo, late);
        hi = std::max(hi, late);
      }
      worst = std::max(worst, hi - lo);
      EXPECT_LE(hi - lo, c.jitter) << c.axes[a] << " (level " << int(level) << ") wanders " << lo << ".." << hi;
    }
  }
  std::printf("%s %s coordinated: %zu moves (smoothing levels 0..3: %d %d %d %d), largest spread of an axis %lld cycles\n",
              c.image, c.axes, moves.size(), levels[0], levels[1], levels[2], levels[3], (long long)worst);
  for (int l = 0; l < 4; ++l) EXPECT_GT(levels[l], 0) << "no move at smoothing level " << l;
}

// A coordinated event's outputs leave in axis order, the shield's latch once
// every axis has staged its step: on the Uno an axis's edge moves by the
// work of the axes stepping before it in that event (shield staging about
// 40 cycles each), on top of the UART's hold-off; 87 cycles seen
// (docs/step-engine.md).
constexpr int64_t kCoordinatedCoilJitter = 128;

const int kUnits1[] = {1, 1, 1, 1, 2};
const int kShield[] = {2, 2, 2};
const int kM16[] = {1, 2};

}  // namespace

TEST(Invariants, M32CoordinatedBlocks) { check_coordinated({"m32-direct", "XYZE", kUnits1, kSoftwareJitter, 40000}, 21, 60); }
TEST(Invariants, UnoCoordinatedShield) { check_coordinated({"uno", "XY", kShield, kCoordinatedCoilJitter, 20000}, 22, 40); }
TEST(Invariants, M16CoordinatedBlocks) { check_coordinated({"m16", "ZU", kM16, kSoftwareJitter, 20000}, 23, 40); }

TEST(Invariants, TheTimerPulsedAxisMovesAlone) {
  auto m = simtest::run("uno", {"MOVE Z10 X5", "MOVE X5 Z0", "POS"});
  const std::vector<sim::Response>& r = m->serial().responses();
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r[0].answer, "error:109");
  EXPECT_EQ(r[0].reason, "the hardware-timed axis moves alone");
  EXPECT_EQ(r[1].answer, "ok");  // Z0 takes no part
  EXPECT_TRUE(m->axis('Z')->step_cycles.empty());
  EXPECT_EQ(m->axis('X')->step_cycles.size(), 5u);
}
