// Axis ticks for the pictures: "nice" values (1, 2 or 5 times a power of ten)
// and labels that print them exactly as written (0.2, not 0.20000000000000001).
//
// Linear axes (nice_ticks)
//   The step is the smallest 1-2-5 value for which the range, widened out to
//   whole steps ([floor(lo/step)*step, ceil(hi/step)*step]), spans at most
//   `max_intervals` steps. The ticks are every multiple of the step in the
//   widened range (widen = true: the data then sits inside labelled limits)
//   or in [lo, hi] only (widen = false: for time, which starts at 0 and ends
//   where the run ended). An empty range (lo == hi) is widened by 1 on each
//   side first, or by 10 % of |lo| when that is larger.
//
// Logarithmic axes (log_ticks)
//   Every 1, 2 and 5 times a power of ten inside [lo, hi]; when the range is
//   wider than three decades, only the powers of ten.
#pragma once
#include <string>
#include <vector>

namespace sim {

struct Ticks {
  double lo = 0, hi = 1;       // the axis limits (widened or as given)
  double step = 1;             // 1, 2 or 5 times a power of ten
  std::vector<double> values;  // the ticks, increasing, each an integer multiple of step
  int decimals = 0;            // digits after the point that label every tick exactly
};

Ticks nice_ticks(double lo, double hi, int max_intervals = 6, bool widen = true);
std::vector<double> log_ticks(double lo, double hi);

// A tick label: fixed-point with `decimals` digits, no "-0".
std::string tick_label(double value, int decimals);
// A label for a log-axis tick (1, 2, 5, 10, 0.5, 0.02, ...).
std::string log_tick_label(double value);

}  // namespace sim
