// The step engine's invariants on the real images for coordinated blocks
// (several axes in one MOVE, docs/step-engine.md): every axis ends on its
// target (pins = command = POS) and every step of every axis falls on the
// block's schedule, computed here from the documented rules; and the
// timer-pulsed axis moves alone. One axis at a time: test_invariants.cpp;
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

}  // namespace

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
// 40 cycles each), on top of the UART's hold-off; 89 cycles seen
// (docs/step-engine.md).
constexpr int64_t kCoordinatedCoilJitter = 128;

const int kUnits1[] = {1, 1, 1, 1, 2};
const int kShield[] = {2, 2, 2};
const int kM16[] = {1, 2};

}  // namespace

TEST(Invariants, M32CoordinatedBlocks) { check_coordinated({"m32-direct", "XYZE", kUnits1, kSoftwareJitter, 40000}, 21, 60); }
TEST(Invariants, M1284CoordinatedBlocks) { check_coordinated({"m1284", "XYZE", kUnits1, kSoftwareJitter, 40000}, 23, 60); }
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
