// The planner: turns one accepted move into step segments for the engine.
//
// Contract
//   start() takes a move of one axis (steps != 0) after the caller checked the
//   ramp configuration; pump() is called from the main loop and pushes as many
//   segments as the engine's queue accepts, returning at once when it is full.
//   idle() is true when every segment of the move has been queued.
//   Positions are counted here when a move is accepted, in each axis's
//   position units (steps; 1/64 full step for coil-driven axes, so moves in
//   different excitation modes add up): what the protocol reports once the
//   engine is idle is where the motors are.
#pragma once
#include <stdint.h>

#include "../../core/motion/speed_ramp.h"

namespace planner {

// The motion policy: a move's rate is held to its axis's limit and its
// acceleration and deceleration to the board's kMaxAccel. Returns which were
// clamped (kClamped* bits), so the caller can say so before the move runs.
constexpr uint8_t kClampedRate = 1, kClampedAccel = 2, kClampedDecel = 4;
uint8_t clamp(uint8_t axis, am::RampConfig& config);

// Whether the move ends inside the position counter's range (int32 units);
// start() takes only a move that does, so a position can never wrap.
bool fits(uint8_t axis, int32_t steps);
void start(uint8_t axis, int32_t steps, const am::RampConfig& config);
void pump();
bool idle();
// Whether a move of `axis` may start now: the last move is queued, and it
// was on the same axis or has ended (a move on another axis never starts
// under a running one, so energising it cannot hold off the step interrupt).
bool ready_for(uint8_t axis);
int32_t position(uint8_t axis);

}  // namespace planner
