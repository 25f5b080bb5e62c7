// The ideal-motion model the TrapezoidRuns tests compare with
// (test_trapezoid.cpp, test_trapezoid_parts.cpp): a long double model of a
// block written from the contract, a runner that checks every event of a
// block against it, the sweep's speeds and accelerations, and the probe
// that reads the generator's private state between calls.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/motion/trapezoid.h"

namespace am {
// Reads the generator's state between calls: which call plans a run (float
// work) and which only hands out a part of it.
struct TrapezoidProbe {
  template <class R>
  static bool pending(const BasicTrapezoidRuns<R>& r) {
    return r.left_[0] | r.left_[1];
  }
  template <class R>
  static bool cruise_next(const BasicTrapezoidRuns<R>& r) {
    return !pending(r) && r.done_ >= r.edge_[0] && r.n_ - r.done_ > r.edge_[1];
  }
  // The next call plans a ramp run or the event across a phase boundary.
  template <class R>
  static bool plans_next(const BasicTrapezoidRuns<R>& r) {
    return !pending(r) && r.done_ != r.n_ && !cruise_next(r);
  }
  template <class R>
  static bool accelerating_next(const BasicTrapezoidRuns<R>& r) {
    return r.done_ + 1 < r.edge_[0];
  }
  template <class R>
  static bool decelerating_next(const BasicTrapezoidRuns<R>& r) {
    return r.n_ - r.done_ < r.edge_[1];
  }
};
}  // namespace am

namespace trapezoidtest {

using am::StepRun;
using am::TrapezoidBlock;

constexpr uint32_t kLongestInterval = 256u * 65536u;
const uint32_t kTickRates[] = {16000000, 8000000, 20000000};

// The ideal motion of a block, in long double and seconds, written from the
// contract: closed-form phase times, position as a function of time.
struct Ideal {
  enum Shape { cruise_only, trapezoid, triangle, all_decel, all_accel, kShapes };
  uint32_t c;  // ceil(tick_hz / cruise), exact
  long double n, a, v0, v1, vp, d_accel, t_accel, t_cruise, t_end;
  Shape shape;

  Ideal(const TrapezoidBlock& b, uint32_t tick_hz) : n(b.events), a(b.accel) {
    // A float significand times an integer below 2^33 is exact in long double.
    const long double f = tick_hz, cruise = b.cruise;
    c = uint32_t(ceill(f / cruise));
    while (c > 1 && (c - 1) * cruise >= f) --c;
    while (c * cruise < f) ++c;
    const long double top = f / c;
    v0 = std::min<long double>(b.entry, top);
    v1 = std::min<long double>(b.exit, top);
    shape = trapezoid;
    if (v1 * v1 > v0 * v0 + 2 * a * n) {
      v1 = sqrtl(v0 * v0 + 2 * a * n);
      shape = all_accel;
    } else if (v0 * v0 > v1 * v1 + 2 * a * n) {
      v1 = sqrtl(v0 * v0 - 2 * a * n);
      shape = all_decel;
    }
    const long double peak_sq = a * n + (v0 * v0 + v1 * v1) / 2;
    vp = peak_sq >= top * top ? top : sqrtl(peak_sq);
    if (shape == trapezoid && vp < top) shape = triangle;
    if (shape == trapezoid && v0 == top && v1 == top) shape = cruise_only;
    d_accel = (vp * vp - v0 * v0) / (2 * a);
    const long double d_decel = (vp * vp - v1 * v1) / (2 * a);
    t_accel = (vp - v0) / a;
    t_cruise = std::max<long double>(0, n - d_accel - d_decel) / vp;
    t_end = t_accel + t_cruise + (vp - v1) / a;
  }

  long double position(long double t) const {
    if (t <= t_accel) return v0 * t + a * t * t / 2;
    if (t <= t_accel + t_cruise) return d_accel + vp * (t - t_accel);
    if (t <= t_end) {
      const long double s = t_end - t;
      return n - v1 * s - a * s * s / 2;
    }
    return n + v1 * (t - t_end);  // the next block goes on at the exit speed
  }
};

struct Outcome {
  long double worst = 0;  // max |e - x(t_e)| over the block, events
  uint64_t end_ticks = 0;  // the last event's tick, from the block's start
  uint32_t runs = 0;
  std::string broken;  // the first rule broken, empty if none
};

// Runs one block through `runs` and checks every event. `offset` (s) is
// added to the block's clock for the reference: 0 compares with the block's
// own ideal motion.
template <class Runs>
Outcome run_block(Runs& runs, const TrapezoidBlock& b, uint32_t tick_hz, long double offset = 0) {
  Outcome out;
  const Ideal ideal(b, tick_hz);
  if (!runs.start(b, tick_hz)) {
    out.broken = "refused";
    return out;
  }
  const long double per_tick = 1.0L / tick_hz;
  uint64_t t = 0, e = 0;
  for (;;) {
    const StepRun r = runs.next_run();
    if (r.count == 0) {
      if (r.interval != 0) out.broken = "end marker not {0,0}";
      break;
    }
    ++out.runs;
    if (r.interval < ideal.c) out.broken = "interval below ceil(tick_hz / cruise)";
    if (r.interval > kLongestInterval) out.broken = "interval above 256 * 65536";
    if (e + r.count > b.events) {
      out.broken = "more than N events";
      return out;
    }
    for (uint32_t j = 0; j < r.count; ++j) {
      t += r.interval;
      ++e;
      const long double err = fabsl(e - ideal.position(t * per_tick + offset));
      if (!(err <= out.worst)) out.worst = err;  // NaN shows as NaN
    }
    if (!out.broken.empty()) return out;
  }
  if (e != b.events) out.broken = "fewer than N events";
  if (runs.events_done() != b.events) out.broken = "events_done() != N";
  if (runs.next_run().count != 0) out.broken = "runs after the end";
  out.end_ticks = t;
  return out;
}

inline std::string describe(const TrapezoidBlock& b, uint32_t tick_hz) {
  char s[160];
  snprintf(s, sizeof s, "N=%u entry=%g cruise=%g exit=%g accel=%g tick_hz=%u", b.events,
           double(b.entry), double(b.cruise), double(b.exit), double(b.accel), tick_hz);
  return s;
}

const float kCruises[] = {10, 77.7f, 1000, 12345.6f, 99999, 250000};
const float kAccels[] = {10, 517, 33333, 2e6f, 1.5e8f, 2147483648.0f};
struct SpeedPair {
  float entry, exit;  // fractions of the cruise speed
};
const SpeedPair kSpeedPairs[] = {{0, 0},     {1, 1},        {1, 0},      {0, 1},
                                 {0.37f, 0.81f}, {0.9f, 0.05f}, {1.5f, 2}, {0.999f, 0.6f}};
constexpr int kPairs = sizeof kSpeedPairs / sizeof kSpeedPairs[0];

inline TrapezoidBlock block(uint32_t n, float cruise, float accel, const SpeedPair& p) {
  return TrapezoidBlock{n, p.entry * cruise, cruise, p.exit * cruise, accel};
}


}  // namespace trapezoidtest
