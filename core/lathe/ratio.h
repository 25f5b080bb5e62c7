// Gear ratio of an electronic leadscrew, exact in integers.
//
// Contract
//   lambda = leadscrew counts per spindle count
//          = (lead / leadscrew pitch) x
//            (leadscrew counts per turn / spindle counts per turn)
//   with lead = thread (or feed) pitch x starts. gear_ratio() returns lambda
//   reduced (exact_num / exact_den, below 2^64) and the Ratio the Follower runs:
//   the same fraction when it fits the follower (num < 2^32 and den within
//   the limit below: status exact, error_pm 0), else the nearest fraction that
//   fits (best_rational: status approximated) and error_pm, the lead it cuts
//   minus the lead requested, in picometres per spindle turn, truncated toward
//   zero and saturated to the int32 range (the seed's LCD showed this figure
//   in um). out_of_range: a zero input, a reduced N or D above 64 bits, lambda
//   >= 2^32, or the nearest fraction is 0. gear_ratio_exact() is the same
//   without the fallback: where gear_ratio() approximates, it says
//   out_of_range.
//
// Exact inputs
//   Pitches are rationals in micrometres: a metric pitch is an integer number
//   of um (pitch_um(1500)), an inch pitch is 25400 / TPI um (1 in = 25.4 mm
//   exactly), half TPI included (pitch_tpi_x2(9) = 4.5 TPI), so 13 TPI or
//   11.5 TPI are exact, not rounded to 0.01 mm. Leadscrew counts per turn are
//   rational too: steps x microsteps x screw teeth / motor teeth (a 30:40 belt
//   is not an integer), or encoder pulses x gearbox ratio. The spindle has an
//   integer count per turn (encoder on the spindle, index once a turn).
//
// Hand: left hand (or a leadscrew that turns the other way: Machine) sets
// `reversed`, the Follower's sign; the ratio itself is unsigned, so no table
// is duplicated per hand.
//
// Denominator limit: kMaxDen / m, m = starts / gcd(starts, spindle counts),
// so that every start's phase offset of a multi-start thread can be held
// exactly by the Follower's finer unit (follower.h). The caller may pass a
// smaller limit (the seed's B(n) list was capped at 150 nodes).
//
// Arithmetic: the eight 32-bit factors are cancelled pairwise by gcd, which
// leaves the product reduced, then multiplied exactly in 128 bits (wide.h);
// the reduced N and D must fit 64 bits (else out_of_range). The error uses
// e = p D - q N from the continued fraction:
// error = lead (lambda' / lambda - 1) = lead e / (q N).
#pragma once
#include <stdint.h>

#include "follower.h"
#include "rational.h"
#include "wide.h"

