// A unipolar stepper (28BYJ-48 and the like) on a ULN2003 driver, its inputs
// IN1..IN4 (coils A+, B+, A-, B-; seed-003) on any four output pins.
//
// The coils must change together, or the motor (and the simulator's decoder)
// sees a passing state between two steps. When all four pins share a port the
// new pattern is written in one port write. Otherwise the order is chosen so
// that no intermediate pattern is a state of the cycle: coils are switched off
// first when the new state has one coil on (the transient has none on), on
// first when it has two (the transient has three on).
#pragma once
#include <stdint.h>

#include "../../core/board/descriptor.h"
#include "../../core/motor/phase_sequencer.h"
#include "../../hal/avr/gpio.h"

template <char Name, typename In1, typename In2, typename In3, typename In4, uint32_t StepsPerMetre>
struct UnipolarAxis {
  static constexpr char name = Name;
  static am::PhaseSequencer sequencer;

  static void init() {
    show(am::coil::off);
    In1::output();
    In2::output();
    In3::output();
    In4::output();
  }
  static void energise() { show(sequencer.hold()); }
  static void release() {
    sequencer.release();
    show(am::coil::off);
  }
  // Position in 1/64 full step, like the shield's axes: a full step in wave
  // and two-phase drive, half of one in half-step drive. (energise() has
  // already put the rotor on a state of the current mode when a move starts,
  // so every step of the move is whole.)
  static constexpr uint8_t units_per_full_step = 64;
  static int32_t units_for(int32_t steps, bool) {
    return steps * (sequencer.mode() == am::StepMode::half ? 32 : 64);
  }
  static void set_direction(bool) {}
  static void pulse_begin(bool forward) { show(sequencer.step(forward)); }
  static void pulse_end() {}

  static constexpr am::AxisDescriptor descriptor() {
    return am::AxisDescriptor{Name, am::AxisKind::unipolar4,
                              {am::pin_code(In1::port, In1::bit), am::pin_code(In2::port, In2::bit),
                               am::pin_code(In3::port, In3::bit), am::pin_code(In4::port, In4::bit)},
                              0, 0, StepsPerMetre};
  }

 private:
  static constexpr bool one_port =
      In1::port == In2::port && In1::port == In3::port && In1::port == In4::port;
  static constexpr uint8_t port_mask = In1::mask | In2::mask | In3::mask | In4::mask;

  static void show(uint8_t pattern) {
    if (one_port) {
      const uint8_t bits = uint8_t(((pattern & am::coil::a_pos) ? In1::mask : 0) |
                                   ((pattern & am::coil::b_pos) ? In2::mask : 0) |
                                   ((pattern & am::coil::a_neg) ? In3::mask : 0) |
                                   ((pattern & am::coil::b_neg) ? In4::mask : 0));
      hal::PortBits<In1::port>::write(port_mask, bits);
      return;
    }
    const bool single = pattern == am::coil::a_pos || pattern == am::coil::b_pos ||
                        pattern == am::coil::a_neg || pattern == am::coil::b_neg;
    if (single) {
      switch_off(pattern);
      switch_on(pattern);
    } else {
      switch_on(pattern);
      switch_off(pattern);
    }
  }
  static void switch_on(uint8_t p) {
    if (p & am::coil::a_pos) In1::high();
    if (p & am::coil::b_pos) In2::high();
    if (p & am::coil::a_neg) In3::high();
    if (p & am::coil::b_neg) In4::high();
  }
  static void switch_off(uint8_t p) {
    if (!(p & am::coil::a_pos)) In1::low();
    if (!(p & am::coil::b_pos)) In2::low();
    if (!(p & am::coil::a_neg)) In3::low();
    if (!(p & am::coil::b_neg)) In4::low();
  }
};

template <char Name, typename In1, typename In2, typename In3, typename In4, uint32_t S>
am::PhaseSequencer UnipolarAxis<Name, In1, In2, In3, In4, S>::sequencer;
