// Where the motors are while they move: the steps the step interrupt has
// made, worked out in the main loop when asked, at no cost to the
// interrupt and almost none to the path.
//
// Contract
//   The path reports every block it hands to the engine, when it takes it
//   (taken(): its steps, the axes that move and those that move forward, its
//   events, its serial and interpolator if it is coordinated), and every run
//   of it that it queues (queued(): events).
//   now(steps) gives, for every axis, the signed steps made since power-up
//   up to one instant, the running segment's included (uint32 arithmetic: it
//   wraps, differences stay exact).
//
// Why
//   Counting in the interrupt would cost every step, and the 160 kHz fast
//   path has no cycle to spare; counting every finished segment in the main
//   loop costs the path enough per segment to starve that same fast path
//   (tests/sim/test_step_timing.cpp). So now() starts from the steps of
//   every block handed over and takes off what has not happened yet: the
//   runs of the newest block not queued yet, and the queue's segments not
//   yet made, newest first (the running one in part). A coordinated block's
//   share of a stretch of events comes from its interpolator in closed form
//   (LineDda::steps_after: floor((e |delta| + h) / N) after event e): a
//   block's segments sit together in the queue, so one stretch per block.
#pragma once
#include <stdint.h>

#include "../board.h"
#include "step_engine.h"

namespace odometer {

void taken(const int32_t (&steps)[board::Axes::count], uint8_t axes, uint8_t dirs, uint32_t events,
           const engine::Dda* dda, uint8_t serial);
void queued(uint16_t events);
void now(uint32_t (&steps)[board::Axes::count]);

}  // namespace odometer
