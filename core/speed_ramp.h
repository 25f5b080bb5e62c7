// Constant-acceleration speed ramp: the delay before every step of a move that
// starts and ends at rest.
//
// Contract
//   plan(steps, config) prepares a move; next() then yields, step by step, the
//   number of timer ticks that precede each step (so step k happens at the sum
//   of the first k+1 intervals after the move starts). next_run() yields the
//   same sequence grouped into runs of equal intervals, which is what the step
//   queue stores: ramps are runs of one, the cruise is a single long run.
//
// Method (the "seed" method, Austin / Atmel AVR446, as in seed-000 Appendix 1)
//   c0 = 0.676 * f * sqrt(2 / accel) and c_n = c_{n-1} - 2 c_{n-1} / (4n + 1).
//   The ramp accelerates until the first c below the cruise delay and holds that
//   c (the reference tables do the same); deceleration runs the recurrence
//   backwards, c_{k-1} = c_k + 2 c_k / (4k - 1), over the last k steps, where
//   k is the number of steps needed to stop (n_accel * accel / decel). A move
//   too short to reach cruise speed turns into a triangle at the step where the
//   remaining distance equals the stopping distance.
//
//   All arithmetic is integer so the AVR and the host produce identical
//   intervals: c is kept in 1/16 tick (Q4) and the division remainder is carried
//   from step to step, so truncation does not accumulate. A 64-bit square root
//   runs once per move. Limits: tick rate <= 16 MHz, 1 <= accel, decel and
//   1 <= max_rate <= tick rate.
#pragma once
#include <stdint.h>
#include "isqrt.h"

namespace am {

struct RampConfig {
  uint32_t tick_hz;   // timer ticks per second
  uint32_t max_rate;  // cruise speed, steps/s
  uint32_t accel;     // steps/s^2
  uint32_t decel;     // steps/s^2
};

// out_of_range: a limit of ExactRamp (speed_ramp_exact.h) or of plan_delays().
enum class RampError : uint8_t { none, zero_speed, zero_accel, rate_above_tick, out_of_range };

struct StepRun {
  uint32_t interval;  // ticks before each step of the run
  uint16_t count;     // steps in the run (0 = move finished)
};

class SpeedRamp {
 public:
  static RampError check(const RampConfig& cfg) {
    if (cfg.max_rate == 0) return RampError::zero_speed;
    if (cfg.accel == 0 || cfg.decel == 0) return RampError::zero_accel;
    if (cfg.max_rate > cfg.tick_hz) return RampError::rate_above_tick;
    return RampError::none;
  }

  // First delay of the ramp, in ticks (Q4): 0.676 f sqrt(2/a).
  static uint32_t first_delay_q4(uint32_t tick_hz, uint32_t accel) {
    // (0.676^2 * 2) = 0.913952; c0^2 = 0.913952 f^2 / a; Q4 squares to 2^8.
    const uint64_t khz = tick_hz / 1000u;
    const uint64_t c0_squared = khz * khz * 913952u / accel;
    return isqrt64(c0_squared << 8);
  }

  RampError plan(uint32_t steps, const RampConfig& cfg) {
    const RampError err = check(cfg);
    if (err != RampError::none) return err;
    cfg_ = cfg;
    remaining_ = steps;
    c_ = first_delay_q4(cfg.tick_hz, cfg.accel);
    c_min_ = (cfg.tick_hz << 4) / cfg.max_rate;
    rest_ = 0;
    n_ = 0;
    stop_steps_ = 0;
    phase_ = Phase::accel;
    return RampError::none;
  }

