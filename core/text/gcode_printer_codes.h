// The printer M-codes of the G-code interpreter (gcode_interpreter.h,
// "Heater codes and printer codes" in its contract): GcodeInterpreter::printer() turns an
// M73, M201, M203, M204, M205, M220 or M221 line into a
// GcodePrinterCommand, with its words checked and nothing in the
// interpreter's state changed. Reached through heater() (the same board
// flag, the same rule that the code is alone on its line). Included at the
// end of gcode_interpreter.h, which declares what it defines.
//
// Contract
//   Action printer, GcodePrinterCommand: each word in the code's slots, in
//   the line's units. Alone on the line, as the heater's.
//     M201 <axes>        accelerations, mm/s^2, above 0 (bad_limit)
//     M203 <axes>        top feeds, mm/s, above 0
//     M204 [P][T][R][S]  path accelerations, mm/s^2, above 0: print,
//                        travel, retract; S print and travel
//     M205 [J]           junction deviation, 0.001 .. 10 mm; X Y Z E S T B
//                        (jerk and minimum feeds) taken, not used
//     M73 [P][R]         progress, whole 0 .. 100 %, R whole minutes left;
//                        Q, S taken, not used (bad_percent)
//     M220 [S], M221 [S] feed override, flow: whole 10 .. 500 %
#pragma once
#include "gcode_interpreter.h"

namespace am {

template <uint8_t N, bool Arcs, bool Heater, uint8_t MarlinDwell, bool Modes, bool Printer, bool Retract>
GcodeError GcodeInterpreter<N, Arcs, Heater, MarlinDwell, Modes, Printer, Retract>::printer(const GcodeBlock& b,
                                                                                   GcodeAction<N>& a) const {
  const GcodeCode code = b.group(GcodeGroup::machine);
  const bool limits = code >= GcodeCode::m201 && code <= GcodeCode::m204;  // lengths per s or s^2, above 0
  // The slots' letters (GcodePrinterCommand), then the words taken and not
  // used: M205's classic-jerk and minimum-feed words a slicer's machine
  // limits carry (the planner has no jerk), M73's silent-mode Q and S
  // (PrusaSlicer).
  constexpr uint8_t kSlots = N > 4 ? N : 4;
  char letter[kSlots] = {'S'};
  uint32_t ignored = 0;
  if (code == GcodeCode::m201 || code == GcodeCode::m203) {
    for (uint8_t i = 0; i < N; ++i) letter[i] = axes_[i].letter;
  } else if (code == GcodeCode::m204) {
    letter[0] = 'P', letter[1] = 'T', letter[2] = 'R', letter[3] = 'S';
  } else if (code == GcodeCode::m205) {
    letter[0] = 'J';
    ignored = gcode_letter_bit('X') | gcode_letter_bit('Y') | gcode_letter_bit('Z') | gcode_letter_bit('E') |
              gcode_letter_bit('S') | gcode_letter_bit('T') | gcode_letter_bit('B');
  } else if (code == GcodeCode::m73) {
    letter[0] = 'P', letter[1] = 'R';
    ignored = gcode_letter_bit('Q') | gcode_letter_bit('S');
  }
  uint32_t takes = gcode_letter_bit('N') | ignored;
  for (uint8_t k = 0; k < kSlots; ++k)
    if (letter[k]) takes |= gcode_letter_bit(letter[k]);
  if (b.words & ~takes) return GcodeError::unused_word;
  GcodePrinterCommand<N>& p = a.printer;
  p.code = code;
  p.given = 0;
  for (uint8_t k = 0; k < kSlots; ++k) {
    if (!letter[k] || !b.has(letter[k])) continue;
    int32_t v = b.get(letter[k]);
    p.given = uint8_t(p.given | 1u << k);
    if (limits || code == GcodeCode::m205) {
      if (v <= 0 || (!limits && (v < 10 || v > 100000)))
        return GcodeError::bad_limit;
    } else {  // whole: M73 P 0 .. 100 and R, M220/M221 S 10 .. 500
      const int32_t lo = code == GcodeCode::m73 ? 0 : 100000;
      const int32_t hi = code != GcodeCode::m73 ? 5000000 : k == 0 ? 1000000 : 0x7FFFFFFF;
      if (v % 10000 || v < lo || v > hi) return GcodeError::bad_percent;
      v /= 10000;
    }
    p.value[k] = v;
  }
  return hold_position(a, GcodeActionKind::printer);
}

}  // namespace am
