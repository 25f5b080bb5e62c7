#include "planner.h"

#include "step_engine.h"

namespace planner {
namespace {

am::SpeedRamp ramp;
am::StepRun pending{0, 0};  // a run taken from the ramp but not yet queued
uint8_t axis_mask;
uint8_t dir_mask;
uint8_t block;  // the coordinated block's serial
uint32_t dwell_ms;  // of a dwell still to be queued
int32_t positions[board::Axes::count];

uint32_t magnitude(int32_t steps) { return steps < 0 ? uint32_t(-(steps + 1)) + 1u : uint32_t(steps); }

uint8_t mask_of(const Move& move) {
  uint8_t mask = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i)
    if (move.steps[i]) mask |= uint8_t(1u << i);
  return mask;
}

uint32_t dominant_count(const Move& move) {
  uint32_t most = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i)
    if (magnitude(move.steps[i]) > most) most = magnitude(move.steps[i]);
  return most;
}

bool coordinated(uint8_t mask) { return (mask & (mask - 1)) != 0; }

uint32_t rate_limit(uint8_t axis, bool several) {
  const uint32_t own = board::Axes::max_rate_at(axis);
  return (own && !several) ? own : board::kMaxStepRate;
}

}  // namespace

Refusal check(const Move& move) {
  const uint8_t mask = mask_of(move);
  if (mask == 0) return Refusal::nothing_to_do;
  // The timer-pulsed axis's edge is armed one period ahead, before the
  // interpolator has said whether it steps: it moves alone.
  if (coordinated(mask) && (mask & board::Axes::timer_mask)) return Refusal::timer_axis_not_alone;
  // Both ways of counting the first step (the engine may go idle before
  // start() runs) must fit.
  for (uint8_t i = 0; i < board::Axes::count; ++i) {
    for (uint8_t idle = 0; idle < 2; ++idle) {
      const int64_t end = int64_t(positions[i]) + board::Axes::units_for(i, move.steps[i], idle);
      if (end < -int64_t(0x80000000) || end > int64_t(0x7FFFFFFF)) return Refusal::position_range;
    }
  }
  return Refusal::none;
}

uint8_t clamp(const Move& move, am::RampConfig& config) {
  const uint32_t events = dominant_count(move);
  const bool several = coordinated(mask_of(move));
  uint8_t clamped = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i) {
    const uint32_t n = magnitude(move.steps[i]);
    if (n == 0) continue;
    // Axis i steps n times in `events` events: F * n / events <= its limit.
    const uint64_t most = uint64_t(rate_limit(i, several)) * events / n;
    if (config.max_rate > most) {
      config.max_rate = uint32_t(most);
      clamped |= kClampedRate;
    }
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

void start(const Move& move, const am::RampConfig& config) {
  const uint8_t mask = mask_of(move);
  uint8_t dirs = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i)
    if (move.steps[i] > 0) dirs |= uint8_t(1u << i);
  if (coordinated(mask)) engine::begin_block(block)->start(move.steps);
  ramp.plan(dominant_count(move), config);
  // One division per ramp step costs about 1800 cycles here: above 4 kHz
  // the ramp is planned in runs of sqrt(n) steps instead (speed_ramp.h).
  ramp.batch_below(F_CPU / 4000);
  axis_mask = mask;
  dir_mask = dirs;
  const bool idle = !engine::busy();
  board::Axes::energise(mask);
  for (uint8_t i = 0; i < board::Axes::count; ++i) positions[i] += board::Axes::units_for(i, move.steps[i], idle);
  pump();
}

void dwell(uint32_t ms) { dwell_ms = ms; }

void pump() {
  // Fill the queue as far as it goes, then let the engine run on it: a move
  // from rest starts only with a full queue (or all of it queued).
  for (;;) {
    if (pending.count == 0 && dwell_ms) {
      // Whole milliseconds, one timer period each, no axis stepping.
      const uint16_t ms = dwell_ms > 0xFFFF ? 0xFFFF : uint16_t(dwell_ms);
      if (!engine::push(am::StepSegment::make(F_CPU / 1000, ms, 0, 0))) break;
      dwell_ms -= ms;
      continue;
    }
    if (pending.count == 0) {
      if (ramp.finished()) break;
      pending = ramp.next_run();
    }
    if (engine::queue_full()) break;
    am::StepSegment s = am::StepSegment::make(pending.interval, pending.count, axis_mask, dir_mask);
    s.block = block;
    engine::push(s);
    pending.count = 0;
  }
  engine::start();
}

bool idle() { return pending.count == 0 && ramp.finished() && dwell_ms == 0; }

bool ready_for(const Move& move) {
  const uint8_t mask = mask_of(move);
  if (!idle() || (engine::busy() && axis_mask != mask)) return false;
  return !coordinated(mask) || engine::block_available();
}

int32_t position(uint8_t axis) { return positions[axis]; }

}  // namespace planner
