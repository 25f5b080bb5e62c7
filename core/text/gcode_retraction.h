// Firmware retraction in the G-code interpreter (gcode_interpreter.h, its
// Retract flag): G10 pulls the filament back by the retraction length (and
// lifts Z by the hop), G11 pushes it forward by the length plus the extra
// (and lowers Z), as Marlin's FWRETRACT and RepRapFirmware do; M207 and
// M208 set them. Included at the end of gcode_interpreter.h, which declares
// what it defines.
//
// Contract
//   G10, G11 alone on their line (N allowed; another code: multiple_actions;
//   a word: unused_word). A G10 while retracted and a G11 while not are
//   taken and move nothing (Marlin's rule). Otherwise the action is a move
//   (GcodeActionKind::move, not rapid) of E by -length (G10) or
//   +length + extra (G11) and of Z by +hop or -hop (when hop is not 0 and the
//   board has Z), at the retraction's feed or the recovery's, as one block.
//   The program positions do not change: the steps go into the axes' G92
//   offsets (as M221's flow does), so the G-code's E and Z numbers keep
//   their meaning while retracted; action.coord[] holds where the move
//   ends in program units (the state's coord plus the lengths), so the
//   machine times the move over its real length, and the next line's
//   coord_before is the state's coord again. No E axis: no_such_axis.
//   M207 [S<length>] [F<feed>] [Z<hop>], M208 [S<extra>] [F<feed>]: lengths
//   0 .. 100 mm, feeds above 0 and at most 100000 mm/min (out_of_range
//   otherwise), in the line's units (G20: inches); a word not given keeps
//   its value; nothing moves. M207 while retracted changes the next G11's
//   length: the G10's pull stays in the offset and the G11 pushes the
//   length in force (Marlin's rule too), so the E offset ends at that
//   length minus the G10's, plus the extra.
#pragma once
#include "gcode_interpreter.h"

namespace am {

template <uint8_t N, bool Arcs, bool Heater, uint8_t MarlinDwell, bool Modes, bool Printer, bool Retract>
GcodeError GcodeInterpreter<N, Arcs, Heater, MarlinDwell, Modes, Printer, Retract>::retract(
    const GcodeBlock& b, GcodeAction<N>& a, bool out, RetractionSlot<true>& slot) {
  using namespace gcode_detail;
  if (b.words & ~gcode_letter_bit('N')) return GcodeError::unused_word;
  for (uint8_t g = 0; g < kGcodeGroups; ++g)
    if (g != uint8_t(GcodeGroup::non_modal) && b.code[g] != GcodeCode::none) return GcodeError::multiple_actions;
  const uint8_t e = index_of('E'), z = index_of('Z');
  if (e == kNoAxis) return GcodeError::no_such_axis;
  hold_position(a, GcodeActionKind::none);
  Retraction& r = slot.value;
  if (out == r.retracted) return GcodeError::none;
  // E by the length, then Z by the hop, on a copy of their states.
  const uint8_t axis[2] = {e, z};
  const int32_t length[2] = {out ? -r.length : r.length + r.extra, out ? r.hop : -r.hop};
  GcodeAxisState next[2];
  uint8_t axes = 0;
  for (uint8_t k = 0; k < 2; ++k) {
    const uint8_t i = axis[k];
    if (i == kNoAxis || length[k] == 0) continue;
    const GcodeAxisState& st = state_.axis[i];
    int32_t d;
    if (!length_to_steps(length[k], axes_[i].steps_per_m, d) || !add_checked(st.steps, d, next[k].steps) ||
        !add_checked(st.offset, d, next[k].offset) || !add_checked(st.coord, length[k], a.coord[i]))
      return GcodeError::target_out_of_range;
    a.target[i] = next[k].steps;
    axes = uint8_t(axes | 1u << i);
  }
  a.axes = axes;
  a.rapid = false;
  a.feed = out ? r.feed : r.recover_feed;
  a.kind = GcodeActionKind::move;
  // Commit: the machine positions and offsets; the program positions stay.
  for (uint8_t k = 0; k < 2; ++k) {
    if (!(axes & (1u << axis[k]))) continue;
    state_.axis[axis[k]].steps = next[k].steps;
    state_.axis[axis[k]].offset = next[k].offset;
  }
  r.retracted = out;
  return GcodeError::none;
}

template <uint8_t N, bool Arcs, bool Heater, uint8_t MarlinDwell, bool Modes, bool Printer, bool Retract>
GcodeError GcodeInterpreter<N, Arcs, Heater, MarlinDwell, Modes, Printer, Retract>::retract_settings(
    const GcodeBlock& b, bool recover, RetractionSlot<true>& slot) {
  using namespace gcode_detail;
  const uint32_t takes = gcode_letter_bit('N') | gcode_letter_bit('S') | gcode_letter_bit('F') |
                         (recover ? 0 : gcode_letter_bit('Z'));
  if (b.words & ~takes) return GcodeError::unused_word;
  for (uint8_t g = 0; g < kGcodeGroups; ++g)
    if (g != uint8_t(GcodeGroup::machine) && b.code[g] != GcodeCode::none) return GcodeError::multiple_actions;
  const bool inches = state_.modal.inches;
  constexpr int32_t kMaxLength = 1000000;      // 100 mm
  constexpr int32_t kMaxFeed = 1000000000;     // 100000 mm/min
  Retraction next = slot.value;
  const char letters[3] = {'S', 'F', 'Z'};
  int32_t* fields[3] = {recover ? &next.extra : &next.length, recover ? &next.recover_feed : &next.feed, &next.hop};
  for (uint8_t k = 0; k < 3; ++k) {
    if (!b.has(letters[k])) continue;
    int32_t v;
    if (!to_length(b.get(letters[k]), inches, v)) return GcodeError::out_of_range;
    const bool feed = k == 1;
    if (feed ? (v <= 0 || v > kMaxFeed) : (v < 0 || v > kMaxLength)) return GcodeError::out_of_range;
    *fields[k] = v;
  }
  slot.value = next;
  return GcodeError::none;
}

}  // namespace am
