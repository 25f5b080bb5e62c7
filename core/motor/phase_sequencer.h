// Stepper phase sequencer: which coils are on for each step, in every
// excitation mode, walked forward or backward.
//
// Contract
//   A coil pattern is a 4-bit value in the fixed order bit0 = A+, bit1 = B+,
//   bit2 = A-, bit3 = B-. Outputs (74HC595 latch, ULN2003 pins, driver-board
//   port) map these bits to their own wiring; the sequence itself is shared.
//
//   The rotor position is kept as an index into the 8-state half-step cycle
//   A+, A+B+, B+, B+A-, A-, A-B-, B-, B-A+ (clockwise). Wave drive uses the even
//   states, two-phase drive the odd ones, half step all of them. A full step in
//   wave or two-phase mode therefore moves the index by 2, a half step by 1.
//
//   From power-up (index 0, coils off) the first forward two-phase step lands on
//   A+B+, the first wave step on B+ and the first half step on A+B+: the same
//   order as the AFMotor library, so the shield sees the latch bytes users know.
#pragma once
#include <stdint.h>

namespace am {

enum class StepMode : uint8_t { wave = 0, two_phase = 1, half = 2 };

namespace coil {
constexpr uint8_t a_pos = 0x1, b_pos = 0x2, a_neg = 0x4, b_neg = 0x8, off = 0x0;
}

// Coil pattern of each of the 8 half-step states: the one definition of the
// cycle (the shield's flash tables are built from it at compile time). A
// table, not a chain of comparisons, since the step interrupt calls this on
// every coil-driven step; not function-local, because avr-gcc copies a
// function-local constexpr array onto the stack on every call; a template's
// member, because a namespace-scope constexpr array is one copy in RAM per
// file that indexes it (two on the m16: C++14 has no inline variables).
template <typename = void>
struct HalfStepTable {
  static constexpr uint8_t patterns[8] = {
      coil::a_pos,          coil::a_pos | coil::b_pos, coil::b_pos,          coil::b_pos | coil::a_neg,
      coil::a_neg,          coil::a_neg | coil::b_neg, coil::b_neg,          coil::b_neg | coil::a_pos};
};
template <typename T>
constexpr uint8_t HalfStepTable<T>::patterns[8];

constexpr uint8_t half_step_pattern(uint8_t index) { return HalfStepTable<>::patterns[index & 7]; }

class PhaseSequencer {
 public:
  explicit PhaseSequencer(StepMode mode = StepMode::two_phase) : mode_(mode) {}
  // Starts on a given half-step state (taken modulo 8), coils still off: a
  // board whose power-up state is fixed (the seed-002 driver board starts on
  // A+B+, index 1) holds that state on its first hold().
  PhaseSequencer(StepMode mode, uint8_t start_index) : mode_(mode), index_(uint8_t(start_index & 7)) {}

  StepMode mode() const { return mode_; }
  void set_mode(StepMode mode) { mode_ = mode; }

  // Advances one step of the current mode and returns the coil pattern it lands on.
  uint8_t step(bool forward) {
    if (mode_ == StepMode::half) {
      index_ = uint8_t((index_ + (forward ? 1 : 7)) & 7);
    } else {
      // Snap to the mode's parity first (a mode switch may leave the rotor on
      // the other kind of state), then move a full step.
      const uint8_t parity = mode_ == StepMode::two_phase ? 1 : 0;
      if ((index_ & 1) != parity) {
        index_ = uint8_t((index_ + (forward ? 1 : 7)) & 7);
      } else {
        index_ = uint8_t((index_ + (forward ? 2 : 6)) & 7);
      }
    }
    energised_ = true;
    return pattern();
  }

  // Coils of the current state, or all off after release().
  uint8_t pattern() const { return energised_ ? half_step_pattern(index_) : coil::off; }

  // De-energise all coils; the rotor index is kept so the next step continues
  // the sequence without a jump.
  void release() { energised_ = false; }
  // Energise the coils (hold torque). If the rotor index is not a state of
  // the current mode (a wave or two-phase mode on a state of the other
  // parity), it first moves back one half step, so the next forward step lands
  // exactly where it would have landed from the index: from power-up the
  // two-phase hold shows B-A+ and the first step A+B+.
  uint8_t hold() {
    if (mode_ != StepMode::half) {
      const uint8_t parity = mode_ == StepMode::two_phase ? 1 : 0;
      if ((index_ & 1) != parity) index_ = uint8_t((index_ + 7) & 7);
    }
    energised_ = true;
    return pattern();
  }

  uint8_t index() const { return index_; }

 private:
  StepMode mode_;
  uint8_t index_ = 0;
  bool energised_ = false;
};

}  // namespace am
