// An axis on a step/direction driver (A4988, DRV8825, TB6600, the seed's
// driver board...). The step line rises at pulse_begin and falls at pulse_end,
// so the pulse lasts as long as the step interrupt's body between the two
// (measured in docs/step-engine.md); the direction changes only between
// segments, a full step interval ahead of the next pulse.
#pragma once
#include <stdint.h>

#include "../../core/board/descriptor.h"
#include "../../hal/avr/gpio.h"

template <char Name, typename Step, typename Dir, typename Enable, bool EnableActiveLow,
          uint32_t StepsPerMetre>
struct StepDirAxis {
  static constexpr char name = Name;

  static void init() {
    Step::low();
    Step::output();
    Dir::low();
    Dir::output();
    Enable::set(EnableActiveLow);  // driver off until the first move
    Enable::output();
  }
  static void energise() { Enable::set(!EnableActiveLow); }
  static void release() { Enable::set(EnableActiveLow); }
  static void set_direction(bool forward) { Dir::set(forward); }
  static void pulse_begin(bool) { Step::high(); }
  static void pulse_end() { Step::low(); }

  static constexpr am::AxisDescriptor descriptor() {
    return am::AxisDescriptor{Name, am::AxisKind::step_dir,
                              {am::pin_code(Step::port, Step::bit), am::pin_code(Dir::port, Dir::bit),
                               am::pin_code(Enable::port, Enable::bit), am::kNoPin},
                              uint8_t(EnableActiveLow ? 1 : 0), 0, StepsPerMetre};
  }
};
