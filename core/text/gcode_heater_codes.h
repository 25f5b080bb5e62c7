// The heater M-codes of the G-code interpreter (gcode_interpreter.h, "Heater
// codes and printer codes" in its contract): GcodeInterpreter::heater() turns an M104, M105,
// M106, M107 (the part fan), M108, M109, M155, M301, M303 or M500 line into a
// GcodeHeaterCommand, with
// its words checked and nothing in the interpreter's state changed. Included
// at the end of gcode_interpreter.h, which declares what it defines.
//
// Contract
//   Their words are parameters, never axes (M303's C is the cycle count),
//   and the line holds no other code (heater_code_alone).
//     M104 S<C>          set the target (S0: off)
//     M109 S<C> | R<C>   set it and wait (S: only while heating; R: either way)
//     M105, M108         report; end a wait (the machine's business)
//     M155 S<s>          auto-report every S whole seconds, 0 .. 60 (0: off)
//     M106 [S<duty>], M107  the part fan: duty 0 .. 255 (M106 alone: 255),
//                        M107: 0 (a board without a heater, not a printer,
//                        has neither: unsupported_code)
//     M301 [P][I][D]     set the given PID gains (Marlin's units), report
//     M303 [S<C>][C<n>]  relay autotune at S (default 150 C), C cycles 3 .. 20
//                        (default 5)
//   Temperatures are 0 .. 260 C (kGcodeMaxTarget; M303 above 0), kept in
//   0.01 C; gains P, I 0 .. 1000, D 0 .. 10000, kept in thousandths. A word
//   the code does not take is unused_word; a missing S is
//   missing_temperature. The state does not change.
#pragma once
#include "gcode_interpreter.h"

namespace am {

namespace gcode_detail {

// M301's word `letter` into thousandths: 1 given, 0 absent, 8 beyond 0 .. max
// (1/10000 units).
inline uint8_t gain(const GcodeBlock& b, char letter, int32_t max, uint32_t& out) {
  if (!b.has(letter)) return 0;
  const int32_t v = b.get(letter);
  out = (uint32_t(v) + 5) / 10;
  return v < 0 || v > max ? 8 : 1;
}

// A whole number lo .. hi in a word's 1/10000 units, into out.
inline bool whole_in(int32_t v, uint8_t lo, uint8_t hi, uint8_t& out) {
  if (v < 0 || v % 10000) return false;
  const int32_t n = v / 10000;
  out = uint8_t(n);
  return n >= lo && n <= hi;
}

}  // namespace gcode_detail

// A heater M-code line (see Heater codes); nothing in the state changes.
template <uint8_t N, bool Arcs, bool Heater, uint8_t MarlinDwell, bool Modes, bool Printer, bool Retract>
GcodeError GcodeInterpreter<N, Arcs, Heater, MarlinDwell, Modes, Printer, Retract>::heater(const GcodeBlock& b,
                                                                                  GcodeAction<N>& a) const {
  const GcodeCode code = b.group(GcodeGroup::machine);
  const bool fan = code == GcodeCode::m106 || code == GcodeCode::m107;
  const bool printer_code = code >= GcodeCode::m73, seed_code = code == GcodeCode::m3 || code == GcodeCode::m5;
  if (!Heater || ((printer_code || seed_code) && !Printer))
    return fan || printer_code || seed_code ? GcodeError::unsupported_code : GcodeError::no_heater;
  for (uint8_t g = 0; g < kGcodeGroups; ++g)
    if (g != uint8_t(GcodeGroup::machine) && b.code[g] != GcodeCode::none) return GcodeError::heater_code_alone;
  if (printer_code) return printer(b, a);
  GcodeHeaterCommand& h = a.heater;
  // The seed's M3 S<C> and M5: the hot end's control on at S, as M104;
  // off, as M104 S0 (its extrusion is what the E words do).
  h.code = seed_code ? GcodeCode::m104 : code;
  h.target = 0;
  const bool m109 = code == GcodeCode::m109, m155 = code == GcodeCode::m155;
  const bool m301 = code == GcodeCode::m301, m303 = code == GcodeCode::m303;
  const bool needs_s = m109 || m155 || code == GcodeCode::m104 || code == GcodeCode::m3;
  const uint32_t s = gcode_letter_bit('S'), r = gcode_letter_bit('R');
  uint32_t takes = gcode_letter_bit('N');
  if (needs_s) takes |= m109 && !b.has('S') ? r : s;
  if (m301) takes |= gcode_letter_bit('P') | gcode_letter_bit('I') | gcode_letter_bit('D');
  if (m303) takes |= s | gcode_letter_bit('C');
  if (code == GcodeCode::m106) takes |= s;
  if (b.words & ~takes) return GcodeError::unused_word;
  if (needs_s && !(b.words & (s | r))) return GcodeError::missing_temperature;
  h.wait_cooling = b.has('R');
  const int32_t t = b.get(h.wait_cooling ? 'R' : 'S');  // 1/10000
  if (fan) {  // duty S 0 .. 255 (Marlin's full speed without S); M107: 0
    h.count = b.has('S') ? 0 : code == GcodeCode::m106 ? 255 : 0;
    if (b.has('S') && !gcode_detail::whole_in(t, 0, 255, h.count)) return GcodeError::out_of_range;
  } else if (m155) {
    if (!gcode_detail::whole_in(t, 0, 60, h.count)) return GcodeError::bad_interval;
  } else if (m301) {
    using gcode_detail::gain;
    h.gains_given = uint8_t(gain(b, 'P', 10000000l, h.gains[0]) | gain(b, 'I', 10000000l, h.gains[1]) << 1 |
                            gain(b, 'D', 100000000l, h.gains[2]) << 2);
    if (h.gains_given & 0x38) return GcodeError::bad_gains;
  } else if (needs_s || m303) {
    const bool given = (b.words & (s | r)) != 0;
    if (given && (t < m303 || t > int32_t(kGcodeMaxTarget) * 100)) return GcodeError::bad_temperature;
    h.target = given ? int16_t((t + 50) / 100) : kGcodeAutotuneDefault;
    h.count = kGcodeAutotuneCycles;
    if (b.has('C') && !gcode_detail::whole_in(b.get('C'), 3, 20, h.count)) return GcodeError::bad_cycles;
  }
  return hold_position(a, GcodeActionKind::heater);
}

}  // namespace am
