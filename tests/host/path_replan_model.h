// The model PathPlanner's replanning is checked against
// (test_path_planner_replan.cpp): the axes and limits, the planner's own
// float lengths, a plain reverse-then-forward reference pass in double over
// limits computed here (grbl's junction formula, nominal speeds, 2 a L),
// what every block take() gives must satisfy, and the random block
// sequences.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <deque>
#include <random>
#include <vector>

#include "core/motion/path_planner.h"

namespace replantest {

// Y is fast (2 m/s, 5 m/s^2) for the single steps at speed.
const am::PathAxis kAxes[4] = {{80, 16000, 80000, true},
                               {100, 200000, 500000, true},
                               {400, 4000, 40000, true},
                               {95, 9500, 95000, false}};
constexpr float kDeviation = 0.01f;
constexpr float kEventCap = 300000;

using Ring16 = am::PathPlanner<4, 16>;

struct Input {
  int32_t steps[4];
  float mm[4];
  float feed;
  bool rapid;
};

// The planner's own float length and events per mm, as the contract defines
// them (the path axes' norm, or the others', or from steps), to check the
// hand-over x * (k_next / k) bit for bit.
inline float per_mm_float(const Input& in, uint32_t events, const am::PathAxis (&axes)[4] = kAxes) {
  bool given = false;
  for (float v : in.mm) given |= v != 0;
  float path = 0, other = 0;
  for (int i = 0; i < 4; ++i) {
    const float m = given ? in.mm[i] : float(in.steps[i]) / axes[i].steps_per_mm;
    (axes[i].in_path ? path : other) += m * m;
  }
  return float(events) / std::sqrt(path > 0 ? path : other);
}

// One block as the reference sees it, in double.
struct Ref {
  Input in;
  uint32_t events;
  double length, k;   // mm, events per mm
  double nominal;     // mm/s
  double two_al;      // (mm/s)^2, with kPlanAccel
  double max_entry;   // (mm/s)^2
  bool along;
  double unit[4];
  bool taken = false;
  float cruise = 0;        // events/s: the cruise of this block alone
  bool fixed = false;      // entry fixed: from rest, or by the previous block's take
  bool by_take = false;    // fixed by the previous block's take
  double fixed_sqr = 0;    // (mm/s)^2
};

inline Ref describe(const Input& in) {
  Ref r{};
  r.in = in;
  for (int32_t s : in.steps) r.events = std::max<uint32_t>(r.events, uint32_t(std::abs(s)));
  bool given = false;
  for (float v : in.mm) given |= v != 0;
  double mm[4], path = 0, other = 0;
  for (int i = 0; i < 4; ++i) {
    mm[i] = given ? double(in.mm[i]) : in.steps[i] / double(kAxes[i].steps_per_mm);
    (kAxes[i].in_path ? path : other) += mm[i] * mm[i];
  }
  r.along = path > 0;
  r.length = std::sqrt(r.along ? path : other);
  r.k = r.events / r.length;
  double rate = in.rapid ? 1e300 : in.feed / 60.0 * r.k, accel = 1e300;
  rate = std::min(rate, double(kEventCap));
  for (int i = 0; i < 4; ++i) {
    if (in.steps[i] == 0) continue;
    const double ratio = double(r.events) / std::abs(in.steps[i]);
    rate = std::min(rate, kAxes[i].max_rate * ratio);
    accel = std::min(accel, kAxes[i].max_accel * ratio);
  }
  r.nominal = rate / r.k;
  r.two_al = 2.0 * Ring16::kPlanAccel * (accel / r.k) * r.length;
  for (int i = 0; i < 4; ++i) r.unit[i] = r.along && kAxes[i].in_path ? mm[i] / r.length : 0;
  return r;
}

// grbl's junction speed squared between unit directions u and w, v^2 = a d
// h / (1 - h), with h = sin(theta / 2) = |w + u| / 2 and 1 - h^2 = |w - u|^2
// / 4 (so that a reversal and a straight line keep their precision):
// h / (1 - h) = h (1 + h) / (1 - h^2).
inline double grbl_sqr(const double (&u)[4], const double (&w)[4]) {
  double d = 0, s = 0;
  for (int i = 0; i < 4; ++i) {
    d += (w[i] - u[i]) * (w[i] - u[i]);
    s += (w[i] + u[i]) * (w[i] + u[i]);
  }
  if (d == 0) return 1e300;  // straight on
  double a = 1e300;
  for (int i = 0; i < 4; ++i) {
    const double j = (w[i] - u[i]) / std::sqrt(d);
    if (j != 0) a = std::min(a, kAxes[i].max_accel / kAxes[i].steps_per_mm / std::abs(j));
  }
  const double h = std::sqrt(s) / 2;
  return a * kDeviation * h * (1 + h) / (d / 4);
}

// The reference ring: the planner's blocks, in order, taken ones first.
class Reference {
 public:
  void add(const Input& in) {
    Ref r = describe(in);
    am::PathPlanner<4, 2> alone(kAxes, kDeviation, kEventCap);
    alone.add(in.steps, in.mm, in.feed, in.rapid);
    r.cruise = alone.take()->cruise;
    const bool from_rest = first_open() == ring_.size();
    if (from_rest) {
      r.fixed = true;
      r.max_entry = 0;
    } else {
      const Ref& prev = ring_.back();
      const double cap = std::min(prev.nominal, r.nominal);
      r.max_entry = prev.along && r.along ? std::min(cap * cap, grbl_sqr(prev.unit, r.unit)) : 0;
    }
    ring_.push_back(r);
  }
  // The planner took the first open block with this exit (events/s).
  void take(double exit) {
    const size_t i = first_open();
    ring_[i].taken = true;
    if (i + 1 < ring_.size()) {
      ring_[i + 1].fixed = ring_[i + 1].by_take = true;
      const double v = exit / ring_[i].k;
      ring_[i + 1].fixed_sqr = v * v;
    }
  }
  void done() { ring_.pop_front(); }
  size_t first_open() const {
    size_t i = 0;
    while (i < ring_.size() && ring_[i].taken) ++i;
    return i;
  }
  const Ref& at(size_t i) const { return ring_[i]; }
  size_t size() const { return ring_.size(); }

