// Heater PID in fixed point, with Marlin's gain convention so that M301
// P/I/D values mean the same here.
//
// Contract
//   Called once per sample period Ts with the measured temperature and the
//   target (0.01 C), update() returns the heater duty for the next period:
//     u = Kp e + Ki Ts sum(e) - D,   e = target - measured,
//     D = low-pass of (Kd / Ts) (measured - previous measured),
//   rounded and clamped to 0 .. 255 (255 = always on). Gains are Marlin's
//   (M301): Kp in duty per C, Ki in duty per C per s, Kd in duty * s per C,
//   duty on the 0 .. 255 scale; they are given in thousandths (PidGains).
//   - The derivative acts on the measurement, not the error: a target change
//     moves the output by (Kp + Ki Ts) times the step, with no kick.
//   - Its low-pass is d += (raw - d) / 2^k per sample (d_filter_shift k, time
//     constant about 2^k Ts: 2 s at the defaults k = 4, Ts = 125 ms; Marlin's
//     is a fixed 0.95 / 0.05 blend per sample, a comparable smoothing).
//   - Anti-windup: the integral does not grow while the output is saturated
//     in the direction of the error (conditional integration), and it is
//     kept within 0 .. 255 duty on its own. A long saturated heat-up
//     therefore arrives with the integral it had when the output left the
//     rail, not with minutes of accumulated error.
//   - Off is off: a target <= 0 or a faulty reading returns 0 and clears the
//     state; an output below half a step rounds to 0. (The PWM layer must
//     turn OC2 off for 0: fast PWM at OCR 0 still pulses one tick a period.)
//   Unlike Marlin there is no full-power band beyond PID_FUNCTIONAL_RANGE:
//   the anti-windup makes it unnecessary, and the heat-up is the PID's own.
//
// Arithmetic (run per sample: integer only, no division)
//   The output is summed in duty / 2^16 (int32), the integral kept in
//   duty / 2^24 (uint32, 0 .. 255 duty) so that a bed's small Ki Ts (Ki
//   0.023 at 125 ms: 482 units per 0.01 C) is resolved to 0.1 %. P and D are
//   computed as coefficient times a clamped input, so neither exceeds 2^28
//   (4096 duty, 16 times full scale) and no sum overflows; a clamped term is
//   saturated either way. The integral moves by at most 128 duty a sample.
//   Three 32-bit multiplies per update. set_gains() converts the gains with
//   mul_div_round (no floating point, no 64-bit library code).
//   Ranges (set_gains returns false outside them and keeps the old gains):
//   Kp <= 1000, Ki <= 1000, Kd <= 10000, 50 <= Ts <= 1000 ms, k <= 8.
//   ATmega32, avr-g++ 5.4 -Os: update() at most 445 cycles (28 us at 16 MHz)
//   over 64 varied calls, set_gains() about 18300; 50 bytes of RAM, about
//   1.9 kB of flash with set_gains (measured in a throwaway image).
#pragma once
#include <stdint.h>

#include "fixed_point.h"
#include "temperature.h"

namespace am {

struct PidGains {
  uint32_t kp_milli;  // Kp * 1000, duty per C
  uint32_t ki_milli;  // Ki * 1000, duty per (C s)
  uint32_t kd_milli;  // Kd * 1000, duty s per C
};

class HeaterPid {
 public:
  static constexpr uint8_t kMaxOutput = 255;
  static constexpr uint16_t kDefaultPeriodMs = 125;
  static constexpr uint8_t kDefaultFilterShift = 4;

