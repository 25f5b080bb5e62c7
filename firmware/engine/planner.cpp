#include "planner.h"

#include <avr/pgmspace.h>

#include "limits.h"
#include "odometer.h"

namespace planner {
namespace {

int32_t positions[board::Axes::count];
uint32_t counted[board::Axes::count];  // steps counted in, as the odometer counts them out

uint32_t magnitude(int32_t steps) { return steps < 0 ? uint32_t(-(steps + 1)) + 1u : uint32_t(steps); }

bool coordinated(uint8_t mask) { return (mask & (mask - 1)) != 0; }

uint32_t rate_limit(uint8_t axis, bool several) {
  const uint32_t own = board::Axes::max_rate_at(axis);
  return (own && !several) ? own : board::kMaxStepRate;
}

}  // namespace

uint8_t mask_of(const Steps& steps) {
  uint8_t mask = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i)
    if (steps[i]) mask |= uint8_t(1u << i);
  return mask;
}

uint8_t dirs_of(const Steps& steps) {
  uint8_t dirs = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i)
    if (steps[i] > 0) dirs |= uint8_t(1u << i);
  return dirs;
}

uint32_t dominant_count(const Steps& steps) {
  uint32_t most = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i)
    if (magnitude(steps[i]) > most) most = magnitude(steps[i]);
  return most;
}

Refusal check(const Move& move) {
  if (limits::alarm()) return Refusal::alarm;
  const uint8_t mask = mask_of(move.steps);
  if (mask == 0) return Refusal::nothing_to_do;
  // The timer-pulsed axis's edge is armed one period ahead, before the
  // interpolator has said whether it steps: it moves alone.
  if (coordinated(mask) && (mask & board::Axes::timer_mask)) return Refusal::timer_axis_not_alone;
  // Both ways of counting the first step (the engine may go idle before
  // the move is queued) must fit; they differ only on axes with units of
  // their own.
  for (uint8_t i = 0; i < board::Axes::count; ++i) {
    for (uint8_t at_rest = 0; at_rest < (board::Axes::own_units ? 2 : 1); ++at_rest) {
      int32_t end;
      if (__builtin_add_overflow(positions[i], board::Axes::units_for(i, move.steps[i], at_rest), &end))
        return Refusal::position_range;
    }
  }
  return limits::kSwitches && limits::outside(move) ? Refusal::soft_limit : Refusal::none;
}

const char* refusal_text(Refusal r) {
  return r == Refusal::position_range         ? PSTR("move would leave the position range")
         : r == Refusal::timer_axis_not_alone ? PSTR("the hardware-timed axis moves alone")
         : r == Refusal::alarm                ? PSTR("alarm (hard limit, failed homing, reset in motion): M999 or $X unlocks")
                                              : PSTR("move beyond the soft limits");
}

RampError check_ramp(const Ramp& ramp) {
  if (ramp.rate == 0) return RampError::zero_speed;
  if (ramp.accel == 0) return RampError::zero_accel;
  if (ramp.rate > board::kStepTimerHz) return RampError::rate_above_tick;
  // The first step from rest, sqrt(2 / A) s, must fit one segment's
  // interval (core/motion/trapezoid.h): A >= 2 (f / 2^24)^2.
  const uint32_t f24 = board::kStepTimerHz >> 24;
  if (ramp.accel < 2 * (f24 + 1) * (f24 + 1)) return RampError::accel_too_low;
  return RampError::none;
}

uint8_t clamp(const Move& move, Ramp& ramp) {
  const uint32_t events = dominant_count(move.steps);
  const bool several = coordinated(mask_of(move.steps));
  uint8_t clamped = 0;
  for (uint8_t i = 0; i < board::Axes::count; ++i) {
    const uint32_t n = magnitude(move.steps[i]);
    if (n == 0) continue;
    // Axis i steps n times in `events` events: F * n / events <= its limit.
    const uint64_t most = uint64_t(rate_limit(i, several)) * events / n;
    if (ramp.rate > most) {
      ramp.rate = uint32_t(most);
      clamped |= kClampedRate;
    }
  }
  if (ramp.accel > board::kMaxAccel) {
    ramp.accel = board::kMaxAccel;
    clamped |= kClampedAccel;
  }
  return clamped;
}

void count(const Move& move, bool at_rest) {
  for (uint8_t i = 0; i < board::Axes::count; ++i) {
    positions[i] += board::Axes::units_for(i, move.steps[i], at_rest);
    if (board::kOdometer) counted[i] += uint32_t(move.steps[i]);
  }
}

int32_t position(uint8_t axis) { return positions[axis]; }

void set_position(uint8_t axis, int32_t units) { positions[axis] = units; }

void positions_now(int32_t (&units)[board::Axes::count]) {
  if (!board::kOdometer) {
    for (uint8_t i = 0; i < board::Axes::count; ++i) units[i] = positions[i];
    return;
  }
  uint32_t made[board::Axes::count];
  odometer::now(made);
  for (uint8_t i = 0; i < board::Axes::count; ++i)
    units[i] = positions[i] - board::Axes::units_for(i, int32_t(counted[i] - made[i]), false);
}

}  // namespace planner
