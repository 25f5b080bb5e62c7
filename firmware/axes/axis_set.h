// A board's axes as a compile-time list. The step interrupt calls
// pulse_begin/pulse_end with the segment's axis and direction masks; the loops
// below unroll at compile time, so an axis costs one bit test when idle.
//
// Every axis type provides, as static members:
//   name, descriptor(), init(), energise(), release(),
//   set_direction(bool forward), pulse_begin(bool forward), pulse_end(),
//   and optionally pulse_commit() (see OwnCommit).
// The set also yields the board descriptor's axis table (descriptor.cpp).
#pragma once
#include <stdint.h>

#include "../../core/board/descriptor.h"
#include "../../hal/avr/claims.h"

// Whether an axis type's step edges come from the step timer's output-compare
// pin (it declares `static constexpr bool timer_pulse = true`).
template <typename A, typename = void>
struct TimerPulsed {
  static constexpr bool value = false;
};
template <typename A>
struct TimerPulsed<A, decltype(void(A::timer_pulse))> {
  static constexpr bool value = A::timer_pulse;
};

// An axis type's own step-rate limit (`static constexpr uint32_t max_rate`),
// or 0: the board's kMaxStepRate applies.
template <typename A, typename = void>
struct OwnMaxRate {
  static constexpr uint32_t value = 0;
};
template <typename A>
struct OwnMaxRate<A, decltype(void(A::max_rate))> {
  static constexpr uint32_t value = A::max_rate;
};

// The hardware an axis type claims (`static constexpr uint32_t claims`, bits
// of hal/avr/claims.h), or none.
template <typename A, typename = void>
struct OwnClaims {
  static constexpr uint32_t value = 0;
};
template <typename A>
struct OwnClaims<A, decltype(void(A::claims))> {
  static constexpr uint32_t value = A::claims;
};

// A step an axis type stages in pulse_begin and shows in pulse_commit
// (`static void pulse_commit()`), or nothing to commit.
template <typename A, typename = void>
struct OwnCommit {
  static void run() {}
};
template <typename A>
struct OwnCommit<A, decltype(void(&A::pulse_commit))> {
  static void run() { A::pulse_commit(); }
};

// Position bookkeeping: an axis type may count its position in finer units
// than its steps (`static int32_t units_for(int32_t steps, bool idle)` and
// `static constexpr uint8_t units_per_full_step`: the coil-driven axes count
// 1/64 full steps, so moves in different excitation modes add up); by
// default one step is one unit.
template <typename A, typename = void>
struct OwnUnits {
  static int32_t units_for(int32_t steps, bool) { return steps; }
  static constexpr uint8_t per_full_step = 1;
  static constexpr bool own = false;
};
template <typename A>
struct OwnUnits<A, decltype(void(A::units_per_full_step))> {
  static int32_t units_for(int32_t steps, bool idle) { return A::units_for(steps, idle); }
  static constexpr uint8_t per_full_step = A::units_per_full_step;
  static constexpr bool own = true;
};

template <typename... Axes>
struct AxisSet;

template <>
struct AxisSet<> {
  static constexpr uint8_t count = 0;
  static constexpr uint8_t timer_mask = 0;
  using Claims = hal::ClaimSet<>;
  static void init() {}
  static void release() {}
  static void energise(uint8_t, uint8_t) {}
  static void set_direction(uint8_t, uint8_t, uint8_t) {}
  static void stage(uint8_t, uint8_t, uint8_t) {}
  static void commit(uint8_t, uint8_t) {}
  static void pulse_end(uint8_t, uint8_t) {}
  static int8_t index_of(char, uint8_t = 0) { return -1; }
  static constexpr char name_at(uint8_t) { return '?'; }
  static constexpr uint32_t max_rate_at(uint8_t) { return 0; }
  static constexpr uint32_t steps_per_m_at(uint8_t) { return 0; }
  static int32_t units_for(uint8_t, int32_t, bool) { return 0; }
  static uint8_t units_per_full_step_at(uint8_t) { return 1; }
  static constexpr bool own_units = false;
};

template <typename First, typename... Rest>
struct AxisSet<First, Rest...> {
  using Tail = AxisSet<Rest...>;
  static constexpr uint8_t count = 1 + sizeof...(Rest);
  // Mask bits of the axes pulsed by the timer hardware.
  static constexpr uint8_t timer_mask = uint8_t((TimerPulsed<First>::value ? 1 : 0) | (Tail::timer_mask << 1));
  // Whether an axis counts in units of its own (units_for() then depends on
  // whether it is idle); false: every unit is a step.
  static constexpr bool own_units = OwnUnits<First>::own || Tail::own_units;
  static_assert((timer_mask & (timer_mask - 1)) == 0, "one OC1A: at most one timer-pulsed axis");
  // What the axes claim together: two axes on one PWM channel do not compile.
  using Claims = hal::ClaimSet<OwnClaims<First>::value, Tail::Claims::all>;

  static void init() { First::init(); Tail::init(); }
  static void release() { First::release(); Tail::release(); }

  // The `bit` argument is the mask bit of First; the public entry points start
  // at bit 1.
  static void energise(uint8_t axes, uint8_t bit = 1) {
    if (axes & bit) First::energise();
    Tail::energise(axes, uint8_t(bit << 1));
  }
  static void set_direction(uint8_t axes, uint8_t dirs, uint8_t bit = 1) {
    if (axes & bit) First::set_direction(dirs & bit);
    Tail::set_direction(axes, dirs, uint8_t(bit << 1));
  }
  // Every stepping axis stages its step, then each commits it (an output
  // several axes share, the shield's latch, is written once).
  static void pulse_begin(uint8_t axes, uint8_t dirs) {
    stage(axes, dirs, 1);
    commit(axes, 1);
  }
  static void stage(uint8_t axes, uint8_t dirs, uint8_t bit) {
    if (axes & bit) First::pulse_begin(dirs & bit);
    Tail::stage(axes, dirs, uint8_t(bit << 1));
  }
  static void commit(uint8_t axes, uint8_t bit) {
    if (axes & bit) OwnCommit<First>::run();
    Tail::commit(axes, uint8_t(bit << 1));
  }
  static void pulse_end(uint8_t axes, uint8_t bit = 1) {
    if (axes & bit) First::pulse_end();
    Tail::pulse_end(axes, uint8_t(bit << 1));
  }
  static int8_t index_of(char name, uint8_t index = 0) {
    return First::name == name ? int8_t(index) : Tail::index_of(name, uint8_t(index + 1));
  }
  static constexpr char name_at(uint8_t index) { return index == 0 ? First::name : Tail::name_at(uint8_t(index - 1)); }
  static constexpr uint32_t max_rate_at(uint8_t index) {
    return index == 0 ? OwnMaxRate<First>::value : Tail::max_rate_at(uint8_t(index - 1));
  }
  static constexpr uint32_t steps_per_m_at(uint8_t index) {
    return index == 0 ? First::descriptor().steps_per_m : Tail::steps_per_m_at(uint8_t(index - 1));
  }
  // Position units moved by `steps` steps of axis `index` (see OwnUnits).
  static int32_t units_for(uint8_t index, int32_t steps, bool idle) {
    return index == 0 ? OwnUnits<First>::units_for(steps, idle) : Tail::units_for(uint8_t(index - 1), steps, idle);
  }
  static uint8_t units_per_full_step_at(uint8_t index) {
    return index == 0 ? OwnUnits<First>::per_full_step : Tail::units_per_full_step_at(uint8_t(index - 1));
  }
};
