// avrmotion-sim --progress: the serial script run in slices, with a line on
// standard error now and then, so a long run shows that it is alive.
#pragma once
#include <cstdint>
#include <ostream>

#include "machine.h"

namespace sim {

// Runs the serial script exactly as Machine::run_script(budget) does (the
// same instructions, the same end), in slices of 0.1 s of simulated time.
// With `out` set it prints progress_line() (report.h) there whenever
// `every_wall_s` of wall-clock time have passed since the last one (0: after
// every slice), and always once more when the run has ended: the last line
// printed carries the final figures, the ones the report gives.
RunEnd run_script_with_progress(Machine& m, uint64_t budget, std::ostream* out, double every_wall_s = 1.0);

}  // namespace sim
