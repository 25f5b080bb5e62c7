// One locked lathe pass on the m16-lathe image (or the m16-servo's: below) at a steady spindle speed,
// measured: for the timing tests (tests/sim/test_lathe_timing.cpp) and the
// benchmark's lathe rows (sim/bench_lathe.cpp).
//
// run_lathe_pass(): a fresh machine; the encoder line, then the spindle
// ramps from rest (at 0.2 s, over ramp_s) to `rpm`, turns `seconds` more and
// ramps back to rest; the G33 line is sent at rest, the status line once the
// spindle stands again. It reports the pass's
// check (lathe_check.h), the counts the model made against the firmware's
// count and lost counts (its status line), the step pulses' shortest high
// and low times, the shortest direction set-up before a step and whether
// the direction ever changed during a pulse, the step rate reached (the
// most steps in any 10 ms, per second) and the spindle vectors' longest run.
#pragma once
#include <cstdint>
#include <string>

#include "lathe_check.h"
#include "spindle_encoder.h"

namespace sim {

struct LatheRunFigures {
  bool ran = false;          // every line answered, the status line read
  PassResult pass;
  std::string status;        // the firmware's status line at the end
  int64_t model_counts = 0;  // what the encoder model produced
  int64_t firmware_counts = 0;
  int64_t firmware_lost = -1;
  double edge_rate = 0;      // the encoder's counts per second at `rpm`
  PulseTiming pulses;
  double step_rate = 0;      // steps/s, the busiest 10 ms
  uint64_t vector_max = 0;   // INT0/INT1, entry to RETI, cycles
  // A DC-servo leadscrew (m16-servo, sim/dc_servo.h) instead of a stepper:
  // its model runs, the step figures above stay empty, `pass` is not
  // checked (tests/sim/test_lathe_servo.cpp measures a servo's pass).
  bool servo = false;
  double servo_position = 0;  // motor encoder pulses, at the end
};

LatheRunFigures run_lathe_pass(const std::string& elf, const SpindleParams& spindle, double rpm, double ramp_s,
                               double seconds, const std::string& encoder_line, const std::string& g33_line,
                               const ThreadSpec& thread);

}  // namespace sim
