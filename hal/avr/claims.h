// Hardware resources a board's parts claim, checked at compile time.
//
// Contract
//   A claim is a bit mask of the units in `claim::`. Exclusive units (a
//   timer's mode and clock, a compare-output pin, an interrupt line, the
//   UART, the ADC) belong to one user each. `timerN_pwm8` is the one shared
//   unit: any number of Pwm8 channels may claim it, because they all ask for
//   the same thing (fast PWM, TOP 0xFF, no prescaler), but nothing may then
//   also claim timerN for another use. A board lists what its parts claim in
//   `using Claims = hal::ClaimSet<...>;` and the set refuses to compile when
//   two claims collide, naming the rule that broke.
//
// Why
//   The step clock, a heater's or a servo's PWM and a time base all want a
//   timer, and the AVR has three: two parts that quietly reprogram one timer
//   fail only at run time, in ways a test may never meet.
#pragma once
#include <stdint.h>

namespace hal {
namespace claim {

constexpr uint32_t timer0 = 1ul << 0, timer1 = 1ul << 1, timer2 = 1ul << 2;
constexpr uint32_t timer0_pwm8 = 1ul << 3, timer2_pwm8 = 1ul << 4;  // shared, see above
constexpr uint32_t oc0a = 1ul << 5, oc0b = 1ul << 6, oc1a = 1ul << 7, oc1b = 1ul << 8;
constexpr uint32_t oc2a = 1ul << 9, oc2b = 1ul << 10;
constexpr uint32_t int0 = 1ul << 11, int1 = 1ul << 12;
constexpr uint32_t uart = 1ul << 13, adc = 1ul << 14;

constexpr uint32_t shared = timer0_pwm8 | timer2_pwm8;

}  // namespace claim

// The claims of several users (an axis set reports its axes' this way too).
template <uint32_t... Claims>
struct ClaimSet;

template <>
struct ClaimSet<> {
  static constexpr uint32_t all = 0;
  static constexpr bool exclusive_ok = true;
};

template <uint32_t First, uint32_t... Rest>
struct ClaimSet<First, Rest...> {
  using Tail = ClaimSet<Rest...>;
  static constexpr uint32_t all = First | Tail::all;
  static constexpr bool exclusive_ok = ((First & Tail::all & ~claim::shared) == 0) && Tail::exclusive_ok;
  static_assert(exclusive_ok, "two parts of this board claim the same timer, compare pin, interrupt, UART or ADC");
  static_assert(!((all & claim::timer0_pwm8) && (all & claim::timer0)),
                "Timer0 drives 8-bit PWM here and is claimed for something else too");
  static_assert(!((all & claim::timer2_pwm8) && (all & claim::timer2)),
                "Timer2 drives 8-bit PWM here and is claimed for something else too");
};

}  // namespace hal
