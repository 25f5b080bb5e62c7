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

uint8_t clamp(uint8_t axis, am::RampConfig& config) {
  const uint32_t own_limit = board::Axes::max_rate_at(axis);
  const uint32_t rate_limit = own_limit ? own_limit : board::kMaxStepRate;
  uint8_t clamped = 0;
  if (config.max_rate > rate_limit) {
    config.max_rate = rate_limit;
    clamped |= kClampedRate;
  }
  if (config.accel > board::kMaxAccel) {
    config.accel = board::kMaxAccel;
    clamped |= kClampedAccel;
  }
  if (config.decel > board::kMaxAccel) {
    config.decel = board::kMaxAccel;
    clamped |= kClampedDecel;
  }
  return clamped;
}

bool fits(uint8_t axis, int32_t steps) {
  // Both ways of counting the first step (the engine may go idle before
  // start() runs) must fit.
  for (uint8_t idle = 0; idle < 2; ++idle) {
    const int64_t end = int64_t(positions[axis]) + board::Axes::units_for(axis, steps, idle);
    if (end < -int64_t(0x80000000) || end > int64_t(0x7FFFFFFF)) return false;
  }
  return true;
}

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
  // Fill the queue as far as it goes, then let the engine run on it: a move
  // from rest starts only with a full queue (or all of it queued).
  for (;;) {
    if (pending.count == 0) {
      if (ramp.finished()) break;
      pending = ramp.next_run();
    }
    if (engine::queue_full()) break;
    engine::push(am::StepSegment::make(pending.interval, pending.count, axis_mask, dir_mask));
    pending.count = 0;
  }
  engine::start();
}

bool idle() { return pending.count == 0 && ramp.finished(); }

bool ready_for(uint8_t axis) { return idle() && (!engine::busy() || axis_mask == uint8_t(1u << axis)); }

int32_t position(uint8_t axis) { return positions[axis]; }

}  // namespace planner
