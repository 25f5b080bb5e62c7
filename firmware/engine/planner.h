// The motion policy: what a move may be, and where the axes are.
//
// Contract
//   A Move gives every axis of the board its steps (0 = stays). check()
//   refuses what the engine cannot run exactly, before anything moves.
//   check_ramp() refuses a rate or acceleration the profile cannot time.
//   clamp() holds a direct move's rate F so that no axis exceeds its own
//   limit (the dominant axis's, and each other axis's scaled by its share of
//   the events; a coordinated block steps from the C handler, so its events
//   are held to the board's kMaxStepRate) and its acceleration A to the
//   board's kMaxAccel, and says which it clamped, so the caller can report it
//   before the move runs. G-code blocks get the same limits from the
//   look-ahead planner's axis table (path.cpp).
//   count() adds a queued move into the positions, in each axis's position
//   units (steps; 1/64 full step for coil-driven axes, so moves in different
//   excitation modes add up): what position() reports once the engine is
//   idle is where the motors are; positions_now() is where they are while
//   they move. at_rest: nothing was moving or queued when the move was
//   accepted (a coil axis's first step after a mode change may be a partial
//   one).
#pragma once
#include <stdint.h>

#include "../board.h"

namespace planner {

struct Move {
  int32_t steps[board::Axes::count];
};

// A direct move's profile: dominant-axis steps/s and steps/s^2, from rest to
// rest.
struct Ramp {
  uint32_t rate;
  uint32_t accel;
};

// alarm: a hard limit or a failed homing locked the motion; soft_limit: a
// homed axis would leave its travel (firmware/engine/limits.h).
enum class Refusal : uint8_t { none, nothing_to_do, position_range, timer_axis_not_alone, alarm, soft_limit };
Refusal check(const Move& move);
// The error text of a refusal from position_range on (in flash).
const char* refusal_text(Refusal r);

enum class RampError : uint8_t { none, zero_speed, zero_accel, rate_above_tick, accel_too_low };
RampError check_ramp(const Ramp& ramp);

constexpr uint8_t kClampedRate = 1, kClampedAccel = 2;
uint8_t clamp(const Move& move, Ramp& ramp);

// Of steps per axis (a Move's, a planned block's): the steps of the axis
// with the most, which axes move, which move forward.
using Steps = int32_t[board::Axes::count];
uint32_t dominant_count(const Steps& steps);
uint8_t mask_of(const Steps& steps);
uint8_t dirs_of(const Steps& steps);

void count(const Move& move, bool at_rest);
int32_t position(uint8_t axis);
// Homing: the axis is at `units` (nothing moves).
void set_position(uint8_t axis, int32_t units);
// Where the motors are now, in the same units, while they move: position()
// less the steps counted but not yet made (firmware/engine/odometer.h), one
// instant for every axis. At rest it is position(). A coil axis's
// unfinished move from rest may be off by the partial first step it has
// not made yet (less than one step). On a board without the odometer
// (board::kOdometer) it is position().
void positions_now(int32_t (&units)[board::Axes::count]);

}  // namespace planner
