// An axis on a step/direction driver whose STEP input is wired to the step
// timer's OC1A pin (Uno D9; PD5 on the ATmega16/32). The compare match itself
// raises the step line, so every rising edge sits exactly on its timer tick:
// no interrupt latency, no jitter. The step interrupt ends the pulse the
// board's kTimerPulseCycles later (docs/step-engine.md) and arms the next one.
//
// One such axis per board: there is one OC1A.
#pragma once
#include <stdint.h>

#include "../../core/board/descriptor.h"
#include "../../hal/avr/claims.h"
#include "../../hal/avr/gpio.h"
#include "../../hal/avr/step_timer.h"

template <char Name, typename Dir, typename Enable, bool EnableActiveLow, uint32_t StepsPerMetre>
struct TimerStepAxis {
  using Step = hal::Pin<HAL_OC1A_PORT, HAL_OC1A_BIT>;
  static constexpr char name = Name;
  static constexpr bool timer_pulse = true;
  // Its STEP pin is the step timer's compare output (the engine claims the
  // timer itself).
  static constexpr uint32_t claims = hal::claim::oc1a;
  // The pulse must have ended before the next match raises STEP again. It
  // ends kTimerPulseCycles (32 on the Uno) after its match, later by
  // whatever holds the step vector off: a UART handler's prologue (they
  // nest, about 25 cycles) or a shield latch write from the main loop
  // (interrupts off, about 70 cycles). 100 cycles between steps: 160 kHz at
  // 16 MHz, checked by avrmotion-bench.
  static constexpr uint32_t max_rate = F_CPU / 100;

  static void init() {
    Step::low();
    Step::output();
    Dir::low();
    Dir::output();
    Enable::set(EnableActiveLow);
    Enable::output();
  }
  static void energise() { Enable::set(!EnableActiveLow); }
  static void release() { Enable::set(EnableActiveLow); }
  static void set_direction(bool forward) { Dir::set(forward); }
  // The edges are the timer's: see step_engine.cpp and step_vector.S.
  static void pulse_begin(bool) {}
  static void pulse_end() {}

  static constexpr am::AxisDescriptor descriptor() {
    return am::AxisDescriptor{Name, am::AxisKind::step_dir,
                              {am::pin_code(Step::port, Step::bit), am::pin_code(Dir::port, Dir::bit),
                               am::pin_code(Enable::port, Enable::bit), am::kNoPin},
                              uint8_t(EnableActiveLow ? 1 : 0), 0, StepsPerMetre};
  }
};
