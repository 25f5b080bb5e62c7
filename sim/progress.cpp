#include "progress.h"

#include <algorithm>
#include <chrono>

#include "report.h"

namespace sim {

RunEnd run_script_with_progress(Machine& m, uint64_t budget, std::ostream* out, double every_wall_s) {
  using clock = std::chrono::steady_clock;
  const uint64_t end = m.cycles() + budget;
  const uint64_t slice = std::max<uint64_t>(1, m.f_cpu() / 10);
  auto last = clock::now();
  RunEnd result = RunEnd::budget_spent;
  for (;;) {
    // run() checks the stop condition before the budget, as one long call
    // would: slicing changes nothing but where the loop pauses.
    const uint64_t now = m.cycles();
    const uint64_t chunk = now >= end ? 0 : std::min(slice, end - now);
    result = m.run_script(chunk);
    if (result != RunEnd::budget_spent || m.cycles() >= end) break;
    if (out && std::chrono::duration<double>(clock::now() - last).count() >= every_wall_s) {
      *out << progress_line(m) << std::endl;
      last = clock::now();
    }
  }
  if (out) *out << progress_line(m) << std::endl;
  return result;
}

}  // namespace sim
