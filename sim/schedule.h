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

}  // namespace sim
