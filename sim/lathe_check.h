// What a lathe pass should have cut, computed independently of the firmware,
// and the pass the simulated board did cut, from its pins: for the lathe
// tests (tests/sim/test_lathe_*.cpp) and the benchmark (sim/bench_lathe.cpp).
//
// ThreadSpec: the thread in the test's own integers. The carriage's target
// after s spindle counts from the index is
//     floor( sigma lead (s - k C / n) / C x S / L )
// with lead = pitch x n starts, k the start, C counts per spindle turn, S
// leadscrew steps per turn, L the leadscrew's pitch, sigma = -1 for a
// right-hand thread (the m16-lathe: positive steps move away from the chuck),
// evaluated exactly in 128-bit integers.
// check_pass(): finds the pass's index count (the first count after `armed`
// that reads the index high after one that read it low), then walks every
// spindle count after it: the carriage position just before the next count
// (from the step pin's decoded trace) against base + target(s). The pass is
// locked from the first count from which every later one matches, up to the
// end of the pass (the position reaching `end`, when given: the target is
// clamped there, or `until`).
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "axis_decoder.h"
#include "machine.h"
#include "spindle_encoder.h"

namespace sim {

struct ThreadSpec {
  int64_t pitch_num, pitch_den;  // um = num / den
  int starts = 1, start = 0;
  bool right_hand = true;
  int64_t counts_per_turn = 0;
  int64_t steps_per_turn = 800;
  int64_t screw_num = 25400, screw_den = 8;  // the leadscrew's pitch, um: 3.175 mm
};

int64_t target_steps(const ThreadSpec& t, int64_t s);

struct PassResult {
  bool index_found = false;
  uint64_t index_cycle = 0;
  size_t counts = 0;             // spindle counts after the index, to the pass's end
  int64_t s_end = 0;             // the net count there
  bool locked = false;
  size_t locked_after = 0;       // counts from the index to the lock
  uint64_t lock_cycles = 0;      // from the index to the lock
  size_t mismatches = 0;         // counts after the lock whose position is off
  int64_t position = 0, expected = 0;  // at the pass's end
  uint64_t max_latency = 0;      // locked counts that step: the count's edge to the step's rise, cycles
  size_t latency_samples = 0;
};

PassResult check_pass(const SpindleEncoder& spindle, const AxisTrace& axis, const std::vector<PinEdge>& step_pin,
                      const ThreadSpec& t, int64_t base, uint64_t armed, uint64_t until, const int64_t* end = nullptr);

// A step/dir driver's timing on the pins: the shortest high time of a step
// pulse, the shortest low time between two, the shortest time from a
// direction change to the next rise, whether the direction ever changed
// while the step line was high (all cycles; 0: none seen).
struct PulseTiming {
  uint64_t min_high = 0, min_low = 0, min_dir_setup = 0;
  size_t pulses = 0, dir_changes = 0;
  bool dir_changed_in_pulse = false;
};
PulseTiming pulse_timing(const std::vector<PinEdge>& step, const std::vector<PinEdge>& dir);


}  // namespace sim
