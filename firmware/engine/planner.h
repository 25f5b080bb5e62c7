// The planner: turns one accepted move into step segments for the engine.
//
// Contract
//   A Move gives every axis of the board its steps (0 = stays). One axis
//   moving is a one-axis block; several move together as a coordinated
//   block: a straight line in steps, the axis with the most steps (the
//   dominant one) stepping at every event and the others on its Bresenham
//   schedule (core/motion/line_dda.h), all ending on their targets together.
//   The ramp (rate F, acceleration A, deceleration D) is the dominant axis's.
//
//   The caller asks ready_for() (false: try again later), checks the ramp
//   configuration, applies clamp() and then calls start(). pump() is called
//   from the main loop and pushes as many segments as the engine's queue
//   accepts, returning at once when it is full. idle() is true when every
//   segment of the move has been queued. Positions are counted here when a
//   move is accepted, in each axis's position units (steps; 1/64 full step
//   for coil-driven axes, so moves in different excitation modes add up):
//   what the protocol reports once the engine is idle is where the motors
//   are.
#pragma once
#include <stdint.h>

#include "../../core/motion/speed_ramp.h"
#include "../board.h"

namespace planner {

struct Move {
  int32_t steps[board::Axes::count];
};

// Why a move cannot run as given (checked before anything moves).
enum class Refusal : uint8_t { none, nothing_to_do, position_range, timer_axis_not_alone };
Refusal check(const Move& move);

// The motion policy: F is held so that no axis exceeds its own rate limit
// (the dominant axis's limit, and each other axis's scaled by its share of
// the events), and A and D to the board's kMaxAccel. A coordinated block
// steps from the C handler, so its events are held to the board's
// kMaxStepRate. Returns which were clamped (kClamped* bits), so the caller
// can say so before the move runs.
constexpr uint8_t kClampedRate = 1, kClampedAccel = 2, kClampedDecel = 4;
uint8_t clamp(const Move& move, am::RampConfig& config);

// Whether `move` may start now: the last move is queued, it moved the same
// axes or has ended (a move on other axes never starts under a running one,
// so energising them cannot hold off the step interrupt), and a coordinated
// block has an interpolator slot free.
bool ready_for(const Move& move);
void start(const Move& move, const am::RampConfig& config);
// Queues `ms` milliseconds in which nothing steps, after everything queued
// so far (call when idle()): a dwell timed by the step timer itself. A move
// of the same axes as the last one queues behind it without a gap.
void dwell(uint32_t ms);
void pump();
bool idle();
int32_t position(uint8_t axis);

}  // namespace planner
