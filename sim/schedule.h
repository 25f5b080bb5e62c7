// The schedule the firmware computes for a direct move from rest to rest:
// the core's exact trapezoid (core/motion/trapezoid.h) run on the host,
// where its float arithmetic gives the chip's results bit for bit, one
// interval (timer ticks before the step) per step. Tests and the benchmark
// compare the step edges they see with it.
#pragma once
#include <cstdint>
#include <vector>

#include "../core/motion/trapezoid.h"

namespace sim {

// A direct move's profile as the firmware runs it (after its clamps): the
// dominant axis's rate and acceleration, from rest to rest.
struct Ramp {
  uint32_t tick_hz;
  uint32_t rate;   // steps/s
  uint32_t accel;  // steps/s^2, up and down
};

inline std::vector<uint32_t> planned_schedule(uint32_t steps, const Ramp& r) {
  am::TrapezoidRuns runs;
  if (!runs.start(am::TrapezoidBlock{steps, 0.0f, float(r.rate), 0.0f, float(r.accel)}, r.tick_hz)) return {};
  std::vector<uint32_t> out;
  for (am::StepRun s = runs.next_run(); s.count; s = runs.next_run()) out.insert(out.end(), s.count, s.interval);
  return out;
}

// The smoothing level the firmware gives a coordinated block of `events`
// dominant steps cruising at `rate` (core/motion/amass.h, chosen in
// firmware/engine/path.cpp): the largest L <= 3 with rate 2^L within a
// quarter of the board's kMaxStepRate and events 2^L <= 2^24. Written out
// here from that rule, not taken from the firmware's code.
inline uint8_t smoothing_level(uint32_t events, uint32_t rate, uint32_t max_step_rate) {
  uint8_t level = 0;
  for (uint8_t l = 1; l <= 3; ++l)
    if (uint64_t(rate) << l <= max_step_rate / 4 && uint64_t(events) << l <= (uint64_t(1) << 24)) level = l;
  return level;
}

// A coordinated direct move's events at smoothing level L: the schedule of
// steps 2^L events at rate and accel 2^L, one interval per event.
inline std::vector<uint32_t> smoothed_events(uint32_t steps, const Ramp& r, uint8_t level) {
  return planned_schedule(steps << level, Ramp{r.tick_hz, r.rate << level, r.accel << level});
}

// The dominant axis's intervals at that level: each the sum of its 2^L
// events' (the dominant steps on every 2^L-th event).
inline std::vector<uint32_t> smoothed_schedule(uint32_t steps, const Ramp& r, uint8_t level) {
  const std::vector<uint32_t> events = smoothed_events(steps, r, level);
  std::vector<uint32_t> out;
  for (size_t k = 0; (k + 1) << level <= events.size(); ++k) {
    uint32_t sum = 0;
    for (size_t e = k << level; e < (k + 1) << level; ++e) sum += events[e];
    out.push_back(sum);
  }
  return out;
}

// How far step edges stray from a schedule: stamps[first + k] against
// stamps[first] + plan[1] + ... + plan[k], for the `count` steps from
// `first`. lo..hi is the range of that lateness in cycles; its width is the
// jitter, and any drift (a lost or extra tick) widens it for good.
struct Lateness {
  int64_t lo = 0, hi = 0;
  int64_t spread() const { return hi - lo; }
};

inline Lateness lateness(const std::vector<uint64_t>& stamps, size_t first, size_t count,
                         const std::vector<uint32_t>& plan) {
  Lateness l;
  uint64_t due = stamps[first];
  for (size_t i = 1; i < count; ++i) {
    due += plan[i];
    const int64_t late = int64_t(stamps[first + i]) - int64_t(due);
    if (late < l.lo) l.lo = late;
    if (late > l.hi) l.hi = late;
  }
  return l;
}

}  // namespace sim
