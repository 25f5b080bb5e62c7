// The G-code side of the cnc program's line protocol (docs/gcode.md): a line
// that starts with G, M or N and a number, or with a comment (after blanks),
// is G-code; the direct controls
// (MOVE, POS, WAIT, RELEASE, MODE: docs/protocol.md) stay beside it, with the
// same answers in the board's style (reply.h).
//
// Contract
//   accept(line) parses and interprets one line (core/text/gcode_*.h). On an
//   error it prints the refusal (reply.h) and nothing changes; otherwise the line's
//   action waits, and execute() carries it out once the machine can take it
//   (false: not yet, call again), printing its report and `ok`.
//   Moves (G0, G1) become one coordinated block each (firmware/engine), from
//   rest to rest until the look-ahead planner exists: F is the path feed,
//   turned into the dominant axis's rate by the move's length; G0 runs at the
//   axes' limits. G4 queues an idle stretch of P in the step engine, so it
//   times out after the motion before it and to the tick. G2/G3 are refused
//   (the arc interpolator is not on the engine yet).
#pragma once
#include "../../../core/text/gcode_parser.h"
#include "../../../core/text/gcode_state.h"

namespace gcode {

// Whether `line` is G-code.
bool claims(const char* line);
// False when the line was refused (its error is printed).
bool accept(const char* line);
bool execute();
// An axis's scale, position units per metre (the interpreter's mm<->steps):
// the board's (its descriptor), or its steps/mm setting
// (firmware/services/settings.h), which sets it at rest and then calls
// rescale(): machine positions and G92 offsets in steps stay, the program
// positions in mm follow.
void set_scale(uint8_t axis, uint32_t steps_per_m);
void rescale();
uint32_t steps_per_m(uint8_t axis);
// The modal feed, whole mm/min (0 before the first F).
uint32_t feed_mm_per_min();
// A printer's overrides (firmware/services/printer_codes.h), percent: of
// every later feed move's F (M220) and of every later move's E steps
// (M221, the interpreter's flow).
void set_feed_percent(uint16_t percent);
uint16_t feed_percent();
void set_flow(uint16_t percent);
uint16_t flow();
// The firmware retraction's settings (board::kFirmwareRetract): M207's and
// M208's, and the settings' (firmware/services/settings.h), which leave its
// state (retracted or not) as it is.
am::GcodeRetraction retraction();
void set_retraction(const am::GcodeRetraction& settings);
// Prints the refusal `e` (its text and grbl number): the direct controls
// share the texts they have in common with G-code.
void refuse(am::GcodeError e);
// grbl's `$G`: `[GC:G1 G17 G21 G90 G94 M82 F1200]` (motion, plane,
// units, distance, feed mode, E mode, feed in the line's units).
void write_state();

}  // namespace gcode
