#include "motion.h"

#include <algorithm>
#include <cmath>

namespace sim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCut = 6;  // kernel support, in sigmas: there g is 1.5e-8 of its peak
// The cut Gaussian's area, so that each step still adds exactly its size to
// the integral of the velocity: erf(6 / sqrt 2).
const double kCutArea = std::erf(kCut / std::sqrt(2.0));

}  // namespace

double mm_per_unit(const AxisTrace& a) {
  const double units = a.units_per_step > 0 ? a.units_per_step : 1;
  return a.steps_per_mm > 0 ? 1 / (units * a.steps_per_mm) : 1 / units;
}

std::vector<double> smoothing_widths(const AxisTrace& a, double f_cpu, double t_end) {
  const double lo = std::max(t_end, 1e-6) / 600, hi = std::max(t_end, 1e-6) / 60;
  const size_t n = a.step_cycles.size();
  std::vector<double> out(n, lo);
  for (size_t i = 0; i < n; ++i) {
    double gap = 0;  // the shorter neighbouring interval; 0 for a lone step
    if (i > 0) gap = double(a.step_cycles[i] - a.step_cycles[i - 1]) / f_cpu;
    if (i + 1 < n) {
      const double next = double(a.step_cycles[i + 1] - a.step_cycles[i]) / f_cpu;
      gap = i > 0 ? std::min(gap, next) : next;
    }
    out[i] = std::min(std::max(lo, 1.5 * gap), std::max(lo, hi));
  }
  return out;
}

MotionProfile derive_motion(const AxisTrace& a, double f_cpu, double t_end, size_t samples) {
  MotionProfile p;
  if (samples < 2) samples = 2;
  if (!(t_end > 0)) t_end = 1e-6;
  const std::vector<double> widths = smoothing_widths(a, f_cpu, t_end);
  p.sigma_min_s = t_end / 600;
  p.sigma_max_s = widths.empty() ? p.sigma_min_s : *std::max_element(widths.begin(), widths.end());
  p.t.resize(samples);
  p.vel.assign(samples, 0);
  p.acc.assign(samples, 0);
  const double dt = t_end / double(samples - 1);
  for (size_t k = 0; k < samples; ++k) p.t[k] = dt * double(k);

  const double scale = mm_per_unit(a);
  for (size_t i = 0; i < a.step_cycles.size(); ++i) {
    const double s = widths[i], norm = 1 / (s * std::sqrt(2 * kPi) * kCutArea);
    const double ti = double(a.step_cycles[i]) / f_cpu, d = a.step_deltas[i] * scale;
    const long k0 = std::max(0L, long(std::ceil((ti - kCut * s) / dt)));
    const long k1 = std::min(long(samples) - 1, long(std::floor((ti + kCut * s) / dt)));
    for (long k = k0; k <= k1; ++k) {
      const double u = (p.t[size_t(k)] - ti) / s;
      const double g = norm * std::exp(-0.5 * u * u);
      p.vel[size_t(k)] += d * g;
      p.acc[size_t(k)] -= d * g * u / s;  // d/dt of g(t - ti)
    }
  }
  return p;
}

IntervalHistogram interval_histogram(const AxisTrace& a, double f_cpu, int bins_per_decade) {
  IntervalHistogram h;
  h.bins_per_decade = bins_per_decade > 0 ? bins_per_decade : 10;
  const size_t n = a.step_cycles.size();
  if (n < 2) return h;
  std::vector<double> us(n - 1);
  for (size_t i = 1; i < n; ++i) us[i - 1] = double(a.step_cycles[i] - a.step_cycles[i - 1]) * 1e6 / f_cpu;
  h.intervals = us.size();
  h.min_us = *std::min_element(us.begin(), us.end());
  h.max_us = *std::max_element(us.begin(), us.end());
  const double b = h.bins_per_decade;
  // Bin j covers [10^(j/b), 10^((j+1)/b)); an interval of 0 cycles (two
  // events in one cycle) goes to the lowest bin.
  const auto bin = [b](double v) { return int(std::floor(std::log10(std::max(v, 1e-3)) * b + 1e-9)); };
  const int j0 = bin(h.min_us), j1 = bin(h.max_us);
  h.counts.assign(size_t(j1 - j0 + 1), 0);
  for (int j = j0; j <= j1 + 1; ++j) h.edges_us.push_back(std::pow(10.0, j / b));
  for (const double v : us) ++h.counts[size_t(bin(v) - j0)];
  return h;
}

}  // namespace sim
