// Endstop switches: one per homed axis, at the end of its travel it homes
// to, read by the step interrupt (hard limits, firmware/engine/limits.h) and
// by the homing service (firmware/services/homing.h).
//
// Contract
//   Endstop<'X', Pin, Claims, AtMax> is the switch of axis X on `Pin`, at the
//   axis's maximum end when AtMax (else its minimum); Claims names the pin's
//   special function (hal/avr/claims.h: INT0, OC1B...), which a part reading
//   the pin takes from everything else. EndstopSet<Axes, ClosedHigh, E...>
//   is a board's switches (all on one port, so the step interrupt reads them
//   with one IN); ClosedHigh is the polarity: a switch to ground on the pin's
//   pull-up reads low when closed (false). EndstopSet<Axes, false> (no
//   switch) compiles every use below to nothing.
//     watch(axes, dirs)  the pin mask of the switches that a segment moving
//                        `axes` in `dirs` (forward bits) runs toward
//     watch_latches(axes, dirs)  the same switches' edge latches (those on
//                        INT0/INT1: their INTFn flags, cleared now)
//     closed(watched, latches, inverted)  whether a switch of the pins
//                        `watched` (watch()'s) or the `latches` is closed
//                        now, or has closed since (a latched edge: bounce
//                        cannot hide it); `inverted` (a pin mask, 0 by
//                        default) the switches whose pins read the other
//                        way: normally closed (a board's $5)
//     closed_at(k, inverted)  whether the k-th switch is closed now
//     init(inverted)     the latches set for the closing edges, the other
//                        edge where the switches are inverted
//     pins               the pin mask of every switch
//     axis_at(k)         its axis index; pin_of(axis) its pin (descriptor)
//   HomingAxis is what the homing service and the soft limits need of a
//   switch's axis, HomingSettings<N> those of a board's N switches in the
//   set's order: one struct, so that settings loaded from the EEPROM can
//   replace the board's constants (board::kHomingSettings) later.
//
// Why
//   Read in the step interrupt rather than by an interrupt of their own: the
//   check costs a few cycles of a step event, and a closed switch is seen at
//   the next step, so no axis runs on by more than one step period. A
//   bouncing contact may read open at that step; the INT0/INT1 flags latch
//   its first closing edge (init(): the sense set, the interrupts left
//   masked), so X and Y on the m32 stop within one step period whatever
//   the bounce; a switch on a plain pin (Z) only once its reading is closed
//   (docs/homing.md).
#pragma once
#include <stdint.h>

#include "../../core/board/descriptor.h"
#include "../../hal/avr/claims.h"
#include "../../hal/avr/ext_int.h"
#include "../../hal/avr/gpio.h"
#include "axis_set.h"

// Steps and steps/s of the switch's axis (position units: steps on the
// step/dir axes that have switches). The homed axis may go from `home`
// `travel` steps away from its switch; the seek looks 1.5 travel for it.
struct HomingAxis {
  uint16_t seek_rate;    // toward the switch, first
  uint16_t locate_rate;  // toward it again, slowly, after backing off
  uint16_t back_off;     // away from it between seek and locate
  uint16_t pull_off;     // away from it at the end: the position becomes `home`
  int32_t home;
  uint32_t travel;
};

template <uint8_t N>
struct HomingSettings {
  HomingAxis axis[N];
};

template <char Axis, typename P, uint32_t Claims = 0, bool AtMax = false>
struct Endstop {
  static constexpr char axis = Axis;
  using Pin = P;
  static constexpr uint32_t claims = Claims;
  static constexpr bool at_max = AtMax;
};

