// Feed hold on the exact trapezoid: a block stopped part-way at its own
// acceleration, and restarted from rest, without losing or adding a step.
//
// Contract
//   begin(b) notes the block whose runs (TrapezoidRuns) are being handed out,
//   as it was started. stop(runs, last_interval, tick_hz), called between
//   runs (runs.between_runs()), replaces every event not handed out yet:
//     - slowing down from the speed reached, tick_hz / last_interval (the
//       interval of the last run handed out, so the stop's first interval
//       follows on from it; the block's entry if none of it is out), at the
//       block's acceleration, to rest after ceil(v^2 / 2 accel) events when
//       that many are left: the events after those are held();
//     - or, with fewer left, slowing down over all of them; the block then
//       ends at speed and carried() says how much slower than planned
//       (exit_speed() over the planned exit, at most 1), the factor the
//       next block's planned entry is to be multiplied by, so that it goes
//       on slowing;
//     the speed reached is taken at most the planned deceleration's to the
//     block's exit there, sqrt(exit^2 + 2 accel left), so a stop never ends
//     a block faster than planned;
//     - or, from rest with nothing out yet, nothing at all: every event is
//       held (stop() returns false: no runs to hand out).
//   resume(runs, tick_hz) starts the held events from rest to the block's
//   planned exit, or what accelerating over them reaches of it, and returns
//   the factor (at most 1) by which the next block's entry must be lowered
//   for that, 1 when nothing was held or the exit is reached.
//   Events: those handed out before stop() plus the stop's plus held() are
//   the block's, always.
//
// Why
//   The step generator only ever changes what is not queued yet (the engine's
//   queue is committed), so a hold starts where the queue ends; starting the
//   stop at the last run's own speed keeps the intervals continuous across
//   it. Float, main loop only, like the trapezoid it drives. A class: the
//   AVR reaches its members through one pointer (half the code of globals).
#pragma once
#include <math.h>
#include <stdint.h>

#include "trapezoid.h"

namespace am {

class FeedHold {
 public:
  void begin(const TrapezoidBlock& b) {
    block_ = b;
    held_ = 0;
    stopped_ = false;
  }

  [[gnu::noinline]] bool stop(TrapezoidRuns& runs, uint32_t last_interval, uint32_t tick_hz) {
    stopped_ = true;
    const uint32_t left = runs.events_left();
    if (left == 0) return true;  // it ends here: the next block slows down instead
    float v = left < block_.events ? float(tick_hz) / float(last_interval) : block_.entry;
    // Never above the planned deceleration to the exit (the last run's
    // intervals are its mean speed, a little above its end's while slowing).
    const float most = sqrtf(block_.exit * block_.exit + (block_.accel + block_.accel) * float(left));
    if (most < v) v = most;
    if (!(v > 0)) {
      held_ = left;
      return false;
    }
    const float need = v * v / (block_.accel + block_.accel);
    const uint32_t events = need < float(left) ? uint32_t(need) + 1 : left;
    held_ = left - events;
    runs.start(TrapezoidBlock{events, v, v, 0.0f, block_.accel}, tick_hz);
    return true;
  }

  bool stopped() const { return stopped_; }
  uint32_t held() const { return held_; }

  [[gnu::noinline]] float carried(const TrapezoidRuns& runs) const {
    if (!stopped_ || held_ || !(block_.exit > 0)) return 0.0f;
    const float slower = float(runs.exit_speed()) / block_.exit;
    return slower < 1.0f ? slower : 1.0f;
  }

  [[gnu::noinline]] float resume(TrapezoidRuns& runs, uint32_t tick_hz) {
    stopped_ = false;
    if (held_ == 0) return 1.0f;
    runs.start(TrapezoidBlock{held_, 0.0f, block_.cruise, block_.exit, block_.accel}, tick_hz);
    held_ = 0;
    return block_.exit > 0 ? float(runs.exit_speed()) / block_.exit : 1.0f;
  }

 private:
  uint32_t held_ = 0;
  bool stopped_ = false;
  TrapezoidBlock block_{};
};

}  // namespace am
