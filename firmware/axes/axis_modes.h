// MODE for any board's axis set (used by the protocol). An axis takes a mode
// through its own `static bool set_mode(uint8_t)` if it has one (the shield
// steppers), else, for wave/two-phase/half, through a PhaseSequencer member
// `sequencer` (the ULN2003 axis); axes with neither (step/dir) have no
// excitation modes.
#pragma once
#include <stdint.h>

#include "../../core/motor/microstep.h"
#include "../../core/motor/phase_sequencer.h"
#include "axis_set.h"

enum class ModeResult : uint8_t { ok, no_axis, no_modes, unsupported };

template <typename Set>
struct AxisModes;

template <>
struct AxisModes<AxisSet<>> {
  static ModeResult set(char, uint8_t) { return ModeResult::no_axis; }
};

template <typename First, typename... Rest>
struct AxisModes<AxisSet<First, Rest...>> {
  static ModeResult set(char axis, uint8_t mode) {
    if (First::name != axis) return AxisModes<AxisSet<Rest...>>::set(axis, mode);
    return apply<First>(mode, 0, 0);
  }

 private:
  template <typename A>
  static auto apply(uint8_t mode, int, int) -> decltype(A::set_mode(mode), ModeResult()) {
    return A::set_mode(mode) ? ModeResult::ok : ModeResult::unsupported;
  }
  template <typename A>
  static auto apply(uint8_t mode, int, long) -> decltype(A::sequencer.set_mode(am::StepMode::wave), ModeResult()) {
    if (mode > am::excitation::half) return ModeResult::unsupported;
    A::sequencer.set_mode(am::StepMode(mode));
    return ModeResult::ok;
  }
  template <typename A>
  static ModeResult apply(uint8_t, long, long) {
    return ModeResult::no_modes;
  }
};
