// What an axis did, in the units a person reads: position, velocity and
// acceleration against time, and the spread of its step intervals. Everything
// is derived from the decoded step events (AxisTrace: the cycle and signed
// size of every step), nothing from the firmware's own idea of its speed.
//
// Velocity and acceleration
//   A step sequence is a train of impulses (each step moves the axis by its
//   size at its cycle). Velocity is that train with every impulse spread into
//   a Gaussian of unit area, acceleration the same train with every impulse
//   spread into the Gaussian's derivative, so the acceleration shown is
//   exactly the derivative of the velocity shown and the velocity integrates
//   to the position:
//     v(t) = sum_i d_i g_i(t - t_i),   a(t) = sum_i d_i g_i'(t - t_i).
//   Each step's width sigma_i follows the local step spacing (a variable-
//   bandwidth kernel estimate):
//     sigma_i = max(sigma_min, 1.5 * min(interval before, interval after)),
//     sigma_min = the run's length / 600 (half a pixel of a picture's
//                 300-pixel time axis),
//   capped at the run's length / 60 for an isolated step. At a steady rate r
//   Gaussians of width sigma leave a ripple of 2 exp(-2 (pi sigma r)^2) of the
//   rate (Poisson summation): 1e-19 at 1.5 intervals, so stepping shows as a
//   smooth rate even where a ramp's first steps lie tens of milliseconds
//   apart, while fast motion is smoothed by no more than sigma_min: a ramp
//   three pixels long keeps 99 % of its acceleration. The kernel is cut at
//   6 sigma_i (where it is down to 1.5e-8 of its peak, so the cut adds a
//   ripple below 1e-8 of the rate) and rescaled to unit area, so the velocity
//   still integrates to the distance moved; an axis at rest reads exactly 0
//   further than 6 sigma_i from every step.
//   A move starts and ends at a finite step rate (its first interval), so the
//   velocity jumps there: the acceleration shows a short spike at a start or
//   stop whose area is that jump.
//
// Step-interval histogram
//   Intervals between consecutive step events, in microseconds, counted in
//   logarithmic bins (10 per decade, bin edges at 10^(k/10) us), since a ramp
//   spreads them over decades. The long gaps between moves are intervals too:
//   they form the sparse bins on the right.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "axis_decoder.h"

namespace sim {

struct MotionProfile {
  double sigma_min_s = 0;   // the narrowest Gaussian, seconds (the run's length / 600)
  double sigma_max_s = 0;   // the widest one used
  std::vector<double> t;    // sample times, seconds (uniform, from 0 to the end of the run)
  std::vector<double> vel;  // mm/s (steps/s when the axis has no steps per mm)
  std::vector<double> acc;  // mm/s^2
};

// `samples` uniformly spaced points from 0 to t_end (seconds).
MotionProfile derive_motion(const AxisTrace& a, double f_cpu, double t_end, size_t samples);

// sigma_i of each step of `a` (see above), seconds.
std::vector<double> smoothing_widths(const AxisTrace& a, double f_cpu, double t_end);

// Millimetres per position unit of the trace (1 / (units_per_step * steps
// per mm)); 1 / units_per_step, i.e. full steps, when steps per mm is unknown.
double mm_per_unit(const AxisTrace& a);

struct IntervalHistogram {
  int bins_per_decade = 10;
  std::vector<double> edges_us;  // bin edges, size() == counts.size() + 1
  std::vector<uint64_t> counts;
  uint64_t intervals = 0;  // total counted (step events - 1)
  double min_us = 0, max_us = 0;
};

IntervalHistogram interval_histogram(const AxisTrace& a, double f_cpu, int bins_per_decade = 10);

}  // namespace sim
