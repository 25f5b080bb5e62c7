// The G-code interpreter's axis table of a board (gcode.cpp): each axis's
// letter, the M350 modes its type takes and its scale, constant unless the
// board has settings; and whether any axis has modes (kModes, which also
// says which refusals an image can meet: gcode_refusals.cpp).
#pragma once
#include <stdint.h>

#include "../../../core/text/gcode_state.h"
#include "../../axes/axis_modes.h"
#include "../../board.h"

namespace gcode {

// M350 modes an axis type takes (as AxisModes applies them).
template <typename A>
constexpr auto modes_of(int, int) -> decltype(A::set_mode(0), uint8_t()) {
  return am::kModesShield;
}
template <typename A>
constexpr auto modes_of(int, long) -> decltype(A::sequencer, uint8_t()) {
  return am::kModesUnipolar;
}
template <typename A>
constexpr uint8_t modes_of(long, long) {
  return 0;
}

template <typename Set>
struct AxisTable;
// Const (the compiler folds its scales) unless a board's settings set them.
template <bool Settable>
struct TableEntry {
  using type = const am::GcodeAxis;
};
template <>
struct TableEntry<true> {
  using type = am::GcodeAxis;
};
template <typename... A>
struct AxisTable<AxisSet<A...>> {
  static typename TableEntry<board::kSettings>::type value[sizeof...(A)];
};
// Scales in the planner's position units (1/64 full step on coil axes), so a
// target means the same whatever the excitation mode. A board with settings
// (board::kSettings) sets each axis's scale from its steps/mm (set_scale()).
template <typename... A>
typename TableEntry<board::kSettings>::type AxisTable<AxisSet<A...>>::value[sizeof...(A)] = {
    am::GcodeAxis{A::name, modes_of<A>(0, 0), A::descriptor().steps_per_m * OwnUnits<A>::per_full_step}...};

// Whether any axis has excitation modes (M350).
template <typename Set>
struct AnyModes;
template <typename... A>
struct AnyModes<AxisSet<A...>> {
  static constexpr uint8_t all[sizeof...(A)] = {modes_of<A>(0, 0)...};
  static constexpr bool value(uint8_t i = 0) { return i < sizeof...(A) && (all[i] != 0 || value(uint8_t(i + 1))); }
};
constexpr bool kModes = AnyModes<board::Axes>::value();

}  // namespace gcode
