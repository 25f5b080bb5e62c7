// Microstepping: winding currents (8-bit PWM duty) and coil polarity for every
// microstep of a bipolar motor, walked forward or backward.
//
// Contract
//   Microstepper<M> (M = microsteps per full step, a power of two, 2..64)
//   keeps the rotor as an index 0 .. 4M-1 into one electrical cycle. Index i
//   lies in quadrant q = i / M at position cs = i % M inside it; the duties are
//     quadrant 0: pwm_a = curve[M - cs], pwm_b = curve[cs], coils A+ B+
//     quadrant 1: pwm_a = curve[cs],     pwm_b = curve[M - cs], coils B+ A-
//     quadrant 2: pwm_a = curve[M - cs], pwm_b = curve[cs], coils A- B-
//     quadrant 3: pwm_a = curve[cs],     pwm_b = curve[M - cs], coils B- A+
//   (the AFMotor mapping, seed-000 section 2), with curve[k] = round(255 sin(k
//   pi / 2M)). Coil bits use the phase sequencer's order (bit0 = A+, bit1 = B+,
//   bit2 = A-, bit3 = B-), so index M*j/2 is half-step state j of
//   half_step_pattern() with the current fully in the lit coil(s).
//
//   step() moves one microstep and returns the new output; hold() energises the
//   current index; release() turns both windings off (duty 0, no coils) and
//   keeps the index so the next step continues without a jump.
//
//   The curve is computed at compile time with integer arithmetic only: a
//   Taylor series in Q30 fixed point (error < 1e-8, far below half an LSB of
//   the 8-bit duty, so the table equals rounding the true sine except where
//   the true value sits within 1e-8 of a half). For M = 16 it differs from the
//   AFMotor table (0, 25, 50, ..., 253, 255) at k = 6 (142, AFMotor 141: true
//   value 141.67) and k = 15 (254, AFMotor 253: true value 253.77); AFMotor
//   truncated those two.
#pragma once
#include <stdint.h>

namespace am {

namespace microstep_detail {

constexpr int64_t q30 = int64_t(1) << 30;
constexpr int64_t pi_q30 = 3373259426;  // round(pi * 2^30)

// sin(x) for 0 <= x <= pi/2, x and result in Q30. Terms up to x^15/15!; the
// first omitted term is below 2e-10 at pi/2.
constexpr int64_t sin_q30(int64_t x) {
  const int64_t x2 = (x * x) >> 30;
  int64_t term = x;
  int64_t sum = x;
  for (int64_t i = 1; i <= 7; ++i) {
    term = -((term * x2) >> 30) / ((2 * i) * (2 * i + 1));
    sum += term;
  }
  return sum;
}

// round(255 * sin(k * pi / (2 * m))) for 0 <= k <= m.
constexpr uint8_t duty(uint8_t k, uint8_t m) {
  return uint8_t((255 * sin_q30(pi_q30 * k / (2 * m)) + q30 / 2) >> 30);
}

}  // namespace microstep_detail

// The quarter-wave current curve, M + 1 entries from 0 to 255.
template <uint8_t M>
struct MicrostepCurve {
  static_assert(M >= 2 && M <= 64 && (M & (M - 1)) == 0,
                "microsteps per full step must be a power of two, 2..64");
  uint8_t duty[M + 1];
  constexpr MicrostepCurve() : duty() {
    for (uint8_t k = 0; k <= M; ++k) duty[k] = microstep_detail::duty(k, M);
  }
};

struct MicrostepOutput {
  uint8_t coils;  // phase-sequencer bit order
  uint8_t pwm_a;  // winding A duty, 0..255
  uint8_t pwm_b;  // winding B duty, 0..255
};

template <uint8_t M>
class Microstepper {
 public:
  static constexpr uint8_t microsteps = M;
  static constexpr uint16_t cycle = 4 * uint16_t(M);  // indices per electrical cycle

  // Output of any index, energised.
  static MicrostepOutput output_at(uint16_t index) {
    static constexpr MicrostepCurve<M> curve{};
    // Coils lit in each quadrant: A+B+, B+A-, A-B-, B-A+.
    static constexpr uint8_t quadrant_coils[4] = {0x3, 0x6, 0xC, 0x9};
    index %= cycle;
    const uint8_t q = uint8_t(index / M);
    const uint8_t cs = uint8_t(index % M);
    const uint8_t falling = curve.duty[M - cs];
    const uint8_t rising = curve.duty[cs];
    // Even quadrants start with the full current in A, odd ones in B.
    if ((q & 1) == 0) return MicrostepOutput{quadrant_coils[q], falling, rising};
    return MicrostepOutput{quadrant_coils[q], rising, falling};
  }

  MicrostepOutput step(bool forward) {
    index_ = uint16_t((index_ + (forward ? 1 : cycle - 1)) % cycle);
    energised_ = true;
    return output();
  }

  MicrostepOutput hold() {
    energised_ = true;
    return output();
  }

  MicrostepOutput release() {
    energised_ = false;
    return output();
  }

  MicrostepOutput output() const {
    return energised_ ? output_at(index_) : MicrostepOutput{0, 0, 0};
  }

  uint16_t index() const { return index_; }
  bool energised() const { return energised_; }

 private:
  uint16_t index_ = 0;
  bool energised_ = false;
};

}  // namespace am
