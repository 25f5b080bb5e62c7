// What the step engine's invariant sweeps share (test_invariants.cpp,
// test_invariants_coordinated.cpp): the rate, acceleration and distance
// grids, the deterministic sampler, the core's schedule of a move, the
// lines the firmware answers a clamp or a refusal with, POS's values, and
// the software pulses' jitter bound.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "schedule.h"

namespace invtest {

// A clamp the firmware says before a move runs: `[MSG:F clamped to 20000]`
// (grbl's style) or `echo:F clamped to 20000` (Marlin's, the m1284's).
inline bool is_clamp(const std::string& l) {
  return (l.rfind("[MSG:", 0) == 0 || l.rfind("echo:", 0) == 0) && l.find(" clamped to ") == 6;
}

// A refused line's two lines at `at`: its reason and grbl's `error:N`, or
// Marlin's unknown-command echo and `ok`.
inline bool refused(const std::vector<std::string>& got, size_t& at) {
  const bool grbl = got.at(at).rfind("[MSG:", 0) == 0 && got.at(at + 1).rfind("error:", 0) == 0;
  const bool marlin = got.at(at).rfind("echo:Unknown command:", 0) == 0 && got.at(at + 1) == "ok";
  at += 2;
  return grbl || marlin;
}


constexpr uint32_t kRates[] = {50, 400, 4000, 20000, 40000, 100000, 160000, 250000};
constexpr uint32_t kAccels[] = {4, 800, 20000, 400000, 4000000, 20000000, 1000000000, 2147483647};
constexpr int32_t kSteps[] = {1, 2, 3, 7, 18, 100, 1000, 4000};

inline uint64_t next_random(uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return state >> 33;
}

inline std::vector<uint32_t> schedule(uint32_t steps, const sim::Ramp& cfg) {
  const std::vector<uint32_t> out = sim::planned_schedule(steps, cfg);
  EXPECT_EQ(out.size(), steps);
  return out;
}

inline double seconds(const std::vector<uint32_t>& iv, uint32_t f_cpu) {
  double t = 0;
  for (uint32_t i : iv) t += i;
  return t / f_cpu;
}

// "pos X:1 Y:-2.5 ..." -> the value of `axis`, in full steps.
inline double reported(const std::string& pos, char axis) {
  const std::string key = std::string(" ") + axis + ":";
  const size_t at = pos.find(key);
  EXPECT_NE(at, std::string::npos) << pos;
  return at == std::string::npos ? 0 : std::atof(pos.c_str() + at + key.size());
}


// Software pulses trail their match by the latency of the step interrupt:
// 6 cycles of spread on a quiet line (test_step_timing.cpp), up to about 30
// with the UART receiving and answering during the motion (the UART
// handlers' prologues, before they re-enable interrupts).
constexpr int64_t kSoftwareJitter = 48;  // docs/step-engine.md

}  // namespace invtest
