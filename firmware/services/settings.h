// The machine settings in the EEPROM (docs/settings.md), on a board that
// declares them (board::kSettings): the table of core/board/settings.h with
// the board's figures as defaults, applied to the G-code interpreter's
// scale, the look-ahead planner's axis limits and junction deviation, the
// homing service and the soft limits.
//
// Contract
//   boot() once before the banner: reads the block and applies it, so
//   nothing the banner's host sends meets the board's figures instead. A
//   blank EEPROM (no tag) gives the board's defaults without a word; a
//   block of another version or layout, or one whose checksum or values are
//   wrong, gives the defaults and the text (in flash) of the one info line
//   main() prints after the banner (grbl `[MSG:...]`, Marlin `echo:...`);
//   nullptr otherwise. Nothing is written: the EEPROM keeps what it has
//   until a setting is stored.
//   The machine codes' settings where the board has them: the heater's PID
//   gains ($300..302: M301, an autotune), the printer codes' path
//   accelerations ($210..212: M204), the firmware retraction's ($220..224:
//   M207, M208). boot() and every apply put the stored ones in force; the
//   codes change them in RAM, as Marlin's do, and what is in force is what
//   `$$` and M503 show and what M500 and every other change store.
//   list() prints grbl's `$N=value` lines of the settings in force;
//   list(true) M503's lines (Marlin's codes where Marlin has one).
//   marlin(code, words) runs Marlin's settings code M<code> with the rest
//   of its line (`words`): M92/M201/M203/M205 set the named settings (all
//   or none), M500 stores the settings in force, M501 reloads the block
//   (with boot()'s line when it is bad), M502 restores the defaults
//   ($RST=$), M503 reports; it prints the whole answer. The caller has
//   waited for the machine at rest, as for change().
//   change(text) runs `N=value` or `RST=$` (the line after its `$`) and
//   prints the whole answer (`ok`, or the refusal: nothing changed); the
//   caller has waited for the machine to be at rest (path::at_rest()):
//   a new steps/mm keeps the machine position in steps and moves its mm
//   view (gcode::rescale()).
//
// Why
//   The EEPROM is the record: every change is stored at once (grbl's way),
//   so `$$` reads the block back instead of keeping a copy in RAM (the m32's
//   2 KB hold the look-ahead ring and an arc's stack). Only the figures the
//   machine runs on live in RAM, where they lived before (the interpreter's
//   scale, the planner's axis table, limits::settings), all integer or
//   float in the main loop: the step interrupt reads none of them.
#pragma once
#include <stdint.h>

namespace settings {

const char* boot();
void list(bool marlin_lines = false);
void change(const char* text);
void marlin(uint16_t code, char* words);

}  // namespace settings
