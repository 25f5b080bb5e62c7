// The JSON run report of avrmotion-sim. Its keys are documented in
// docs/simulator-report.md and kept stable: tools and tests read them.
#pragma once
#include <ostream>

#include "machine.h"

namespace sim {

void write_report(std::ostream& out, Machine& m, RunEnd end);

}  // namespace sim
