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
//   The ramp accelerates until the first c below the cruise delay and cruises
//   at the cruise delay itself from that step on (the reference tables run
//   that first c, up to 0.5 % too fast: here no interval is ever shorter than
//   max_rate allows, however large the acceleration, and a c0 already below
//   the cruise delay starts the move at cruise speed); deceleration runs the recurrence
//   backwards, c_{k-1} = c_k + 2 c_k / (4k - 1), over the last k steps, where
//   k is the number of steps needed to stop (n_accel * accel / decel). A move
//   too short to reach cruise speed turns into a triangle at the step where the
//   remaining distance equals the stopping distance.
//
//   All arithmetic is integer so the AVR and the host produce identical
//   intervals: c is kept in 1/256 tick (Q8) and the division remainder is carried
//   from step to step, so truncation does not accumulate (Q4 was not enough to
//   give seed-000 Appendix 1 to the microsecond; Q8 gives every delay). A
//   64-bit square root runs once per move. Limits: tick rate <= 16 MHz,
//   1 <= max_rate <= tick rate, and accel, decel large enough that the first
//   delay stays below 2^31 Q8 (8.1 M ticks: >= 4 steps/s^2 at 16 MHz,
//   >= 1 at 8 MHz); check() reports out_of_range otherwise.
#pragma once
#include <stdint.h>
#include "../math/isqrt.h"

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
  // Longest delay the recurrence holds: 2 c + remainder must fit 32 bits,
  // and remainders stay below 4n + 1 < 2^26.
  static constexpr uint32_t kMaxDelayQ8 = (uint32_t(1) << 31) - (uint32_t(1) << 26);

  static RampError check(const RampConfig& cfg) {
    if (cfg.max_rate == 0) return RampError::zero_speed;
    if (cfg.accel == 0 || cfg.decel == 0) return RampError::zero_accel;
    if (cfg.max_rate > cfg.tick_hz) return RampError::rate_above_tick;
    const uint32_t gentler = cfg.accel < cfg.decel ? cfg.accel : cfg.decel;
    if (first_delay_q8(cfg.tick_hz, gentler) >= kMaxDelayQ8) return RampError::out_of_range;
    return RampError::none;
  }

  // First delay of the ramp, in ticks (Q8): 0.676 f sqrt(2/a).
  static uint32_t first_delay_q8(uint32_t tick_hz, uint32_t accel) {
    // (0.676^2 * 2) = 0.913952; c0^2 = 0.913952 f^2 / a; Q8 squares to 2^16.
    const uint64_t khz = tick_hz / 1000u;
    const uint64_t c0_squared = khz * khz * 913952u / accel;
    return isqrt64(c0_squared << 16);
  }

  RampError plan(uint32_t steps, const RampConfig& cfg) {
    const RampError err = check(cfg);
    if (err != RampError::none) return err;
    // Whole ticks, rounded up: the cruise never exceeds max_rate.
    const uint32_t cruise_ticks = cfg.tick_hz / cfg.max_rate + (cfg.tick_hz % cfg.max_rate != 0);
    start(steps, cfg, first_delay_q8(cfg.tick_hz, cfg.accel), cruise_ticks << 8);
    return RampError::none;
  }

  // The same method with its delays given directly: c0 and the cruise delay in
  // Q8 ticks, accel/decel only as their ratio (for the decelerating part).
  // This is how tables stated in physical units (seed-000 Appendix 1: c0 =
  // 16940.51 us for 100 rad/s^2 at 0.0314 rad/step) are reproduced exactly,
  // without rounding the acceleration to whole steps/s^2 first.
  RampError plan_delays(uint32_t steps, uint32_t c0_q8, uint32_t cruise_q8, uint32_t accel,
                        uint32_t decel) {
    if (cruise_q8 == 0) return RampError::zero_speed;
    if (accel == 0 || decel == 0) return RampError::zero_accel;
    // 2 c + rest must stay below 2^32 in the recurrence.
    if (c0_q8 >= kMaxDelayQ8) return RampError::out_of_range;
    start(steps, RampConfig{0, 0, accel, decel}, c0_q8, cruise_q8);
    return RampError::none;
  }

  // Unrounded (Q8) delay of the step next() will return while accelerating;
  // on entering cruise or deceleration the step itself may still change it.
  uint32_t accel_delay_q8() const { return c_; }

  bool finished() const { return remaining_ == 0 && split_.count == 0; }
  uint32_t remaining() const { return remaining_ + split_.count; }

  // Ticks before the next step; 0 once the move is finished.
  uint32_t next() {
    const StepRun run = take(1);
    return run.count ? run.interval : 0;
  }

  // The next run of equal intervals (count 0 once finished).
  StepRun next_run() { return take(0xFFFF); }

  // Fast ramps: from now on, next_run() groups ramp steps whose delay is
  // below `below_ticks` into runs of up to sqrt(n) steps at one delay (n =
  // steps from the nearer end of the ramp), so the planner spends one square
  // root per run instead of one division per step and keeps ahead of a step
  // engine running at 100+ kHz. A run's delay is the mean of the recurrence's
  // first and last delay over the run, which keeps every step within 1/4
  // step of the per-step schedule (tests/host/test_speed_ramp.cpp). The
  // cruise delay is then clamped to the exact max_rate. 0 turns it off (the
  // default: per-step seed behaviour).
  void batch_below(uint32_t below_ticks) { batch_below_q8_ = below_ticks << 8; }

 private:
  enum class Phase : uint8_t { accel, cruise, decel };

  static uint32_t round_q8(uint32_t q8) { return (q8 + 128) >> 8; }
  uint32_t at_least_cruise(uint32_t ticks) const { return ticks < min_ticks_ ? min_ticks_ : ticks; }

  void start(uint32_t steps, const RampConfig& cfg, uint32_t c0_q8, uint32_t cruise_q8) {
    cfg_ = cfg;
    remaining_ = steps;
    c_ = c0_q8;
    c_min_ = cruise_q8;
    min_ticks_ = (cruise_q8 + 255) >> 8;
    rest_ = 0;
    n_ = 0;
    stop_steps_ = 0;
    phase_ = Phase::accel;
    split_ = StepRun{0, 0};
    invariant_valid_ = false;
  }

  // Steps needed to stop after n accelerating steps: n * accel / decel.
  // (Equal rates, the common case, skip the 64-bit division: it is called
  // on every step.)
  uint32_t stopping_steps(uint32_t n) const {
    if (cfg_.accel == cfg_.decel) return n;
    return uint32_t((uint64_t(n) * cfg_.accel + cfg_.decel / 2) / cfg_.decel);
  }

  void enter_decel() {
    phase_ = Phase::decel;
    rest_ = 0;
    invariant_valid_ = false;
  }

  // Decides the phase of the step about to be emitted and updates c_ to its
  // delay. Called once per step, before the step is counted.
  void prepare_step() {
    if (phase_ == Phase::accel) {
      if (n_ > 0 && remaining_ <= stopping_steps(n_)) {
        enter_decel();
      } else if (c_ < c_min_) {
        phase_ = Phase::cruise;
        stop_steps_ = stopping_steps(n_);
        // Per-step ramps keep the recurrence's c, so deceleration mirrors
        // the acceleration exactly (steps run no faster than the cruise
        // anyway); a batched run may have overshot far below the limit.
        if (batch_below_q8_) c_ = c_min_;
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

  // sqrt(x * 2^s) rounded down, for even s <= 16, in 32-bit arithmetic: the
  // scale drops by whole bits when x << s would not fit, which costs nothing
  // in relative precision because x is then large.
  static uint32_t scaled_root(uint32_t x, uint8_t s) {
    uint8_t t = s;
    while (t && x >= (uint32_t(1) << (32 - t))) t = uint8_t(t - 2);
    return uint32_t(isqrt32(x << t)) << ((s - t) / 2);
  }

  // Along the recurrence c_n sqrt(2n + 1) stays constant while accelerating
  // (prod (4i-1)/(4i+1) ~ sqrt((2n+1) / (2n+2k+1))), and c_q sqrt(2q - 1)
  // while decelerating with q steps left. The first batched run of a phase
  // takes that constant from the recurrence's current delay; every later
  // delay of the phase is constant / root, so rounding errors never add up
  // from run to run. (Measured against the product: within 2e-5 for n >= 30.)
  void take_invariant(uint32_t c, uint32_t x) {
    root_scale_ = 16;
    uint64_t k = uint64_t(c) * scaled_root(x, root_scale_);
    while (k >> 32) {
      root_scale_ = uint8_t(root_scale_ - 2);
      k = uint64_t(c) * scaled_root(x, root_scale_);
    }
    invariant_ = uint32_t(k);
  }
  uint32_t delay_at(uint32_t x) const {
    const uint32_t r = scaled_root(x, root_scale_);
    return (invariant_ + r / 2) / r;
  }

  // Steps in a batched ramp run starting here (1 = no batching).
  uint32_t batch_size() const {
    if (batch_below_q8_ == 0 || c_ >= batch_below_q8_) return 1;
    if (phase_ == Phase::accel) {
      // Stay clear of the point where deceleration must begin: k more steps
      // add k * accel / decel to the stopping distance.
      const uint32_t stop = stopping_steps(n_);
      if (remaining_ <= stop) return 1;
      const uint32_t spare = remaining_ - stop;
      const uint32_t k = cfg_.accel == cfg_.decel
                             ? spare / 2
                             : uint32_t(uint64_t(spare) * cfg_.decel / (uint64_t(cfg_.accel) + cfg_.decel));
      const uint32_t root = isqrt32(n_);
      return k < root ? (k ? k : 1) : root;
    }
    const uint32_t root = isqrt32(remaining_);
    return root < remaining_ ? root : remaining_;
  }

  StepRun take(uint16_t max_count) {
    if (split_.count) {  // second half of a batched run
      const StepRun run = split_;
      split_.count = 0;
      return run;
    }
    if (remaining_ == 0) return StepRun{0, 0};
    prepare_step();
    StepRun run{at_least_cruise(round_q8(c_)), 1};
    if (phase_ == Phase::cruise) {
      uint32_t span = remaining_ - stop_steps_;
      if (span > max_count) span = max_count;
      run.count = uint16_t(span);
    } else if (max_count > 1) {
      uint32_t k = batch_size();
      if (k > max_count) k = max_count;
      if (k > 1) return take_batch(uint16_t(k));
    }
    remaining_ -= run.count;
    if (phase_ == Phase::accel) advance_accel();
    return run;
  }

  // k ramp steps at the mean of the first and last delay; leaves the state as
  // if the k steps had been taken one by one. Whole ticks cannot hold the
  // mean, so the run is split in two, at floor and floor + 1 ticks, whose
  // total is the mean times k to the nearest tick; halves shorter than
  // kMinSplit steps are not split off.
  static constexpr uint16_t kMinSplit = 8;
  StepRun take_batch(uint16_t k) {
    const uint32_t first = c_;
    uint32_t last;
    if (phase_ == Phase::accel) {
      if (!invariant_valid_) take_invariant(first, 2 * n_ + 1);
      n_ += k;
      last = delay_at(2 * n_ - 1);
      c_ = delay_at(2 * n_ + 1);
    } else {
      // The k-th delay from here is that of q = r - k + 1 steps left.
      if (!invariant_valid_) take_invariant(first, 2 * remaining_ - 1);
      last = delay_at(2 * (remaining_ - k) + 1);
      c_ = last;
    }
    invariant_valid_ = true;
    rest_ = 0;
    remaining_ -= k;
    const uint32_t total = uint32_t((uint64_t(first + last) * k + 256) >> 9);  // ticks
    const uint32_t base = total / k;
    // A run that reaches the cruise speed on its way runs at it.
    if (base < min_ticks_) return StepRun{min_ticks_, k};
    const uint16_t longer = uint16_t(total - base * k);
    if (longer < kMinSplit || k - longer < kMinSplit) {
      // A short half would be a short segment, which the step engine must
      // switch to and away from within a few steps: round instead (at most
      // kMinSplit / 2 ticks off over the whole run).
      return StepRun{longer * 2 < k ? base : base + 1, k};
    }
    split_ = StepRun{base + 1, longer};
    return StepRun{base, uint16_t(k - longer)};
  }

  RampConfig cfg_{};
  uint32_t remaining_ = 0;
  uint32_t c_ = 0;       // delay of the next step, Q8 ticks
  uint32_t c_min_ = 0;   // cruise delay, Q8 ticks
  uint32_t min_ticks_ = 0;  // the cruise delay rounded up: the shortest interval
  uint32_t rest_ = 0;    // remainder carried by the recurrence
  uint32_t n_ = 0;       // accelerating steps taken
  uint32_t stop_steps_ = 0;
  uint32_t batch_below_q8_ = 0;
  StepRun split_{0, 0};  // the floor + 1 half of a batched run, still to give
  uint32_t invariant_ = 0;   // c sqrt(2n + 1), or c sqrt(2q - 1) decelerating
  uint8_t root_scale_ = 16;  // the invariant's root carries 2^(root_scale_/2)
  bool invariant_valid_ = false;
  Phase phase_ = Phase::accel;
};

}  // namespace am
