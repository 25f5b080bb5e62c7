#include "planner.h"

#include "../board.h"
#include "step_engine.h"

namespace planner {
namespace {

am::SpeedRamp ramp;
am::StepRun pending{0, 0};  // a run taken from the ramp but not yet queued
uint8_t axis_mask;
uint8_t dir_mask;
int32_t positions[board::Axes::count];

}  // namespace

void start(uint8_t axis, int32_t steps, const am::RampConfig& config) {
  const bool forward = steps > 0;
  const uint32_t distance = forward ? uint32_t(steps) : uint32_t(-(steps + 1)) + 1u;
  ramp.plan(distance, config);
  // One division per ramp step costs about 1800 cycles here: above 4 kHz
  // the ramp is planned in runs of sqrt(n) steps instead (speed_ramp.h).
  ramp.batch_below(F_CPU / 4000);
  axis_mask = uint8_t(1u << axis);
  dir_mask = forward ? axis_mask : 0;
  const bool idle = !engine::busy();
  board::Axes::energise(axis_mask);
  positions[axis] += board::Axes::units_for(axis, steps, idle);
  pump();
}

void pump() {
  for (;;) {
    if (pending.count == 0) {
      if (ramp.finished()) return;
      pending = ramp.next_run();
    }
    if (engine::queue_full()) return;
    engine::push(am::StepSegment::make(pending.interval, pending.count, axis_mask, dir_mask));
    pending.count = 0;
  }
}

bool idle() { return pending.count == 0 && ramp.finished(); }

int32_t position(uint8_t axis) { return positions[axis]; }

}  // namespace planner