  // The same method with its delays given directly: c0 and the cruise delay in
  // Q4 ticks, accel/decel only as their ratio (for the decelerating part).
  // This is how tables stated in physical units (seed-000 Appendix 1: c0 =
  // 16940.51 us for 100 rad/s^2 at 0.0314 rad/step) are reproduced exactly,
  // without rounding the acceleration to whole steps/s^2 first.
  RampError plan_delays(uint32_t steps, uint32_t c0_q4, uint32_t cruise_q4, uint32_t accel,
                        uint32_t decel) {
    if (cruise_q4 == 0) return RampError::zero_speed;
    if (accel == 0 || decel == 0) return RampError::zero_accel;
    // 2 c + rest must stay below 2^32 in the recurrence.
    if (c0_q4 >= (uint32_t(1) << 30)) return RampError::out_of_range;
    cfg_ = RampConfig{0, 0, accel, decel};
    remaining_ = steps;
    c_ = c0_q4;
    c_min_ = cruise_q4;
    rest_ = 0;
    n_ = 0;
    stop_steps_ = 0;
    phase_ = Phase::accel;
    return RampError::none;
  }

  // Unrounded (Q4) delay of the step next() will return while accelerating;
  // on entering cruise or deceleration the step itself may still change it.
  uint32_t accel_delay_q4() const { return c_; }

  bool finished() const { return remaining_ == 0; }
  uint32_t remaining() const { return remaining_; }

  // Ticks before the next step; 0 once the move is finished.
  uint32_t next() {
    const StepRun run = take(1);
    return run.count ? run.interval : 0;
  }

  // The next run of equal intervals (count 0 once finished).
  StepRun next_run() { return take(0xFFFF); }

 private:
  enum class Phase : uint8_t { accel, cruise, decel };

  static uint32_t round_q4(uint32_t q4) { return (q4 + 8) >> 4; }

  // Steps needed to stop after n accelerating steps: n * accel / decel.
  uint32_t stopping_steps(uint32_t n) const {
    return uint32_t((uint64_t(n) * cfg_.accel + cfg_.decel / 2) / cfg_.decel);
  }

  void enter_decel() {
    phase_ = Phase::decel;
    rest_ = 0;
  }

  // Decides the phase of the step about to be emitted and updates c_ to its
  // delay. Called once per step, before the step is counted.
  void prepare_step() {
    if (phase_ == Phase::accel) {
      if (n_ > 0 && remaining_ <= stopping_steps(n_)) {
        enter_decel();
      } else if (n_ > 0 && c_ < c_min_) {
        phase_ = Phase::cruise;
        stop_steps_ = stopping_steps(n_);
      }
    } else if (phase_ == Phase::cruise && remaining_ <= stop_steps_) {
      enter_decel();
    }
    if (phase_ == Phase::decel) {
      // Going from c_k to c_{k-1} with k = remaining steps.
      const uint32_t den = 4 * remaining_ - 1;
      const uint32_t num = 2 * c_ + rest_;
      c_ += num / den;
      rest_ = num % den;
    }
  }

  // After an accelerating step: c_n = c_{n-1} - 2 c_{n-1} / (4n + 1).
  void advance_accel() {
    ++n_;
    const uint32_t den = 4 * n_ + 1;
    const uint32_t num = 2 * c_ + rest_;
    c_ -= num / den;
    rest_ = num % den;
  }

  StepRun take(uint16_t max_count) {
    if (remaining_ == 0) return StepRun{0, 0};
    prepare_step();
    StepRun run{round_q4(c_), 1};
    if (phase_ == Phase::cruise) {
      uint32_t span = remaining_ - stop_steps_;
      if (span > max_count) span = max_count;
      run.count = uint16_t(span);
    }
    remaining_ -= run.count;
    if (phase_ == Phase::accel) advance_accel();
    return run;
  }

  RampConfig cfg_{};
  uint32_t remaining_ = 0;
  uint32_t c_ = 0;       // delay of the next step, Q4 ticks
  uint32_t c_min_ = 0;   // cruise delay, Q4 ticks
  uint32_t rest_ = 0;    // remainder carried by the recurrence
  uint32_t n_ = 0;       // accelerating steps taken
  uint32_t stop_steps_ = 0;
  Phase phase_ = Phase::accel;
};

}  // namespace am
