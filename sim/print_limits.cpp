// The machine limits, measured from the image (print_limits.h).
#include "print_limits.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "board_info.h"
#include "machine.h"

namespace sim {

MachineLimits probe_limits(const std::string& elf_path, double junction_mm) {
  Machine m(elf_path);
  const am::BoardDescriptor& b = m.board();
  constexpr int kProbeMm = 40;
  m.serial().add_line("G91");
  for (uint8_t i = 0; i < b.axis_count; ++i) {
    m.serial().add_line(std::string("G1 ") + b.axes[i].name + std::to_string(kProbeMm) + " F60000");
    m.serial().add_line("M400");
  }
  if (m.run_script(uint64_t(m.f_cpu()) * 60) != RunEnd::done) throw std::runtime_error("probe_limits: the run did not end");
  MachineLimits l;
  l.junction_mm = junction_mm;
  for (uint8_t i = 0; i < b.axis_count; ++i) {
    const AxisTrace* a = m.axis(b.axes[i].name);
    const double spmm = double(b.axes[i].steps_per_m) / 1000;
    const std::vector<uint64_t>& st = a->step_cycles;
    const size_t expected = size_t(kProbeMm * spmm + 0.5);
    if (st.size() != expected || a->steps() != double(expected))
      throw std::runtime_error(std::string("probe_limits: axis ") + b.axes[i].name + " did not move its steps");
    // The cruise: the middle half of the move (a ramp is a few percent of
    // it at most, or the probe is too short for the machine: checked below).
    const size_t n = st.size(), q1 = n / 4, q3 = 3 * n / 4;
    const double f = m.f_cpu();
    const double rate = double(q3 - q1) * f / double(st[q3] - st[q1]);  // steps/s
    // The ramp from rest: s = a t^2 / 2, so sqrt(s) grows as sqrt(a / 2) t.
    // Between the steps at a quarter and at half the cruise speed.
    size_t k2 = 1;
    while (k2 + 1 < n && double(st[k2] - st[k2 - 1]) > 2 * f / rate) ++k2;
    const size_t k1 = k2 / 4;
    if (k1 < 4 || k2 * 4 > q1)
      throw std::runtime_error(std::string("probe_limits: axis ") + b.axes[i].name + " has no measurable ramp");
    const double per_s = (std::sqrt(double(k2 + 1)) - std::sqrt(double(k1 + 1))) / (double(st[k2] - st[k1]) / f);
    const double accel = 2 * per_s * per_s;  // steps/s^2
    AxisLimit limit;
    limit.name = b.axes[i].name;
    limit.steps_per_mm = spmm;
    limit.max_rate_mm_s = rate / spmm;
    limit.accel_mm_s2 = accel / spmm;
    limit.in_path = limit.name != 'E';
    l.axes.push_back(limit);
  }
  return l;
}

MachineLimits board_limits(const std::string& elf_path, double junction_mm) {
  const am::BoardDescriptor b = read_board_descriptor(elf_path);
  MachineLimits l;
  l.junction_mm = junction_mm;
  for (uint8_t i = 0; i < b.axis_count; ++i) {
    AxisLimit limit;
    limit.name = b.axes[i].name;
    limit.steps_per_mm = double(b.axes[i].steps_per_m) / 1000;
    limit.in_path = limit.name != 'E';
    l.axes.push_back(limit);
  }
  return l;
}

}  // namespace sim