  // Entries (mm/s)^2 of the open blocks from first_open(), and a 0 for the end.
  std::vector<double> plan() const {
    const size_t first = first_open(), n = ring_.size() - first;
    std::vector<double> e(n + 1, 0.0);
    for (size_t j = n; j-- > 1;) e[j] = std::min(ring_[first + j].max_entry, e[j + 1] + ring_[first + j].two_al);
    if (n) e[0] = ring_[first].fixed_sqr;
    for (size_t j = 0; j + 1 < n; ++j) e[j + 1] = std::min(e[j + 1], e[j] + ring_[first + j].two_al);
    return e;
  }

 private:
  std::deque<Ref> ring_;
};

// What every block take() gives must satisfy.
inline void expect_feasible(const am::PathBlock<4>& b) {
  const float ramp = 2.0f * b.accel * float(b.events);
  ASSERT_LE(b.entry * b.entry, b.exit * b.exit + ramp);
  ASSERT_LE(b.exit * b.exit, b.entry * b.entry + ramp);
  ASSERT_LE(std::max(b.entry, b.exit), b.cruise);
  ASSERT_GE(b.exit, 0.0f);
}

// The hand-over from block a (exit) to block b (entry): bit for bit, and the
// same path speed.
inline void expect_hand_over(const am::PathBlock<4>& a, const Input& ain, const am::PathBlock<4>& b,
                             const Input& bin, const Ref& ra, const Ref& rb) {
  const float to_next = per_mm_float(bin, b.events) / per_mm_float(ain, a.events);
  ASSERT_EQ(b.entry, a.exit * to_next);
  ASSERT_NEAR(b.entry / rb.k, a.exit / ra.k, 1e-6 * a.exit / ra.k + 1e-9);
}

class Sequence {
 public:
  // spiky: blocks along Y of 100 .. 600 mm (rapids, or feeds of 1 .. 2
  // m/s) with 1 .. 3 steps between them and a reversal now and then: such a
  // step in a chain that slows down from 1 m/s sheds less than the float
  // rounding of its speed squared.
  explicit Sequence(uint32_t seed, bool spiky = false) : rng_(seed), spiky_(spiky) {}

  Input next() {
    if (spiky_) return spike();
    Input in{};
    const double r = u(0, 1);
    if (r < 0.15) {
    } else if (r < 0.22) {
      for (double& d : dir_) d = -d;
    } else if (r < 0.6) {
      for (double& d : dir_) d += 0.2 * u(-0.5, 0.5);
    } else {
      for (double& d : dir_) d = u(-0.5, 0.5);
      dir_[2] *= 0.3;
    }
    const double n = std::sqrt(dir_[0] * dir_[0] + dir_[1] * dir_[1] + dir_[2] * dir_[2]);
    for (double& d : dir_) d /= n;
    const double mm = std::exp(u(std::log(0.01), std::log(50.0)));
    double delta[4] = {dir_[0] * mm, dir_[1] * mm, dir_[2] * mm, 0};
    const double kind = u(0, 1);
    if (kind < 0.05) {
      delta[0] = delta[1] = delta[2] = 0;  // retract or prime
      delta[3] = u(-3, 3);
    } else if (kind < 0.35) {
      delta[3] = 0.05 * mm;  // extrusion along the path
    }
    for (int i = 0; i < 4; ++i) {
      const int64_t to = std::llround((pos_[i] + delta[i]) * kAxes[i].steps_per_mm);
      in.steps[i] = int32_t(to - std::llround(pos_[i] * kAxes[i].steps_per_mm));
      pos_[i] += delta[i];
      in.mm[i] = float(delta[i]);
    }
    if (u(0, 1) < 0.03) std::fill(in.mm, in.mm + 4, 0.0f);  // steps only
    in.rapid = u(0, 1) < 0.1;
    in.feed = in.rapid ? 0.0f : float(std::exp(u(std::log(30.0), std::log(30000.0))));
    return in;
  }
  double u(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }

 private:
  Input spike() {
    Input in{};
    if (u(0, 1) < 0.15) sign_ = -sign_;
    const bool single = ++count_ % 2;
    in.steps[1] = sign_ * int32_t(single ? u(1, 4) : u(10000, 60000));
    in.mm[1] = in.steps[1] / 100.0f;
    in.rapid = single || u(0, 1) < 0.5;
    in.feed = float(u(60000, 120000));  // 1 .. 2 m/s: the single step before it ends at its nominal
    return in;
  }

  std::mt19937 rng_;
  bool spiky_;
  int32_t sign_ = 1;
  int count_ = 0;
  double dir_[3] = {1, 0, 0};
  double pos_[4] = {0, 0, 0, 0};
};

inline bool moves(const Input& in) {
  for (int32_t s : in.steps) {
    if (s) return true;
  }
  return false;
}


}  // namespace replantest
