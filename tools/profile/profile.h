// Host-only speed-profile and stall analysis behind avrmotion-profile.
//
// Contract
//   parse_args() turns the command line into Options or an error message.
//   plan_intervals() runs the firmware's own ramp code (core/motion/speed_ramp.h or
//   core/motion/speed_ramp_exact.h) and returns the tick interval of every step.
//   Motor models the torque-speed method of seed-000 section 3.3: with the
//   motor's pull-out torque T(f) (piecewise linear in steps/s), load torque
//   T_L and inertia J, the fastest speed change is
//     df/dt = [T(f) - T_L] n p / (2 pi J)   accelerating
//     df/dt = [T(f) + T_L] n p / (2 pi J)   braking (the load helps)
//   with n p the full steps per revolution. check_ramp() compares each step's
//   speed change with that and reports the first step the motor cannot follow.
//   Floating point and the standard library are fine here: none of this runs
//   on the AVR.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/motion/speed_ramp.h"
#include "core/motion/speed_ramp_exact.h"

namespace am::profile {

struct TorquePoint {
  double rate;    // steps/s
  double torque;  // N m
};

class Motor {
 public:
  // Points sorted by rate; two points at the same rate make a step in the curve.
  Motor(std::vector<TorquePoint> curve, double load_nm, double inertia_kgm2, double steps_per_rev)
      : curve_(std::move(curve)), load_(load_nm), inertia_(inertia_kgm2), spr_(steps_per_rev) {}

  // Pull-out torque at rate f; 0 beyond the last point.
  double torque(double f) const {
    if (curve_.empty() || f > curve_.back().rate) return 0;
    if (f <= curve_.front().rate) return curve_.front().torque;
    for (size_t i = 1; i < curve_.size(); ++i) {
      const TorquePoint& lo = curve_[i - 1];
      const TorquePoint& hi = curve_[i];
      if (f <= hi.rate && hi.rate > lo.rate)
        return lo.torque + (hi.torque - lo.torque) * (f - lo.rate) / (hi.rate - lo.rate);
    }
    return curve_.back().torque;
  }

  double max_accel(double f) const { return (torque(f) - load_) * spr_ / (2 * M_PI * inertia_); }
  double max_decel(double f) const { return (torque(f) + load_) * spr_ / (2 * M_PI * inertia_); }

  // Highest rate at which the motor still carries the load (T(f) >= T_L).
  double pull_out_rate() const {
    double best = 0;
    for (size_t i = 0; i < curve_.size(); ++i) {
      const TorquePoint& p = curve_[i];
      if (p.torque >= load_) best = p.rate;
      if (i + 1 == curve_.size()) break;
      const TorquePoint& q = curve_[i + 1];
      if (p.torque >= load_ && q.torque < load_ && q.rate > p.rate)
        return p.rate + (q.rate - p.rate) * (p.torque - load_) / (p.torque - q.torque);
    }
    return best;
  }

  // Shortest time from rest to `rate` at full torque: integral of df / (df/dt).
  // Infinite if the motor cannot accelerate somewhere below `rate`.
  double time_to_reach(double rate) const {
    constexpr int slices = 100000;
    const double df = rate / slices;
    double t = 0;
    for (int i = 0; i < slices; ++i) {
      const double accel = max_accel((i + 0.5) * df);
      if (accel <= 0) return INFINITY;
      t += df / accel;
    }
    return t;
  }

