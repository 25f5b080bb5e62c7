// The heater M-codes of the cnc program's G-code (docs/gcode.md, the
// interpreter's Heater codes) on the heater service (heater.h).
//
// Contract
//   run(command) carries out an accepted heater code and prints its whole
//   answer, `ok` included; false: not done yet (M109, M303 wait), call again
//   from the main loop. Answers:
//     M104            ok; M108: ok (it only ends a wait)
//     M105            ok T:<cur> /<target> @:<duty> (Marlin's line, printcore
//                     and OctoPrint read it)
//     M109            T:<cur> /<target> @:<duty> once a second while it waits,
//                     then ok. S: done once T >= target - 1 C (at once when
//                     hotter already, or for S0); R: once |T - target| <= 1 C.
//     M155            ok (the reports follow from the service)
//     M301            echo: p:<Kp> i:<Ki> d:<Kd> (the gains now), ok
//     M303            T: lines once a second, then
//                     `PID Autotune finished: Kp:<> Ki:<> Kd:<>` (applied), ok;
//                     or the refusal `autotune: <overshoot, timeout, sensor, gains
//                     out of range>` (heater off, the gains as they were)
//   A wait (M109, M303) ends early when a byte arrives: refused, `wait ended
//   by the host` (M109 keeps its target, M303 leaves the heater off and the
//   gains as they were); the line that came is then read as usual (M108 is
//   the one to send). It ends too when a fault latches: refused, `heater
//   halted` after the service's `Error:` line. M104, M109 and M303 after a
//   fault: refused, `heater halted (<fault>), reset to clear`, nothing changes.
//   Refusals in the board's style (apps/cnc/reply.h: Marlin's `Error:<text>`
//   and `ok` on the m32).
#pragma once
#include "../../core/text/gcode_interpreter.h"

namespace heater {

bool run(const am::GcodeHeaterCommand& command);

}  // namespace heater
