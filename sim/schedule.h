// The schedule the firmware's planner computes for a one-axis move: the
// core's SpeedRamp, batched above 4 kHz exactly as firmware/apps/cnc/
// planner.cpp does, one interval (timer ticks before the step) per step.
// Tests and the benchmark compare the step edges they see with it.
#pragma once
#include <cstdint>
#include <vector>

#include "../core/motion/speed_ramp.h"

namespace sim {

inline std::vector<uint32_t> planned_schedule(uint32_t steps, const am::RampConfig& cfg) {
  am::SpeedRamp ramp;
  if (ramp.plan(steps, cfg) != am::RampError::none) return {};
  ramp.batch_below(cfg.tick_hz / 4000);
  std::vector<uint32_t> out;
  for (am::StepRun r = ramp.next_run(); r.count; r = ramp.next_run()) out.insert(out.end(), r.count, r.interval);
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
