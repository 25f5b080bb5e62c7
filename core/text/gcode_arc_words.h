// The arc words of the G-code interpreter (gcode_interpreter.h, "Arcs" in
// its contract): GcodeInterpreter::arc() turns a G2/G3 line's plane, end
// point and I/J/K or R words into the centre and radius of its action.
// Included at the end of gcode_interpreter.h, which declares what it
// defines.
#pragma once
#include "gcode_interpreter.h"

namespace am {

// The arc from state_ (start) to a.coord[] (end), into a; m: the line's modes.
template <uint8_t N, bool Arcs, bool Heater, uint8_t MarlinDwell, bool Modes, bool Printer, bool Retract>
GcodeError GcodeInterpreter<N, Arcs, Heater, MarlinDwell, Modes, Printer, Retract>::arc(const GcodeBlock& b, const GcodeModal& m, GcodeAction<N>& a) const {
  using namespace gcode_detail;
  const uint32_t letters = plane_axes(m.plane);
  const uint16_t offset_letters = plane_offsets(m.plane);
  uint8_t idx[2];
  int32_t d[2], o[2];  // chord and centre - start, 1/10000 mm
  for (uint8_t k = 0; k < 2; ++k) {
    const uint8_t i = idx[k] = index_of(char(letters >> (8 * k)));
    if (i == kNoAxis) return GcodeError::no_such_axis;
    if (!add_checked(a.coord[i], -state_.axis[i].coord, d[k])) return GcodeError::target_out_of_range;
    const char letter = char(offset_letters >> (8 * k));
    o[k] = 0;
    if (b.has(letter) && !to_length(b.get(letter), m.inches, o[k])) return GcodeError::out_of_range;
  }
  uint32_t radius;
  GcodeError e;
  if (b.has('R')) {
    int32_t r;
    if (!to_length(b.get('R'), m.inches, r)) return GcodeError::out_of_range;
    e = r_arc_centre(d, r, m.motion == Motion::arc_ccw, o, radius);
  } else {
    e = offset_arc_check(d, o, radius);
  }
  if (e != GcodeError::none) return e;
  for (uint8_t k = 0; k < 2; ++k) {
    const uint8_t i = idx[k];
    const GcodeAxisState& start = state_.axis[i];
    int32_t centre, steps;
    if (!add_checked(start.coord, o[k], centre) || !machine_steps(i, centre, start.offset, steps) ||
        !add_checked(steps, -start.steps, a.centre[k]))
      return GcodeError::target_out_of_range;
    a.centre_length[k] = o[k];
    a.plane_axis[k] = i;
  }
  a.clockwise = m.motion == Motion::arc_cw;
  a.plane_axis[2] = index_of(char(letters >> 16));
  a.radius = int32_t(radius);
  return GcodeError::none;
}

}  // namespace am
