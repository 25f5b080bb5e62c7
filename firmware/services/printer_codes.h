// The printer M-codes of the cnc program's G-code (docs/gcode.md, the
// interpreter's Printer codes): progress, the machine limits a slicer's
// start G-code sets, and the feed and flow overrides. Linked with the
// heater service (a board with a heater is a printer).
//
// Contract
//   run(command) carries out an accepted printer code and prints its whole
//   answer, `ok` included. Every code is done at once: a limit applies to
//   the blocks queued after it (those queued before keep theirs), an
//   override to the moves accepted after it. Nothing is stored: a reset
//   brings back the board's figures.
//     M73 P R      `echo:Progress: <P>%, <R> min left` (what is given), ok
//     M201 <axes>  each axis's acceleration, mm/s^2
//     M203 <axes>  each axis's top feed, mm/s
//                  held within the board's (the step engine's top rate,
//                  board::kMaxAccel; at least 1 step/s and 2 steps/s^2):
//                  `echo:<axis> held within the board's limit` when it had to be
//     M204 P T R S the acceleration along the path of the moves that
//                  extrude, travel, only retract; S: print and travel
//     M205 J       the junction deviation, mm (X Y Z E S T B: no jerk here)
//     M220 [S]     feed override, percent of every later G1/G2/G3's F;
//                  without S `echo:FR:<p>%`
//     M221 [S]     flow, percent of every later move's E steps; without S
//                  `echo:E0 Flow: <p>%`
//   message(line) answers an `M117 <text>` line whole (the text up to a
//   `;` comment as an info line, then ok) and says whether it was one: the
//   G-code side asks before the parser, which would read the text as words.
#pragma once
#include "../../core/text/gcode_interpreter.h"
#include "../board.h"

namespace printer_codes {

void run(const am::GcodePrinterCommand<board::Axes::count>& command);
bool message(const char* line);

}  // namespace printer_codes