  bool set_gains(const PidGains& g, uint16_t period_ms = kDefaultPeriodMs,
                 uint8_t d_filter_shift = kDefaultFilterShift) {
    if (g.kp_milli > 1000000ul || g.ki_milli > 1000000ul || g.kd_milli > 10000000ul ||
        period_ms < 50 || period_ms > 1000 || d_filter_shift > 8)
      return false;
    gains_ = g;
    period_ms_ = period_ms;
    shift_ = d_filter_shift;
    // duty/C -> U/0.01C: * 2^16 / 100 / 1000
    kp_ = int32_t(mul_div_round(g.kp_milli, 65536ul, 100000ul));
    // duty/(C s) * Ts -> (duty/2^24)/0.01C: * Ts/1000 * 2^24 / 100 / 1000
    ki_ = int32_t(mul_div_round(g.ki_milli, uint32_t(period_ms) << 16, 390625ul));
    // duty s/C / Ts -> U/0.01C: * 1000/Ts * 2^16 / 100 / 1000
    kd_ = int32_t(mul_div_round(g.kd_milli, 65536ul, 100ul * period_ms));
    kp_lim_ = input_limit(kp_, kTermLimit);
    ki_lim_ = input_limit(ki_, kStepLimit);
    kd_lim_ = input_limit(kd_, kTermLimit);
    reset();
    return true;
  }
  const PidGains& gains() const { return gains_; }
  uint16_t period_ms() const { return period_ms_; }

  void reset() {
    integral_ = 0;
    d_ = 0;
    primed_ = false;
  }

  // Not inlined: on the AVR its fields are then reached through `this`
  // (2-byte LDD/STD) instead of the global's absolute addresses (4-byte
  // LDS/STS): the m32's heater service is about 370 bytes smaller with the
  // three control calls out of line.
  [[gnu::noinline]] uint8_t update(TempReading measured, int16_t target) {
    if (!measured.ok() || target <= 0) {
      reset();
      return 0;
    }
    const int32_t e = int32_t(target) - measured.centi;
    const int32_t dm = primed_ ? int32_t(measured.centi) - last_ : 0;
    last_ = measured.centi;
    primed_ = true;

    const int32_t p = kp_ * clamp32(e, -kp_lim_, kp_lim_);
    const int32_t raw_d = kd_ * clamp32(dm, -kd_lim_, kd_lim_);
    d_ += (raw_d - d_) >> shift_;  // arithmetic shift (GCC)
    const int32_t before = p + integral_term() - d_;
    const bool stuck_high = before >= kFullScale && e > 0;
    const bool stuck_low = before <= 0 && e < 0;
    if (!stuck_high && !stuck_low) integrate(ki_ * clamp32(e, -ki_lim_, ki_lim_));
    const int32_t u = p + integral_term() - d_;
    if (u >= kFullScale - kHalfStep) return kMaxOutput;
    if (u < kHalfStep) return 0;
    return uint8_t((u + kHalfStep) >> 16);
  }

  // State, for reports and tests: the integral and derivative terms in duty / 2^16.
  int32_t integral_term() const { return int32_t(integral_ >> 8); }
  int32_t derivative_term() const { return d_; }

 private:
  static constexpr int32_t kFullScale = int32_t(kMaxOutput) << 16;
  static constexpr int32_t kHalfStep = int32_t(1) << 15;
  static constexpr int32_t kTermLimit = int32_t(1) << 28;     // U
  static constexpr int32_t kStepLimit = 0x7FFFFFFF;           // duty/2^24: 128 duty a sample
  static constexpr uint32_t kIntegralMax = uint32_t(kMaxOutput) << 24;
  static constexpr int32_t kNoLimit = 0x7FFFFFFF;

  // Largest input whose product with k stays within limit (any input if k = 0).
  static int32_t input_limit(int32_t k, int32_t limit) { return k ? limit / k : kNoLimit; }

  // integral += step, saturating at 0 and kIntegralMax.
  void integrate(int32_t step) {
    if (step >= 0) {
      const uint32_t s = uint32_t(step);
      integral_ = integral_ > kIntegralMax - s ? kIntegralMax : integral_ + s;
    } else {
      const uint32_t s = uint32_t(-(step + 1)) + 1u;
      integral_ = integral_ < s ? 0 : integral_ - s;
    }
  }

  PidGains gains_{0, 0, 0};
  int32_t kp_ = 0, ki_ = 0, kd_ = 0;
  int32_t kp_lim_ = kNoLimit, ki_lim_ = kNoLimit, kd_lim_ = kNoLimit;
  uint32_t integral_ = 0;  // duty / 2^24
  int32_t d_ = 0;         // duty / 2^16
  int16_t last_ = 0;
  bool primed_ = false;
  uint16_t period_ms_ = kDefaultPeriodMs;
  uint8_t shift_ = kDefaultFilterShift;
};

}  // namespace am
