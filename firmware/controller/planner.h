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

#include "../../core/speed_ramp.h"

namespace planner {

void start(uint8_t axis, int32_t steps, const am::RampConfig& config);
void pump();
bool idle();
int32_t position(uint8_t axis);

}  // namespace planner
