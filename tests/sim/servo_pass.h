// The thread pass the m16-servo tests measure (test_lathe_servo.cpp,
// test_lathe_servo_image.cpp): the documented bounds, the spindle's
// continuous angle from its model, and a pass's carriage against the helix
// the test computes itself (never from the firmware).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "lathe_rig.h"
#include "plot_lathe.h"

namespace servotest {

using simtest::ServoRig;

// 1.00 mm on the seed's machine: 780 counts x 1 mm / 3.175 mm per 40
// spindle counts = 780/127 motor counts per spindle count.
constexpr double kLambda = 780.0 / 127.0;
constexpr int kSigma = -1;  // a right-hand thread towards the chuck: -Z

// The documented bounds (docs/lathe.md, "The m16-servo image").
constexpr double kFollowBound = 6;    // counts (24.4 um) of carriage, either way, every sample of a pass
constexpr double kPhaseBound = 6;     // counts, the second pass against the first's helix
constexpr double kReentryBound = 2;   // counts, the second pass at its index (the retract's slip)
constexpr double kStopLeadBound = kFollowBound + kLambda;  // counts (49.4 um) ahead, a spindle slowing to rest mid-pass
constexpr double kOffModelBound = 8;  // counts (32.6 um): a motor whose gain or time constant is off the model's
constexpr double kRunningStartBound = 10;  // counts (40.7 um): a pass armed while the spindle turns at 300 rpm
// Cycles from the switch to ENABLE low for good: the switch is read every
// PWM period (1024 cycles) at its BOTTOM, behind at most one other vector
// (INT1 343, INT0 268, the UART 172 cycles at most, as the test prints
// them), plus the overflow vector's own entry; the test closes it at the
// worst moment, just after a BOTTOM.
constexpr uint64_t kLimitBound = 1600;

// The spindle's continuous angle in encoder phases (two per line, single
// channel) at increasing times: the model's rpm profile integrated (it is
// linear between its points: the trapezoid rule on 10 us steps is exact but
// for the steps that hold a point), from the model's start, mid-phase 0 at
// t = 0 (sim/spindle_encoder.h); a transition is the angle crossing a whole
// phase, so this agrees with the model's log and is right between
// transitions too, and at rest.
class SpindleAngle {
 public:
  explicit SpindleAngle(const sim::SpindleEncoder& sp) : sp_(sp) {}
  double at(uint64_t cycle, double f_cpu) {
    const double t = double(cycle) / f_cpu;
    constexpr double kStep = 1e-5;
    while (t_ < t) {
      const double dt = std::min(kStep, t - t_);
      angle_ += 0.5 * (sp_.rpm_at(t_) + sp_.rpm_at(t_ + dt)) / 60 * sp_.phases_per_turn() * dt;
      t_ += dt;
    }
    return angle_;
  }

 private:
  const sim::SpindleEncoder& sp_;
  double t_ = 0, angle_ = 0.5;
};

struct PassFigures {
  bool index_found = false;
  uint64_t index_cycle = 0;
  int64_t index_phase = 0;
  uint64_t end_cycle = 0;        // the count whose target reached the end (0: none)
  size_t samples = 0;
  double max_lag = 0, max_lead = 0;  // carriage behind / ahead of the helix, counts
  double at_index = 0;           // the carriage against the helix at the index (lag, counts)
  double worst = 0;              // max(|lag|, |lead|)
  std::vector<sim::LathePlotPoint> plot;  // every servo log entry from the index to the end
};

constexpr double kMmPerCount = 3.175 / 780;

// The pass after `armed` on the helix base + sigma lambda s: its index (as
// the firmware finds it), its end (the first count whose target
// floor(sigma lambda s) reaches `end`), and the carriage against the helix
// every servo log entry between the two (or up to `until`).
// `rig`: a ServoRig, or any rig with the same spindle, servo and machine
// (the m32-servo-panel's, test_lathe_servo_panel.cpp).
template <class Rig>
PassFigures measure(const Rig& rig, uint64_t armed, double base, int64_t end, uint64_t until, int sigma = kSigma) {
  PassFigures f;
  bool was_high = true;
  for (const auto& t : rig.spindle->log()) {
    if (t.cycle <= armed || !t.count) continue;
    if (!f.index_found) {
      if (t.index && !was_high) {
        f.index_found = true;
        f.index_cycle = t.cycle;
        f.index_phase = t.phase;
      }
      was_high = t.index;
      continue;
    }
    const int64_t s = (t.phase - f.index_phase) / 2;
    const double target = std::floor(sigma * kLambda * double(s));
    if ((sigma < 0 ? target <= double(end) : target >= double(end)) && t.cycle < until) {
      f.end_cycle = t.cycle;
      break;
    }
  }
  if (!f.index_found) return f;
  const uint64_t last = f.end_cycle ? f.end_cycle : until;
  bool first = true;
  SpindleAngle angle(*rig.spindle);
  for (const auto& e : rig.servo->log()) {
    if (e.cycle < f.index_cycle || e.cycle > last) continue;
    const double s = (angle.at(e.cycle, rig.m->f_cpu()) - double(f.index_phase)) / 2;
    const double helix = base + sigma * kLambda * s;
    const double lag = sigma * (helix - e.position);
    f.plot.push_back({double(e.cycle) / rig.m->f_cpu(), helix * kMmPerCount, e.position * kMmPerCount,
                      lag * kMmPerCount * 1000});
    if (first) f.at_index = lag;
    first = false;
    f.max_lag = std::max(f.max_lag, lag);
    f.max_lead = std::max(f.max_lead, -lag);
    ++f.samples;
  }
  f.worst = std::max(f.max_lag, f.max_lead);
  return f;
}

// The spindle for two passes: from rest to 300 rpm over 1 s, `hold` s at
// speed, back to rest over 1 s (5 hold + 5 turns), from t0 and again from t1.
inline sim::SpindleParams two_runs(double t0, double t1, double hold = 2) {
  sim::SpindleParams p;
  p.lines = 40;
  p.profile = {{t0, 0}, {t0 + 1, 300}, {t0 + 1 + hold, 300}, {t0 + 2 + hold, 0},
               {t1, 0}, {t1 + 1, 300}, {t1 + 1 + hold, 300}, {t1 + 2 + hold, 0}};
  return p;
}

}  // namespace servotest
