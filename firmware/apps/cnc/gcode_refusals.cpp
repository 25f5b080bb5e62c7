// G-code's refusals (gcode.h refuse()): each error's text and grbl number,
// in flash.
#include <avr/pgmspace.h>

#include "../../../core/text/gcode_interpreter.h"
#include "../../board.h"
#include "gcode.h"
#include "gcode_axes.h"
#include "reply.h"

namespace gcode {
namespace {

// The error texts and their pointers in flash (docs/gcode.md: a switch over
// PSTR()s would become a pointer table in RAM). A board without a heater
// can only meet no_heater of the heater's errors (one with a heater never
// meets it), one without arcs none of the arc's geometry errors, one
// without excitation modes none of M350's (unless it has the direct MODE
// command, which answers with them): the others point at an empty text,
// and the linker drops theirs.
#define AM_ERROR_TEXT(name, text) const char name##_text[] PROGMEM = text;
AM_GCODE_ERRORS(AM_ERROR_TEXT)
#undef AM_ERROR_TEXT
const char kNoText[] PROGMEM = "";
constexpr bool reachable(am::GcodeError e) {
  using E = am::GcodeError;
  return (board::kHeater || e < E::heater_code_alone || e > E::bad_limit) && !(board::kHeater && e == E::no_heater) &&
         (board::kArcs || e < E::arc_zero_radius || e > E::arc_full_circle_r) &&
         (kModes || board::kCommands || (e != E::bad_mode && e != E::axis_has_no_modes && e != E::mode_not_available));
}
#define AM_ERROR_POINTER(name, text) reachable(am::GcodeError::name) ? name##_text : kNoText,
const char* const kErrorText[] PROGMEM = {AM_GCODE_ERRORS(AM_ERROR_POINTER)};
#undef AM_ERROR_POINTER

// Each error's grbl number (reply.h, docs/protocol.md); the grbl images
// alone link the table.
constexpr uint8_t grbl_code(am::GcodeError e) {
  using E = am::GcodeError;
  namespace c = reply::code;
  return e == E::bad_character ? c::expected_letter
         : e == E::bad_comment ? c::comment_open
         : e == E::unsupported_word || e == E::unsupported_code || e == E::no_such_axis || e == E::arcs_not_here ||
                 e == E::no_heater
             ? c::unsupported
         : e == E::bad_number ? c::bad_number
         : e == E::out_of_range ? c::out_of_range
         : e == E::bad_line_number ? c::bad_line_number
         : e == E::modal_group_conflict ? c::modal_group
         : e == E::repeated_word ? c::repeated_word
         : e == E::axis_conflict ? c::axis_conflict
         : e == E::multiple_actions ? c::several_actions
         : e == E::missing_axis_word ? c::no_axis_words
         : e == E::missing_dwell_time ? c::value_missing
         : e == E::missing_arc_words ? c::no_offsets
         : e == E::arc_mixed_form ? c::arc_mixed
         : e == E::unused_word ? c::unused_words
         : e == E::bad_feed ? c::undefined_feed
         : e == E::arc_zero_radius ? c::arc_radius
         : e == E::arc_radius_mismatch || e == E::arc_radius_too_small || e == E::arc_full_circle_r ||
                 e == E::target_out_of_range
             ? c::invalid_target
         : e == E::bad_mode ? c::bad_mode
         : e == E::axis_has_no_modes ? c::no_modes
         : e == E::mode_not_available ? c::mode_unavailable
                                      : c::heater;  // the heater's, a Marlin board's
}
#define AM_GRBL_CODE(name, text) grbl_code(am::GcodeError::name),
const uint8_t kGrblCode[] PROGMEM = {AM_GCODE_ERRORS(AM_GRBL_CODE)};
#undef AM_GRBL_CODE

}  // namespace

void refuse(am::GcodeError e) {
  reply::error(reply::marlin() ? 0 : pgm_read_byte(&kGrblCode[uint8_t(e)]),
               reinterpret_cast<const char*>(pgm_read_word(&kErrorText[uint8_t(e)])));
}

}  // namespace gcode