namespace endstops_detail {

constexpr uint8_t or_all() { return 0; }
template <typename... T>
constexpr uint8_t or_all(uint8_t first, T... rest) {
  return uint8_t(first | or_all(rest...));
}
constexpr uint32_t or_claims() { return 0; }
template <typename... T>
constexpr uint32_t or_claims(uint32_t first, T... rest) {
  return first | or_claims(rest...);
}
constexpr bool all_on(char) { return true; }
template <typename... T>
constexpr bool all_on(char port, char first, T... rest) {
  return port == first && all_on(port, rest...);
}

// The axis bit of letter `c` in the axis set's order, 0 if it has none.
template <typename Set>
struct Letter;
template <typename... A>
struct Letter<AxisSet<A...>> {
  static constexpr uint8_t bit(char c) {
    const char names[] = {A::name..., 0};
    for (uint8_t i = 0; i < sizeof...(A); ++i)
      if (names[i] == c) return uint8_t(1u << i);
    return 0;
  }
};

template <typename Axes, typename... E>
struct Each;
template <typename Axes>
struct Each<Axes> {
  static uint8_t read_port() { return 0; }
  static uint8_t latches(uint8_t) { return 0; }
  static void init(bool) {}
  static uint8_t watch(uint8_t) { return 0; }
  static constexpr uint8_t axis_at(uint8_t) { return 0; }
  static bool read_at(uint8_t) { return false; }
  static constexpr uint8_t pin_of(uint8_t) { return am::kNoPin; }
};
template <typename Axes, typename First, typename... Rest>
struct Each<Axes, First, Rest...> {
  static constexpr uint8_t bit = Letter<Axes>::bit(First::axis);
  static_assert(bit != 0, "an endstop on an axis the board does not have");
  static_assert(all_on(First::Pin::port, Rest::Pin::port...),
                "the endstops share one port: the step interrupt reads them at once");
  static uint8_t read_port() { return hal::PortBits<First::Pin::port>::read(); }
  // A switch on INT0's or INT1's pin latches its closing edge there.
  static constexpr bool latching = (First::claims & (hal::claim::int0 | hal::claim::int1)) != 0;
  static constexpr uint8_t line = (First::claims & hal::claim::int0) ? 0 : 1;
  static uint8_t latches(uint8_t toward) {
    return uint8_t(((latching && (toward & bit)) ? hal::ext_int::latch_flag(line) : 0) | Tail::latches(toward));
  }
  static void init(bool closed_high) {
    if (latching) hal::ext_int::latch_edges(line, closed_high);
    Tail::init(closed_high);
  }
  using Tail = Each<Axes, Rest...>;
  static uint8_t watch(uint8_t toward) { return uint8_t(((toward & bit) ? First::Pin::mask : 0) | Tail::watch(toward)); }
  static constexpr uint8_t axis_at(uint8_t k) { return k == 0 ? uint8_t(__builtin_ctz(bit)) : Tail::axis_at(uint8_t(k - 1)); }
  static bool read_at(uint8_t k) { return k == 0 ? First::Pin::read() : Tail::read_at(uint8_t(k - 1)); }
  static constexpr uint8_t pin_of(uint8_t axis_bit) {
    return axis_bit == bit ? am::pin_code(First::Pin::port, First::Pin::bit) : Tail::pin_of(axis_bit);
  }
};

}  // namespace endstops_detail

template <typename Axes, bool ClosedHigh, typename... E>
struct EndstopSet {
  using Each = endstops_detail::Each<Axes, E...>;
  static constexpr uint8_t count = sizeof...(E);
  static constexpr uint8_t axes = endstops_detail::or_all(endstops_detail::Letter<Axes>::bit(E::axis)...);
  static constexpr uint8_t max_end =
      endstops_detail::or_all(uint8_t(E::at_max ? endstops_detail::Letter<Axes>::bit(E::axis) : 0)...);
  static constexpr uint32_t claims = endstops_detail::or_claims(E::claims...);
  static constexpr bool closed_high = ClosedHigh;

  static constexpr uint8_t pins = endstops_detail::or_all(E::Pin::mask...);

  // The closing edges of the switches on INT0/INT1 latch (no interrupt).
  static void init(bool inverted = false) { Each::init(ClosedHigh != inverted); }
  static uint8_t toward(uint8_t moving, uint8_t dirs) { return uint8_t(moving & axes & ~(dirs ^ max_end)); }
  static uint8_t watch(uint8_t moving, uint8_t dirs) { return count ? Each::watch(toward(moving, dirs)) : 0; }
  // Of the latching ones among them: the flags, cleared (an edge of a move
  // away from the switch, its release's bounce, is not this segment's).
  static uint8_t watch_latches(uint8_t moving, uint8_t dirs) {
    const uint8_t flags = count ? Each::latches(toward(moving, dirs)) : 0;
    if (flags) hal::ext_int::clear_latched(flags);
    return flags;
  }
  static bool closed(uint8_t watched, uint8_t latches, uint8_t inverted = 0) {
    if (!count) return false;
    uint8_t level = uint8_t(Each::read_port() ^ inverted);
    if (!ClosedHigh) level = uint8_t(~level);
    return (level & watched) != 0 || (hal::ext_int::latched() & latches) != 0;
  }
  static bool closed_at(uint8_t k, bool inverted = false) { return Each::read_at(k) == (ClosedHigh != inverted); }
  static constexpr uint8_t axis_at(uint8_t k) { return Each::axis_at(k); }
  static constexpr uint8_t pin_of(uint8_t axis) { return Each::pin_of(uint8_t(1u << axis)); }
};
