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
//   step() moves one microstep and returns the output it lands on; hold() energises the
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

#include "phase_sequencer.h"

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


// ---------------------------------------------------------------------------
// Excitation modes on one common rotor angle (added for the shield's modes).
//
// Contract
//   The rotor angle is a uint8_t in 1/64 of a full step: 256 units are one
//   electrical cycle (4 full steps), so the angle wraps by itself. Half-step
//   state j of half_step_pattern() sits at angle 32 j. Every mode is a grid on
//   that angle (unit step s, offset o):
//     wave (0): s 64, o 0    two-phase (1): s 64, o 32    half (2): s 32, o 0
//     16 / 32 / 64 microsteps: s 4 / 2 / 1, o 0
//   step() moves to the next grid point of the current mode strictly ahead (or
//   behind), so after a mode change on an angle that is off the grid of the mode now set the
//   first step is a partial one and the rotor never jumps. set_mode() keeps
//   the angle. snap_down() (the first energise after power-up, when the rotor
//   position is unknown) moves to the grid point at or behind the angle: from
//   angle 0 two-phase holds B-A+ and steps to A+B+, as PhaseSequencer and
//   AFMotor do.
//
//   ExcitationTable holds, for one output wiring, what each angle shows:
//   micro[a] the sine currents of angle a (Microstepper<64> mapping) with the
//   bits of the coils that carry current (a coil at duty 0 gets both inputs
//   low: fast PWM at OCR 0 still spikes one tick, the bridge must not drive);
//   full[j] half-step state j with both enables at 255 (full current).
namespace excitation {
constexpr uint8_t wave = 0, two_phase = 1, half = 2, micro16 = 16, micro32 = 32, micro64 = 64;
constexpr bool valid(uint8_t mode) {
  return mode == wave || mode == two_phase || mode == half || mode == micro16 || mode == micro32 ||
         mode == micro64;
}
constexpr bool microstepping(uint8_t mode) { return mode >= micro16; }
constexpr uint8_t grid_step(uint8_t mode) {
  return mode == wave || mode == two_phase ? 64 : mode == half ? 32 : uint8_t(64 / mode);
}
constexpr uint8_t grid_offset(uint8_t mode) { return mode == two_phase ? 32 : 0; }
}  // namespace excitation

class ExcitationCursor {
 public:
  static constexpr uint8_t units_per_full_step = 64;

  // constexpr, so a static cursor needs no constructor call at start-up.
  constexpr ExcitationCursor() : ExcitationCursor(excitation::two_phase) {}
  explicit constexpr ExcitationCursor(uint8_t mode)
      : mode_(mode),
        micro_(excitation::microstepping(mode)),
        mask_(uint8_t(-excitation::grid_step(mode))),
        fwd_sub_(excitation::grid_offset(mode)),
        fwd_add_(uint8_t(excitation::grid_offset(mode) + excitation::grid_step(mode))),
        rev_sub_(uint8_t(excitation::grid_offset(mode) + 1)),
        rev_add_(excitation::grid_offset(mode)) {}

  // False (and nothing changes) for a mode number that is no mode.
  bool set_mode(uint8_t mode) {
    if (!excitation::valid(mode)) return false;
    const uint8_t angle = angle_;
    *this = ExcitationCursor(mode);
    angle_ = angle;
    return true;
  }

  // Branch-free apart from the direction: it runs in the step interrupt.
  uint8_t step(bool forward) {
    angle_ = forward ? uint8_t(((angle_ - fwd_sub_) & mask_) + fwd_add_)
                     : uint8_t(((angle_ - rev_sub_) & mask_) + rev_add_);
    return angle_;
  }

  uint8_t snap_down() {
    angle_ = uint8_t(((angle_ - fwd_sub_) & mask_) + fwd_sub_);
    return angle_;
  }

  bool on_grid() const { return uint8_t((angle_ - fwd_sub_) & uint8_t(~mask_)) == 0; }
  uint8_t angle() const { return angle_; }
  uint8_t mode() const { return mode_; }
  bool microstepping() const { return micro_; }

 private:
  uint8_t angle_ = 0;
  uint8_t mode_;
  bool micro_;
  uint8_t mask_, fwd_sub_, fwd_add_, rev_sub_, rev_add_;
};

struct ExcitationEntry {
  uint8_t bits;   // output bits of the energised coil ends
  uint8_t pwm_a;  // winding A enable duty
  uint8_t pwm_b;  // winding B enable duty
};

struct ExcitationTable {
  ExcitationEntry micro[256];
  ExcitationEntry full[8];

  // a_pos .. b_neg: the output bit of each coil end (e.g. a latch bit).
  constexpr ExcitationTable(uint8_t a_pos, uint8_t b_pos, uint8_t a_neg, uint8_t b_neg)
      : micro(), full() {
    const MicrostepCurve<64> curve{};
    // Quadrant q lights A+B+, B+A-, A-B-, B-A+; the first coil named is
    // winding A in even quadrants, winding B in odd ones.
    const uint8_t a_bit[4] = {a_pos, a_neg, a_neg, a_pos};
    const uint8_t b_bit[4] = {b_pos, b_pos, b_neg, b_neg};
    for (uint16_t i = 0; i < 256; ++i) {
      const uint8_t q = uint8_t(i >> 6), cs = uint8_t(i & 63);
      const uint8_t falling = curve.duty[64 - cs], rising = curve.duty[cs];
      const uint8_t pa = (q & 1) ? rising : falling;
      const uint8_t pb = (q & 1) ? falling : rising;
      micro[i] = ExcitationEntry{uint8_t((pa ? a_bit[q] : 0) | (pb ? b_bit[q] : 0)), pa, pb};
    }
    const uint8_t ends[4] = {a_pos, b_pos, a_neg, b_neg};  // coil-pattern bit order
    for (uint8_t j = 0; j < 8; ++j) {
      const uint8_t pattern = half_step_pattern(j);
      uint8_t bits = 0;
      for (uint8_t e = 0; e < 4; ++e) bits = uint8_t(bits | ((pattern >> e) & 1 ? ends[e] : 0));
      full[j] = ExcitationEntry{bits, 255, 255};
    }
  }
};

}  // namespace am
