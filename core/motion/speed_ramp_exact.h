// Exact constant-acceleration ramp: every step at the time ideal kinematics
// put it, rounded to the tick, with no accumulated error.
//
// Contract
//   Same interface and configuration as SpeedRamp (plan, next, next_run,
//   finished, remaining); only the step times differ. Step k (1-based) of an
//   N-step move happens at T_k, the exact time at which a body starting at rest
//   with acceleration `accel`, cruising at `max_rate` and stopping with `decel`
//   exactly at position N reaches position k:
//     accel part   T_k = f sqrt(2k / a)                     (k <= v^2 / 2a)
//     cruise       T_k = f (v / 2a + k / v)
//     decel part   T_k = T_end - f sqrt(2 (N - k) / d)      (N - k <= v^2 / 2d)
//   with T_end = f (v/2a + v/2d + N/v) for a trapezoid, or f sqrt(2N/a + 2N/d)
//   for a triangle (a move too short to reach v; the peak falls at position
//   N d / (a + d)). Each interval is T_k - T_{k-1} of the rounded absolute
//   times, so the sum of the first k intervals is T_k within one tick.
//
// Arithmetic (integer only; this runs in the main loop, never in the ISR)
//   Ramp steps: T = round(sqrt(X) / 2) with X = floor(8 f^2 k / a) kept by an
//   exact quotient/remainder accumulator and one isqrt64() per step. 64 bits
//   are needed: X is (2 T)^2 in ticks^2, beyond 32 bits as soon as a ramp is
//   longer than 32768 ticks (2 ms at 16 MHz), i.e. always.
//   Cruise steps: Q8 tick accumulator advanced by 256 f / v with its remainder
//   carried (64-bit add, no division or root).
//   Cruise intervals alternate between floor and ceil of f / v when that is
//   not an integer (that is what keeps the position exact), so next_run()
//   returns shorter runs than SpeedRamp's single cruise run.
//
// Limits (check() reports out_of_range otherwise)
//   tick rate <= 2^30 Hz; 1 <= accel, decel <= 2^24 steps/s^2;
//   1 <= max_rate <= tick rate / 2 and <= 2^24; every ramp no longer than
//   2^30 ticks (f v / a and f v / d < 2^30: 67 s at 16 MHz).
#pragma once
#include <stdint.h>
#include "../math/isqrt.h"
#include "speed_ramp.h"

namespace am {

class ExactRamp {
 public:
  static RampError check(const RampConfig& cfg) {
    const RampError err = SpeedRamp::check(cfg);
    if (err != RampError::none) return err;
    constexpr uint32_t max_rate_or_accel = uint32_t(1) << 24;
    constexpr uint64_t max_ramp_ticks = uint64_t(1) << 30;
    if (cfg.tick_hz > (uint32_t(1) << 30) || cfg.max_rate > cfg.tick_hz / 2 ||
        cfg.max_rate > max_rate_or_accel || cfg.accel > max_rate_or_accel ||
        cfg.decel > max_rate_or_accel)
      return RampError::out_of_range;
    const uint32_t slower = cfg.accel < cfg.decel ? cfg.accel : cfg.decel;
    if (uint64_t(cfg.tick_hz) * cfg.max_rate / slower >= max_ramp_ticks)
      return RampError::out_of_range;
    return RampError::none;
  }

  RampError plan(uint32_t steps, const RampConfig& cfg) {
    const RampError err = check(cfg);
    if (err != RampError::none) return err;
    const uint64_t f = cfg.tick_hz, v = cfg.max_rate, a = cfg.accel, d = cfg.decel;
    steps_ = steps;
    k_ = 0;
    last_t_ = 0;
    pending_ = 0;

    // Ramp accumulators: X(k) = floor(8 f^2 k / a) = k q + floor(k r / a).
    const uint64_t eight_f2 = 8 * f * f;
    acc_.init(eight_f2, cfg.accel, 0);

    // Whole steps inside each ramp: v^2 = 2a n_a + rem_a, likewise for d.
    const uint64_t v2 = v * v;
    const uint64_t n_a = v2 / (2 * a), rem_a = v2 % (2 * a);
    const uint64_t n_d = v2 / (2 * d), rem_d = v2 % (2 * d);
    const bool trapezoid = is_trapezoid(steps, n_a, rem_a, n_d, rem_d, a, d);

    const uint32_t decel_steps =  // steps timed from the end
        trapezoid ? uint32_t(n_d + (rem_d ? 1 : 0)) : steps - uint32_t(uint64_t(steps) * d / (a + d));
    split_ = steps - decel_steps;
    ramp_end_ = trapezoid ? uint32_t(n_a) : split_;
    dec_.init(eight_f2, cfg.decel, decel_steps);

    if (trapezoid) {
      // Q8 times: f v / 2a, f v / 2d and the cruise term f k / v.
      const uint64_t from_start_q8 = (f * v << 8) / (2 * a);
      const uint64_t to_end_q8 = (f * v << 8) / (2 * d);
      cruise_.init(f, cfg.max_rate, ramp_end_, from_start_q8);
      t_end_ = (from_start_q8 + to_end_q8 + q8_ratio(f * steps, v) + 128) >> 8;
    } else {
      t_end_ = (isqrt64(acc_.value_at(steps) + dec_.value_at(steps)) + 1) >> 1;
    }
    return RampError::none;
  }