namespace am {

struct Pitch {
  uint32_t num;  // micrometres = num / den
  uint32_t den;
};

constexpr Pitch pitch_um(uint32_t um) { return {um, 1}; }
constexpr Pitch pitch_tpi(uint32_t tpi) { return {25400, tpi}; }
constexpr Pitch pitch_tpi_x2(uint32_t half_tpi) { return {50800, half_tpi}; }

struct CountsPerTurn {
  uint32_t num;  // leadscrew counts per leadscrew turn = num / den
  uint32_t den;
};

// Stepper: motor pulley motor_teeth drives the leadscrew pulley screw_teeth.
constexpr CountsPerTurn stepper_counts(uint32_t steps, uint32_t microsteps, uint32_t motor_teeth = 1,
                                       uint32_t screw_teeth = 1) {
  return {steps * microsteps * screw_teeth, motor_teeth};
}
// Servo: encoder pulses per motor turn, gearbox gear_num : gear_den (motor
// turns per output turn), e.g. 30 pulses behind 1:26 -> servo_counts(30, 26).
constexpr CountsPerTurn servo_counts(uint32_t pulses, uint32_t gear_num, uint32_t gear_den = 1) {
  return {pulses * gear_num, gear_den};
}

struct Machine {
  Pitch leadscrew;
  CountsPerTurn leadscrew_counts;
  uint16_t spindle_counts;  // per spindle turn
  bool leadscrew_reversed;  // positive counts cut a left-hand thread
};

enum class Hand : uint8_t { right, left };

struct ThreadRequest {
  Pitch pitch;  // thread pitch, or feed per turn
  uint8_t starts;
  Hand hand;
};

enum class RatioStatus : uint8_t { exact, approximated, out_of_range };

struct GearRatio {
  RatioStatus status;
  bool reversed;
  Ratio ratio;         // what the Follower runs
  U128 exact_num;      // lambda, reduced (below 2^64 unless out_of_range)
  U128 exact_den;
  int32_t error_pm;    // per spindle turn; 0 when exact
};

// N / D = (n0 n1 n2 n3) / (d0 d1 d2 d3), reduced: cancelling every pair
// leaves every n_i coprime to every d_j, hence the products coprime. Four
// 32-bit factors always fit 128 bits.
__attribute__((noinline)) inline void reduced_product(uint32_t* n, uint32_t* d, U128& N, U128& D) {
  for (uint8_t i = 0; i < 4; ++i)
    for (uint8_t j = 0; j < 4; ++j) {
      const uint32_t c = gcd32(n[i], d[j]);
      n[i] /= c;
      d[j] /= c;
    }
  N = u128(1);
  D = u128(1);
  for (uint8_t i = 0; i < 4; ++i) {
    mul_small(N, n[i]);
    mul_small(D, d[i]);
  }
}

// (lead it cuts - lead requested) per spindle turn in pm, truncated toward
// zero, saturated: 10^6 lead_num e / (lead_den q N), with e < 2^64 (a Euclid
// remainder) and 10^6 lead_num < 10^6 2^32 2^8 < 2^60, so the product fits.
inline int32_t pitch_error_pm(const ThreadRequest& t, const Approximation& a, const U128& N) {
  U128 x = a.error, rem;
  mul_small(x, 1000000);
  mul_small(x, t.pitch.num);
  mul_small(x, t.starts);
  divmod(x, u128(a.den), x, rem);
  divmod(x, N, x, rem);
  divmod(x, u128(t.pitch.den), x, rem);
  const uint32_t mag = (!fits32(x) || x.w[0] > 0x7FFFFFFFu) ? 0x7FFFFFFFu : x.w[0];
  return a.error_positive ? int32_t(mag) : -int32_t(mag);
}

// The exact part of gear_ratio(): lambda reduced and, when it fits the
// follower, status exact; else status out_of_range and den_limit the
// denominator limit the fallback works to (0 when no fraction can do).
inline GearRatio reduced_ratio(const Machine& m, const ThreadRequest& t, uint32_t max_den, uint32_t& den_limit) {
  GearRatio g = {RatioStatus::out_of_range, false, {0, 1}, u128(0), u128(1), 0};
  den_limit = 0;
  g.reversed = (t.hand == Hand::left) != m.leadscrew_reversed;
  uint32_t n[4] = {t.pitch.num, t.starts, m.leadscrew.den, m.leadscrew_counts.num};
  uint32_t d[4] = {t.pitch.den, m.leadscrew.num, m.leadscrew_counts.den, m.spindle_counts};
  if (max_den == 0) return g;
  for (uint8_t i = 0; i < 4; ++i)
    if (n[i] == 0 || d[i] == 0) return g;
  reduced_product(n, d, g.exact_num, g.exact_den);
  const U128& N = g.exact_num;
  const U128& D = g.exact_den;
  if (!fits64(N) || !fits64(D)) return g;
  const U128 d_shifted = {{0, D.w[0], D.w[1], 0}};  // D 2^32
  if (cmp(N, d_shifted) >= 0) return g;             // lambda >= 2^32

  const uint32_t phase_scale = t.starts / gcd32(t.starts, m.spindle_counts);
  den_limit = kMaxDen / phase_scale;
  if (max_den < den_limit) den_limit = max_den;
  if (fits32(N) && fits32(D) && D.w[0] <= den_limit) {
    g.status = RatioStatus::exact;
    g.ratio = {N.w[0], D.w[0]};
  }
  return g;
}

// gear_ratio() without the fallback: status exact, or out_of_range also
// where gear_ratio() would approximate. For a program that refuses what it
// cannot run exactly (and leaves the continued fraction, about 1.6 KB of
// AVR flash, out of its image).
inline GearRatio gear_ratio_exact(const Machine& m, const ThreadRequest& t) {
  uint32_t den_limit;
  return reduced_ratio(m, t, kMaxDen, den_limit);
}

inline GearRatio gear_ratio(const Machine& m, const ThreadRequest& t, uint32_t max_den = kMaxDen) {
  uint32_t den_limit;
  GearRatio g = reduced_ratio(m, t, max_den, den_limit);
  if (g.status == RatioStatus::exact || den_limit == 0) return g;
  const Approximation a = best_rational(g.exact_num, g.exact_den, 0xFFFFFFFFu, den_limit);
  if (a.num == 0) return g;
  g.status = RatioStatus::approximated;
  g.ratio = {a.num, a.den};
  g.error_pm = pitch_error_pm(t, a, g.exact_num);
  return g;
}

}  // namespace am
