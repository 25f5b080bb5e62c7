#include "ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace sim {

namespace {

constexpr double kTolerance = 1e-9;  // in steps: a value this close to a multiple is on it
constexpr int kMantissas[] = {1, 2, 5};

// m * 10^e, computed so that decimal values come out as the nearest double
// (a division by an exact power of ten instead of a multiplication by 0.1).
double decimal(double m, int e) { return e >= 0 ? m * std::pow(10.0, e) : m / std::pow(10.0, -e); }

}  // namespace

Ticks nice_ticks(double lo, double hi, int max_intervals, bool widen) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) throw std::invalid_argument("nice_ticks: range is not finite");
  if (max_intervals < 1) max_intervals = 1;
  if (lo > hi) std::swap(lo, hi);
  if (hi - lo <= 0) {
    const double pad = std::max(1.0, 0.1 * std::fabs(lo));
    lo -= pad;
    hi += pad;
  }
  const double span = hi - lo;
  int e = int(std::floor(std::log10(span / max_intervals))) - 1;
  for (;; ++e) {
    for (const int m : kMantissas) {
      const double step = decimal(m, e);
      const double first = std::floor(lo / step + kTolerance);
      const double last = std::ceil(hi / step - kTolerance);
      if (last - first > max_intervals) continue;
      Ticks t;
      t.step = step;
      t.decimals = std::max(0, -e);
      const double k0 = widen ? first : std::ceil(lo / step - kTolerance);
      const double k1 = widen ? last : std::floor(hi / step + kTolerance);
      for (double k = k0; k <= k1; ++k) t.values.push_back(decimal(k * m, e));
      t.lo = widen ? decimal(first * m, e) : lo;
      t.hi = widen ? decimal(last * m, e) : hi;
      return t;
    }
  }
}

std::vector<double> log_ticks(double lo, double hi) {
  if (!(lo > 0) || !(hi > 0) || !std::isfinite(lo) || !std::isfinite(hi)) {
    throw std::invalid_argument("log_ticks: range must be positive and finite");
  }
  if (lo > hi) std::swap(lo, hi);
  const int e0 = int(std::floor(std::log10(lo))), e1 = int(std::ceil(std::log10(hi)));
  const bool decades_only = std::log10(hi / lo) > 3;
  std::vector<double> out;
  for (int e = e0; e <= e1; ++e) {
    for (const int m : kMantissas) {
      if (decades_only && m != 1) continue;
      const double v = decimal(m, e);
      if (v >= lo * (1 - kTolerance) && v <= hi * (1 + kTolerance)) out.push_back(v);
    }
  }
  return out;
}

std::string tick_label(double value, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", std::max(0, decimals), value);
  std::string s = buf;
  if (s[0] == '-' && s.find_first_not_of("-0.") == std::string::npos) s.erase(0, 1);
  return s;
}

std::string log_tick_label(double value) {
  if (value >= 1) return tick_label(value, 0);
  return tick_label(value, int(std::ceil(-std::log10(value) - kTolerance)));
}

}  // namespace sim