 private:
  std::vector<TorquePoint> curve_;
  double load_, inertia_, spr_;
};

struct StallReport {
  bool follows = true;
  uint32_t step = 0;     // 1-based step the motor cannot follow
  double rate = 0;       // steps/s there
  double required = 0;   // steps/s^2 the ramp asks for (negative: braking)
  double available = 0;  // steps/s^2 the motor can give there
};

// The acceleration the ramp asks for at step k: mean speeds over two adjacent
// windows of W steps ending at k (W = min(8, (k+1)/2), at least 1), divided by
// the time between the windows' centres; before the first step the motor is
// at rest at time 0. Windows keep tick rounding (1 tick on a sum of W
// intervals) from looking like acceleration at high step rates.
inline StallReport check_ramp(const std::vector<uint32_t>& intervals, double tick_hz, const Motor& motor) {
  std::vector<double> end(intervals.size() + 1, 0.0);  // end[k + 1] = end of step k, ticks
  for (size_t k = 0; k < intervals.size(); ++k) end[k + 1] = end[k] + intervals[k];
  for (size_t k = 0; k < intervals.size(); ++k) {
    const size_t w = std::max<size_t>(1, std::min<size_t>(8, (k + 1) / 2));
    const double a_from = end[k + 1 - w], a_to = end[k + 1];
    const double rate = w * tick_hz / (a_to - a_from);
    double prev_rate = 0, prev_centre = 0;
    if (k + 1 >= 2 * w) {
      const double b_from = end[k + 1 - 2 * w];
      prev_rate = w * tick_hz / (a_from - b_from);
      prev_centre = (a_from + b_from) / 2;
    }
    const double accel = (rate - prev_rate) * tick_hz / ((a_from + a_to) / 2 - prev_centre);
    const double fastest = std::max(rate, prev_rate);
    const double available = accel >= 0 ? motor.max_accel(fastest) : -motor.max_decel(fastest);
    const bool ok = accel >= 0 ? (accel <= available && available >= 0) : accel >= available;
    if (!ok) return StallReport{false, uint32_t(k + 1), rate, accel, available};
  }
  return StallReport{};
}

enum class Method { seed, exact };

struct Options {
  uint32_t steps = 0, speed = 0, accel = 0, decel = 0;  // decel 0 = same as accel
  uint32_t steps_per_rev = 200, tick_hz = 1000000, every = 1;
  Method method = Method::exact;
  std::vector<TorquePoint> torque;  // empty: no stall check
  double load = 0, inertia = 0;
};

inline const char* usage() {
  return "usage: avrmotion-profile --steps N --speed STEPS_PER_S --accel STEPS_PER_S2\n"
         "         [--decel STEPS_PER_S2] [--method seed|exact] [--tick-hz HZ]\n"
         "         [--spr STEPS_PER_REV] [--every N]\n"
         "         [--torque RATE:NM,RATE:NM,... --inertia KG_M2 [--load NM]]\n"
         "Prints step, end time (s), delay (us), rpm and steps/s of every step (or\n"
         "every Nth) of the move. With a torque-speed curve (pull-out torque in N m\n"
         "at step rates, piecewise linear, 0 beyond the last point) it also says\n"
         "whether the motor can follow the ramp and where it would stall.\n";
}

namespace detail {
inline bool positive_u32(const std::string& text, uint32_t& out) {
  char* end = nullptr;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || text[0] == '-' || v == 0 || v > 0xFFFFFFFFull) return false;
  out = uint32_t(v);
  return true;
}
inline bool number(const std::string& text, double& out) {
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return !text.empty() && *end == '\0' && std::isfinite(out);
}
inline bool torque_curve(const std::string& text, std::vector<TorquePoint>& out) {
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const size_t colon = item.find(':');
    TorquePoint p{};
    if (colon == std::string::npos || !number(item.substr(0, colon), p.rate) ||
        !number(item.substr(colon + 1), p.torque) || p.rate < 0 || p.torque < 0)
      return false;
    if (!out.empty() && p.rate < out.back().rate) return false;
    out.push_back(p);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return !out.empty();
}
}  // namespace detail

// Returns an empty string on success, else the error to print.
inline std::string parse_args(const std::vector<std::string>& args, Options& o) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& flag = args[i];
    if (i + 1 >= args.size()) return flag + " needs a value";
    const std::string& value = args[++i];
    bool ok = true;
    if (flag == "--steps") ok = detail::positive_u32(value, o.steps);
    else if (flag == "--speed") ok = detail::positive_u32(value, o.speed);
    else if (flag == "--accel") ok = detail::positive_u32(value, o.accel);
    else if (flag == "--decel") ok = detail::positive_u32(value, o.decel);
    else if (flag == "--spr") ok = detail::positive_u32(value, o.steps_per_rev);
    else if (flag == "--tick-hz") ok = detail::positive_u32(value, o.tick_hz);
    else if (flag == "--every") ok = detail::positive_u32(value, o.every);
    else if (flag == "--method") {
      ok = value == "seed" || value == "exact";
      o.method = value == "seed" ? Method::seed : Method::exact;
    } else if (flag == "--torque") ok = detail::torque_curve(value, o.torque);
    else if (flag == "--load") ok = detail::number(value, o.load) && o.load >= 0;
    else if (flag == "--inertia") ok = detail::number(value, o.inertia) && o.inertia > 0;
    else return "unknown option " + flag;
    if (!ok) return "bad value for " + flag + ": '" + value + "' (" +
                    (flag == "--torque"   ? "expected RATE:NM pairs, rates ascending"
                     : flag == "--method" ? "expected seed or exact"
                     : flag == "--load" || flag == "--inertia" ? "expected a number >= 0 (inertia > 0)"
                                          : "expected a whole number >= 1") + ")";
  }
  if (o.steps == 0) return "--steps is required (>= 1)";
  if (o.speed == 0) return "--speed is required (>= 1 steps/s)";
  if (o.accel == 0) return "--accel is required (>= 1 steps/s^2)";
  if (o.decel == 0) o.decel = o.accel;
  if (!o.torque.empty() && o.inertia <= 0) return "--torque needs --inertia (kg m^2, > 0)";
  return "";
}

inline const char* ramp_error_text(RampError e) {
  switch (e) {
    case RampError::none: return "none";
    case RampError::zero_speed: return "speed must be >= 1 steps/s";
    case RampError::zero_accel: return "accel and decel must be >= 1 steps/s^2";
    case RampError::rate_above_tick: return "speed above the timer frequency";
    case RampError::out_of_range: return "outside the exact method's limits (see docs/ramps.md)";
  }
  return "unknown";
}

// Intervals of every step from the firmware's ramp code; empty + error on failure.
inline std::vector<uint32_t> plan_intervals(const Options& o, std::string& error) {
  const RampConfig cfg{o.tick_hz, o.speed, o.accel, o.decel};
  std::vector<uint32_t> out;
  RampError err;
  if (o.method == Method::seed) {
    SpeedRamp ramp;
    err = ramp.plan(o.steps, cfg);
    while (err == RampError::none && !ramp.finished()) out.push_back(ramp.next());
  } else {
    ExactRamp ramp;
    err = ramp.plan(o.steps, cfg);
    while (err == RampError::none && !ramp.finished()) out.push_back(ramp.next());
  }
  if (err != RampError::none) error = ramp_error_text(err);
  return out;
}

}  // namespace am::profile
