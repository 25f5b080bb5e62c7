// A bipolar stepper on the Adafruit Motor Shield v1: its four bridge inputs
// sit on the shield's 74HC595 and its two L293D enables on PWM-capable pins.
//
// Both shield steppers share the latch, so the latch image lives in one place
// (ShieldLatch) and a step rewrites only the four bits of its own stepper
// before shifting the whole byte out.
#pragma once
#include <stdint.h>

#include "../../core/board_descriptor.h"
#include "../../core/phase_sequencer.h"
#include "../../core/shield_wiring.h"
#include "../../hal/avr/gpio.h"
#include "../../hal/avr/latch595.h"

template <typename Latch>
struct ShieldLatch {
  static uint8_t image;
};
template <typename Latch>
uint8_t ShieldLatch<Latch>::image = 0;

template <char Name, uint8_t Number, typename Latch, typename EnableA, typename EnableB,
          uint32_t StepsPerMetre>
struct ShieldStepper {
  static constexpr char name = Name;
  static am::PhaseSequencer sequencer;

  static void init() {
    EnableA::output();
    EnableB::output();
    EnableA::high();  // full current: the bridges follow the latch
    EnableB::high();
  }
  static void energise() { show(sequencer.hold()); }
  static void release() {
    sequencer.release();
    show(am::coil::off);
  }
  static void set_direction(bool) {}
  static void pulse_begin(bool forward) { show(sequencer.step(forward)); }
  static void pulse_end() {}

  static constexpr am::AxisDescriptor descriptor() {
    // The latch pins are shared; the descriptor names them for the decoder.
    return am::AxisDescriptor{Name, am::AxisKind::shield_latch,
                              {am::pin_code(Latch::Storage::port, Latch::Storage::bit),
                               am::pin_code(Latch::Clock::port, Latch::Clock::bit),
                               am::pin_code(Latch::Data::port, Latch::Data::bit),
                               am::pin_code(Latch::Enable::port, Latch::Enable::bit)},
                              Number, 0, StepsPerMetre};
  }

 private:
  static void show(uint8_t pattern) {
    constexpr am::ShieldStepperWiring wiring = am::shield_wiring(Number);
    uint8_t& image = ShieldLatch<Latch>::image;
    image = uint8_t((image & ~wiring.mask()) | wiring.latch_bits(pattern));
    Latch::write(image);
  }
};

template <char Name, uint8_t Number, typename Latch, typename EnableA, typename EnableB, uint32_t S>
am::PhaseSequencer ShieldStepper<Name, Number, Latch, EnableA, EnableB, S>::sequencer;
