// The JSON run report of avrmotion-sim. Its keys are documented in
// docs/simulator-report.md and kept stable: tools and tests read them.
#pragma once
#include <ostream>
#include <string>

#include "machine.h"
#include "thermal_plant.h"

namespace sim {

struct PtyStats;
class PrintWatch;

// `pty` (a --pty run) adds the "pty" object: sessions, bytes each way, the
// pacing figures (docs/simulator-report.md); `plant`, the hot end attached
// to a board with a heater, the "thermal" key; `wall_seconds` >= 0, the
// host's time for the run, "wall_seconds" and "simulated_per_wall"; `print`
// (sim/print_watch.h: a board with an extruder), the "print" object.
void write_report(std::ostream& out, Machine& m, RunEnd end, const PtyStats* pty = nullptr,
                  const ThermalPlant* plant = nullptr, double wall_seconds = -1, const PrintWatch* print = nullptr);

// The report's name for how a run ended ("done", "timeout", "cpu_stopped",
// "interrupted"); the picture's title uses it too.
const char* end_name(RunEnd end);

// The run's figures as one line, for --progress: the same simulated time
// (the report's "seconds", same digits), lines sent / answered / ok / errors
// and the share of the input answered, e.g.
//   avrmotion-sim: 9.32043 s simulated, 9 of 9 lines sent, 9 answered (8 ok, 1 error), 100% of the input
// Printed after the run, it says exactly what the report says.
std::string progress_line(Machine& m);

}  // namespace sim
