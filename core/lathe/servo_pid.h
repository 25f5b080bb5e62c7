// Position PID for a DC-servo leadscrew (the seed's L298 and 30-slot motor
// encoder, docs/lathe.md "The m16-servo image"), in fixed point.
//
// Contract
//   Called once per sample period Ts with the position error e (target -
//   servo count, in 1/256 of a servo count: Q8) and a feedforward duty,
//   update() returns the PWM duty for the next period, 0 .. kMaxDuty (1023,
//   the 10-bit PWM's TOP):
//     u = ff + Kp e + Ki Ts sum(e) + (Kd / Ts) (e - e_previous)
//   rounded and clamped to 0 .. kMaxDuty. The output drives one way only
//   (the pass's or the move's direction): a negative sum is 0, the motor is
//   never driven backwards to correct an overshoot (the seed's choice; a
//   single-channel encoder counts in the commanded direction, so the motor
//   must not reverse while it is being counted).
//   Gains (ServoGains) are in duty counts per servo count (Kp), per servo
//   count and second (Ki), duty s per servo count (Kd), all x 1000; Ts in
//   microseconds. servo_coefficients() converts them (constexpr: a board's
//   gains at compile time, the lathe panel's settings at run time, once per
//   change); update() is integer only.
//   - Anti-windup: the integral does not grow while the output is saturated
//     in the direction of the error (conditional integration: at kMaxDuty
//     with e > 0, at 0 with e < 0), and it is kept within +-kMaxDuty duty on
//     its own.
//   - The derivative acts on the error (the target is smooth: the firmware
//     interpolates it between spindle counts), its input clamped.
//   - Off is off: an output below half a duty count is 0 exactly (the PWM
//     layer turns OC1A off for 0: fast PWM at OCR1A = 0 still pulses).
//   reset() clears the integral and the derivative's memory (start of a
//   pass or move).
//
// Arithmetic
//   The sum is kept in duty / 2^16 (int32). P: kp (duty/2^8 per count) x e
//   (count/2^8); D: kd x delta e; I: ki Ts (duty/2^16 per count/2^8 per
//   sample) x e >> 8. The inputs are clamped so that |P|, |D| <= 2^27
//   (2048 duty, twice full scale: a clamped term is saturated either way)
//   and an integral step <= 2^22 (64 duty); ff and the integral are <= 2^26:
//   no sum overflows. Ranges (ok false outside them): Kp <= 255, Ki <= 2000,
//   Kd/Ts <= 4000 duty per count, 100 us <= Ts <= 65535 us. Three 32-bit
//   multiplies per update.
#pragma once
#include <stdint.h>

namespace am {

// The sample period from which every Kd up to 4 duty s per count is
// within the range of Kd / Ts (the lathe's settings rely on it).
constexpr uint32_t kServoMinSampleUs = 1000;

struct ServoGains {
  uint32_t kp_milli;  // Kp x 1000, duty per count
  uint32_t ki_milli;  // Ki x 1000, duty per (count s)
  uint32_t kd_milli;  // Kd x 1000, duty s per count
};

// The gains as update()'s coefficients, computed once per change. ok is
// false outside the ranges.
struct ServoCoefficients {
  int32_t kp, ki, kd;
  // Input clamps: |kp e|, |kd delta e| <= 2^27 (2048 duty, twice full
  // scale: a clamped term is saturated either way), |ki e| <= 2^30.
  int32_t p_lim, i_lim, d_lim;
  bool ok;
};

constexpr int32_t servo_input_limit(int32_t k, int32_t term) { return k > 0 ? term / k : term; }

constexpr ServoCoefficients servo_coefficients(const ServoGains& g, uint32_t period_us) {
  // Kd / Ts in duty per count, x 1000.
  const uint64_t kd_per_sample_milli = period_us ? (uint64_t(g.kd_milli) * 1000000ul + period_us / 2) / period_us : 0;
  if (period_us < 100 || period_us > 65535 || g.kp_milli > 255000ul || g.ki_milli > 2000000ul ||
      kd_per_sample_milli > 4000000ul)
    return ServoCoefficients{0, 0, 0, 0, 0, 0, false};
  // duty/count -> (duty/2^8)/(count/2^8): x 256 / 1000; the product with e
  // (count/2^8) is duty/2^16. Ki Ts in duty per count per sample x 2^16: the
  // product with e (count/2^8) >> 8 is duty/2^16; rounded as
  // floor((floor(ki Ts 2^16 / 1000) + 500000) / 10^6), in one division. The
  // rest is 32-bit within the ranges: a gain set at run time (the lathe
  // panel's settings) costs the AVR two 64-bit divisions.
  const int32_t kp = int32_t((g.kp_milli * 256 + 500) / 1000);
  const int32_t ki = int32_t(((uint64_t(g.ki_milli) * period_us << 16) + 500000000ul) / 1000000000ul);
  const int32_t kd = int32_t((uint32_t(kd_per_sample_milli) * 256 + 500) / 1000);
  return ServoCoefficients{kp, ki, kd, servo_input_limit(kp, int32_t(1) << 27), servo_input_limit(ki, int32_t(1) << 30),
                           servo_input_limit(kd, int32_t(1) << 27), true};
}

class ServoPid {
 public:
  static constexpr uint16_t kMaxDuty = 1023;

  // Takes the coefficients (false, and the old ones kept, when !c.ok). Out
  // of line: inlined, avr-gcc copied the whole controller through the stack.
  __attribute__((noinline)) bool set(const ServoCoefficients& c) {
    if (!c.ok) return false;
    c_ = c;
    reset();
    return true;
  }
  void reset() {
    integral_ = 0;
    last_ = 0;
    primed_ = false;
  }

  // e_q8: target - count in 1/256 counts; ff: duty (0 .. kMaxDuty).
  uint16_t update(int32_t e_q8, uint16_t ff) {
    const int32_t e = e_q8;
    // e - last_ may overflow only for errors beyond 2^30 counts / 256.
    const int32_t de = primed_ ? clamp(e - last_, c_.d_lim) : 0;
    last_ = e;
    primed_ = true;
    const int32_t p = c_.kp * clamp(e, c_.p_lim);
    const int32_t d = c_.kd * de;
    const int32_t base = (int32_t(ff) << 16) + p + d;
    const int32_t before = base + integral_;
    const bool stuck_high = before >= kFullScale && e > 0;
    const bool stuck_low = before <= 0 && e < 0;
    if (!stuck_high && !stuck_low) {
      integral_ += (c_.ki * clamp(e, c_.i_lim)) >> 8;  // arithmetic shift (GCC)
      integral_ = clamp(integral_, kFullScale);
    }
    return duty(base + integral_);
  }

  // The integral term, duty / 2^16 (reports, tests).
  int32_t integral() const { return integral_; }

  // A sum in duty / 2^16 as the duty: rounded, 0 .. kMaxDuty, below half a
  // count exactly 0.
  static uint16_t duty(int32_t u) {
    if (u >= kFullScale - kHalf) return kMaxDuty;
    if (u < kHalf) return 0;
    return uint16_t((u + kHalf) >> 16);
  }

 private:
  static constexpr int32_t kFullScale = int32_t(kMaxDuty) << 16;
  static constexpr int32_t kHalf = int32_t(1) << 15;
  static int32_t clamp(int32_t v, int32_t lim) { return v > lim ? lim : v < -lim ? -lim : v; }

  ServoCoefficients c_{};
  int32_t integral_ = 0;
  int32_t last_ = 0;
  bool primed_ = false;
};

}  // namespace am
