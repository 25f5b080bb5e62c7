// Hardware resources a board's parts claim, checked at compile time.
//
// Contract
//   A claim is a bit mask of the units in `claim::`. Exclusive units (a
//   timer's mode and clock, a compare-output pin, an interrupt line, the
//   UART, the ADC, a timer's overflow as a time base) belong to one user
//   each. The shared units may be claimed by any number of users, because
//   they all ask for the same thing:
//   - `timerN_pwm8`: Timer0/Timer2 in 8-bit fast PWM (mode 3, TOP 0xFF);
//     nothing may then also claim timerN for another mode;
//   - `timerN_div1`, `_div8`, `_div64`: the prescaler that timer runs at.
//     Every user of a shared timer names it, and a set that names two
//     prescalers for one timer does not compile: the PWM channels of a timer
//     and a time base on its overflow agree on one rate, so none of them can
//     quietly reprogram the others' (rate() below builds the bit).
//   `timerN_ovf` is the timer's overflow interrupt and its count (TCNTn): a
//   free-running time base (firmware/engine/clock.h). Its owner also claims
//   the timer's mode (`timerN` when the timer is its own, normal mode;
//   `timerN_pwm8` when it counts the PWM's period) and the prescaler, so
//   "this timer's overflow is the clock and its PWM runs at X" is one claim:
//   a second time base, a PWM user at another rate or a part that takes the
//   timer for another mode all collide with it.
//   A board lists what its parts claim in `using Claims =
//   hal::ClaimSet<...>;` and the set refuses to compile when two claims
//   collide, naming the rule that broke.
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
constexpr uint32_t timer0_ovf = 1ul << 15, timer2_ovf = 1ul << 16;  // a time base on the overflow
// The prescaler a timer runs at (shared, see above).
constexpr uint32_t timer0_div1 = 1ul << 17, timer0_div8 = 1ul << 18, timer0_div64 = 1ul << 19;
constexpr uint32_t timer2_div1 = 1ul << 20, timer2_div8 = 1ul << 21, timer2_div64 = 1ul << 22;

constexpr uint32_t timer0_rates = timer0_div1 | timer0_div8 | timer0_div64;
constexpr uint32_t timer2_rates = timer2_div1 | timer2_div8 | timer2_div64;
constexpr uint32_t shared = timer0_pwm8 | timer2_pwm8 | timer0_rates | timer2_rates;

// The prescaler claim of Timer0 or Timer2 (1, 8 or 64); 0 for any other.
constexpr uint32_t rate(uint8_t timer, uint16_t prescaler) {
  return (timer != 0 && timer != 2) ? 0
         : prescaler == 1           ? (timer == 0 ? timer0_div1 : timer2_div1)
         : prescaler == 8           ? (timer == 0 ? timer0_div8 : timer2_div8)
         : prescaler == 64          ? (timer == 0 ? timer0_div64 : timer2_div64)
                                    : 0;
}

// The prescaler a claim names for Timer0 or Timer2, 0 if none.
constexpr uint16_t prescaler_of(uint32_t claims, uint8_t timer) {
  return (claims & rate(timer, 1)) ? 1 : (claims & rate(timer, 8)) ? 8 : (claims & rate(timer, 64)) ? 64 : 0;
}

// At most one bit set.
constexpr bool at_most_one(uint32_t bits) { return (bits & (bits - 1)) == 0; }

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
  static_assert(exclusive_ok,
                "two parts of this board claim the same timer, compare pin, interrupt, UART, ADC or time base");
  static_assert(!((all & claim::timer0_pwm8) && (all & claim::timer0)),
                "Timer0 drives 8-bit PWM here and is claimed for something else too");
  static_assert(!((all & claim::timer2_pwm8) && (all & claim::timer2)),
                "Timer2 drives 8-bit PWM here and is claimed for something else too");
  static_assert(claim::at_most_one(all & claim::timer0_rates),
                "Timer0's users ask for different prescalers: its PWM and its time base share one rate");
  static_assert(claim::at_most_one(all & claim::timer2_rates),
                "Timer2's users ask for different prescalers: its PWM and its time base share one rate");
  static_assert(!(all & claim::timer0_pwm8) || (all & claim::timer0_rates),
                "Timer0 drives 8-bit PWM here but no part names its prescaler");
  static_assert(!(all & claim::timer2_pwm8) || (all & claim::timer2_rates),
                "Timer2 drives 8-bit PWM here but no part names its prescaler");
  static_assert(!(all & claim::timer0_ovf) ||
                    ((all & claim::timer0_rates) && (all & (claim::timer0 | claim::timer0_pwm8))),
                "a time base on Timer0's overflow claims the timer's mode and prescaler too");
  static_assert(!(all & claim::timer2_ovf) ||
                    ((all & claim::timer2_rates) && (all & (claim::timer2 | claim::timer2_pwm8))),
                "a time base on Timer2's overflow claims the timer's mode and prescaler too");
};

}  // namespace hal
