// The machine's limits on a board with endstops (board::Endstops,
// docs/homing.md): the alarm a hard limit raises, the homed axes and the
// soft limits they bring.
//
// Contract
//   The path calls tripped() when the step interrupt has stopped at an
//   endstop (engine::stopped_at_endstop()), after it dropped every block.
//   While a homing move runs (homing(true)) that is what the move looks for:
//   found() says it happened (and forgets it). Any other time it is a hard
//   limit: alarm() from then on, every axis unhomed (the motion queued
//   behind the stop never ran, so the position is lost) and news() true
//   once, for the program to say so. fail() raises the same alarm without a
//   trip (a homing that failed, a soft reset in motion: any board, with
//   endstops or not). While alarm() holds, planner::check()
//   refuses every move (Refusal::alarm); unlock() ends it (M999, grbl's $X)
//   and leaves the axes unhomed.
//   set_homed(k) marks switch k's axis homed (the homing service has put
//   it at its `home`). outside(move) is true when the move would take a
//   homed axis beyond its travel: from `home` away from the switch by
//   `travel` (planner::check(): Refusal::soft_limit, before the move
//   starts). Axes with switches count their position in steps.
//   settings: the board's HomingSettings (board::kHomingSettings), in RAM;
//   on a board with settings (firmware/services/settings.h) they come from
//   the EEPROM, with soft_limits ($20: outside() is false while off) and
//   homing_enabled ($22: G28 and $H refused while off).
#pragma once
#include <stdint.h>

#include "../board.h"
#include "planner.h"

namespace limits {

constexpr uint8_t kSwitches = board::Endstops::count;
using Settings = HomingSettings<kSwitches ? kSwitches : 1>;
extern Settings settings;
extern bool soft_limits, homing_enabled;

bool alarm();
void unlock();
void fail();
void tripped();
bool news();

void homing(bool on);
bool found();

void set_homed(uint8_t k);
bool outside(const planner::Move& move);

}  // namespace limits