  bool finished() const { return k_ == steps_ && pending_ == 0; }
  uint32_t remaining() const { return steps_ - k_ + (pending_ ? 1 : 0); }

  // Ticks before the next step; 0 once the move is finished.
  uint32_t next() {
    if (pending_) {
      const uint32_t interval = pending_;
      pending_ = 0;
      return interval;
    }
    if (k_ == steps_) return 0;
    return advance();
  }

  // The next run of equal intervals (count 0 once finished).
  StepRun next_run() {
    StepRun run{next(), 0};
    if (run.interval == 0) return run;
    run.count = 1;
    while (run.count < 0xFFFF && k_ < steps_) {
      const uint32_t interval = advance();
      if (interval != run.interval) {
        pending_ = interval;
        break;
      }
      ++run.count;
    }
    return run;
  }

 private:
  // floor(8 f^2 j / rate) for j walked by +-1, without dividing per step.
  struct RootArg {
    uint64_t quotient = 0;  // floor(8 f^2 / rate)
    uint32_t rest = 0;      // 8 f^2 mod rate
    uint32_t rate = 1;
    uint64_t x = 0;         // floor(8 f^2 j / rate)
    uint32_t frac = 0;      // (8 f^2 j) mod rate

    void init(uint64_t eight_f2, uint32_t r, uint32_t j) {
      rate = r;
      quotient = eight_f2 / r;
      rest = uint32_t(eight_f2 % r);
      x = value_at(j);
      frac = uint32_t(uint64_t(rest) * j % r);
    }
    uint64_t value_at(uint32_t j) const { return quotient * j + uint64_t(rest) * j / rate; }
    void up() {
      x += quotient;
      frac += rest;
      if (frac >= rate) {
        frac -= rate;
        ++x;
      }
    }
    void down() {
      x -= quotient;
      if (frac < rest) {
        frac += rate;
        --x;
      }
      frac -= rest;
    }
    // round(f sqrt(2 j / rate)) in ticks.
    uint64_t ticks() const { return (uint64_t(isqrt64(x)) + 1) >> 1; }
  };

  // Cruise time in Q8 ticks: f v / 2a + f k / v, k walked upwards.
  struct CruiseClock {
    uint64_t q8 = 0;     // f v / 2a + floor(256 f k / v) / 256, Q8
    uint64_t step = 0;   // floor(256 f / v)
    uint32_t rest = 0;   // 256 f mod v
    uint32_t rate = 1;
    uint32_t frac = 0;

    void init(uint64_t f, uint32_t v, uint32_t k, uint64_t offset_q8) {
      rate = v;
      step = (f << 8) / v;
      rest = uint32_t((f << 8) % v);
      const uint64_t fk = f * k;
      q8 = offset_q8 + q8_ratio(fk, v);
      frac = uint32_t(((fk % v) << 8) % v);
    }
    uint64_t up() {
      q8 += step;
      frac += rest;
      if (frac >= rate) {
        frac -= rate;
        ++q8;
      }
      return (q8 + 128) >> 8;
    }
  };

  // floor(256 n / v) without overflowing 256 n.
  static uint64_t q8_ratio(uint64_t n, uint64_t v) { return ((n / v) << 8) + ((n % v) << 8) / v; }

  // v^2/2a + v^2/2d <= N, from the whole parts n and remainders rem of v^2/2r.
  static bool is_trapezoid(uint64_t steps, uint64_t n_a, uint64_t rem_a, uint64_t n_d,
                           uint64_t rem_d, uint64_t a, uint64_t d) {
    if (n_a + n_d + 2 <= steps) return true;
    if (n_a + n_d > steps) return false;
    // Fractions rem_a / 2a + rem_d / 2d against the spare 0 or 1 step.
    return rem_a * d + rem_d * a <= (steps - n_a - n_d) * 2 * a * d;
  }

  // Absolute time of step k_ + 1, and the interval since step k_.
  uint32_t advance() {
    ++k_;
    uint64_t t;
    if (k_ <= split_) {
      if (k_ <= ramp_end_) {
        acc_.up();
        t = acc_.ticks();
      } else {
        t = cruise_.up();
      }
    } else {
      dec_.down();
      t = t_end_ - dec_.ticks();
    }
    const uint32_t interval = uint32_t(t - last_t_);
    last_t_ = t;
    return interval;
  }

  uint32_t steps_ = 0;
  uint32_t k_ = 0;         // steps whose interval has been computed
  uint32_t split_ = 0;     // last step timed from the start
  uint32_t ramp_end_ = 0;  // last step on the acceleration parabola
  uint64_t last_t_ = 0;    // rounded absolute time of step k_
  uint64_t t_end_ = 0;     // rounded time of the last step
  uint32_t pending_ = 0;   // interval computed ahead by next_run()
  RootArg acc_, dec_;
  CruiseClock cruise_;
};

}  // namespace am
