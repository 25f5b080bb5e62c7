// Homing (G28) on the board's endstops, and the alarm line of a hard limit
// (docs/homing.md), for a board whose header sets kHoming.
//
// Contract
//   run(axes) homes the axes in the mask (0: every axis with an endstop;
//   the caller has checked that each one has), one after the other in the
//   board's order, and returns busy until it is done: homed (each homed
//   axis is at its `home` and marked so for the soft limits: limits.h), or
//   failed, with an `error:` line said and the alarm raised (a switch not
//   found within 1.5 travel, or one that stays closed after backing off).
//   Per axis (board::kHomingSettings): a switch closed at the start is
//   backed off first; then a seek toward the switch at seek_rate until it
//   closes, back_off away, a locate toward it at locate_rate, pull_off away
//   at locate_rate; the position there is `home`. Only the homed axis moves;
//   each move starts and ends at rest with the board's default acceleration,
//   and a closing switch stops it within one step (the step interrupt's
//   check, engine::stopped_at_endstop()).
//   poll() from the main loop: says `ALARM: hard limit...` once when a hard
//   limit has stopped the machine (limits::news()).
#pragma once
#include <stdint.h>

namespace homing {

enum class Result : uint8_t { busy, homed, failed };
Result run(uint8_t axes);
void poll();

}  // namespace homing
