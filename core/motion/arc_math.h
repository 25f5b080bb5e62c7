// Integer arc arithmetic shared by the circular DDA (arc_dda.h) and its
// segment planning (arc_segments.h): the arc's direction and error codes,
// the setup-time helpers, and the G-code R form's centre.
//
// Contract
//   ArcDir and ArcError are the public words of an arc: start() of ArcDda
//   takes the one and returns the other, and so does
//   arc_centre_from_radius(), the R form (below). The arc_detail helpers are
//   exact integer functions: root64 / round_sqrt (floor and nearest square
//   root), canon (a point relative to the centre in its quadrant's canonical
//   frame), switch_point (where a digital circle crosses its diagonal),
//   mul128 / div128 (exact 128-bit products and quotients), atan_q31 /
//   canon_angle_q31 (angles, radians Q31) and radius_q8 (a radius from its
//   square, 1/256 step). None keeps state.
//
// Why a file of its own
//   These are the arithmetic, not the arc: the planner and the R form both
//   use them, and none of them runs per event (64-bit work, divisions and
//   square roots belong to setup). Each is kept out of line (noinline) on
//   purpose: on the AVR 64-bit code is large, and inlined into every caller
//   the arc was 18 KB instead of 9.8 (docs/interpolation.md, Cost).
#pragma once
#include <stddef.h>
#include <stdint.h>
#include "../math/isqrt.h"

namespace am {

enum class ArcDir : uint8_t { cw, ccw };

enum class ArcError : uint8_t {
  none,
  zero_radius,   // start or end point on the centre
  out_of_range,  // a coordinate or the radius mismatch beyond the limits
  unreachable,   // no monotone path to the end point (mismatch too large)
  bad_radius,    // R form: radius shorter than half the chord, or end == start
};

namespace arc_detail {

// floor(sqrt(x)), one out-of-line copy for every caller below (isqrt64 is
// inline, and about 480 bytes on the AVR each time it is inlined).
inline __attribute__((noinline)) uint32_t root64(uint64_t x) { return isqrt64(x); }

// round(sqrt(m)) = round(floor(2 sqrt(m)) / 2): 2 sqrt(m) is never an odd
// integer (4m is even), so there is no tie. m < 2^62.
inline __attribute__((noinline)) uint32_t round_sqrt(uint64_t m) {
  return (arc_detail::root64(m << 2) + 1) >> 1;
}

// A point relative to the centre in its quadrant's canonical frame: the
// motion is counter-clockwise, u > 0 decreases, v >= 0 increases.
// Quadrants are half-open: q0 x > 0, y >= 0; q1 x <= 0, y > 0; q2 x < 0,
// y <= 0; q3 x >= 0, y < 0.
struct Canon {
  uint8_t q;
  int32_t u, v;
};

inline __attribute__((noinline)) Canon canon(int32_t x, int32_t y) {
  if (x > 0 && y >= 0) return Canon{0, x, y};
  if (x <= 0 && y > 0) return Canon{1, y, -x};
  if (x < 0 && y <= 0) return Canon{2, -x, -y};
  return Canon{3, -y, x};
}

// Where the digital circle u^2 + v^2 ~ t crosses from v-fast to u-fast: the
// first row v whose nearest lattice u is <= v, i.e. the least v with
// 2v^2 + v >= t, and the u the path reaches there (one step in from the row
// before when the circle drops by two columns in that row).
inline __attribute__((noinline)) void switch_point(uint64_t t, int32_t* u, int32_t* v) {
  // 2w^2 + w >= t  <=>  (4w + 1)^2 >= 8t + 1  <=>  4w + 1 >= ceil(sqrt(8t + 1)).
  const uint64_t m = 8 * t + 1;
  const uint32_t s = root64(m);
  const uint32_t c = s + (uint64_t(s) * s == m ? 0u : 1u);
  const uint64_t w = (c + 2) / 4;
  const uint32_t here = round_sqrt(t - w * w);
  const uint32_t before = round_sqrt(t - (w - 1) * (w - 1));
  *v = int32_t(w);
  *u = int32_t(here + 1 >= before ? here : before - 1);
}

// 64 x 64 -> 128-bit unsigned product, for exact comparisons in setup code.
struct U128 {
  uint64_t hi, lo;
};
inline __attribute__((noinline)) U128 mul128(uint64_t a, uint64_t b) {
  const uint64_t a0 = uint32_t(a), a1 = a >> 32, b0 = uint32_t(b), b1 = b >> 32;
  const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
  const uint64_t mid = (p00 >> 32) + uint32_t(p01) + uint32_t(p10);
  return U128{p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32), (mid << 32) | uint32_t(p00)};
}
// floor(x / d) and x mod d, for x.hi < d (the quotient fits 64 bits) and
// d < 2^63: restoring division over the low 64 bits. Setup code.
inline __attribute__((noinline)) uint64_t div128(const U128& x, uint64_t d, uint64_t* rem) {
  uint64_t r = x.hi, lo = x.lo, q = 0;
  for (uint8_t i = 0; i < 64; ++i) {
    r = (r << 1) | (lo >> 63);
    lo <<= 1;
    q <<= 1;
    if (r >= d) {
      r -= d;
      q |= 1;
    }
  }
  *rem = r;
  return q;
}

// atan(t / 2^31) for 0 <= t <= 2^31, in radians Q31. atan(t) = pi/4 -
// atan((1 - t) / (1 + t)) brings t below tan(pi/8), then the alternating
// series converges by a factor 0.17 per term. Setup code (divides).
inline __attribute__((noinline)) uint32_t atan_q31(uint32_t t) {
  constexpr uint32_t kQuarterPiQ31 = 1686629713u;  // pi/4 * 2^31
  constexpr uint32_t kTanEighthQ31 = 889516852u;   // tan(pi/8) * 2^31
  bool reflected = false;
  if (t > kTanEighthQ31) {
    t = uint32_t((uint64_t(0x80000000u - t) << 31) / (0x80000000u + uint64_t(t)));
    reflected = true;
  }
  const uint32_t t2 = uint32_t((uint64_t(t) * t) >> 31);
  uint32_t power = t;
  int64_t sum = 0;
  for (uint32_t k = 1; power != 0; k += 2) {
    const int64_t term = power / k;
    sum += (k & 2) ? -term : term;
    power = uint32_t((uint64_t(power) * t2) >> 31);
  }
  return reflected ? kQuarterPiQ31 - uint32_t(sum) : uint32_t(sum);
}

// Angle of a canonical point from its quadrant's start axis, radians Q31.
inline __attribute__((noinline)) uint32_t canon_angle_q31(const Canon& p) {
  constexpr uint32_t kHalfPiQ31 = 3373259426u;  // pi/2 * 2^31
  if (p.v == 0) return 0;
  if (p.v <= p.u) return atan_q31(uint32_t((uint64_t(p.v) << 31) / uint32_t(p.u)));
  return kHalfPiQ31 - atan_q31(uint32_t((uint64_t(p.u) << 31) / uint32_t(p.v)));
}

// Radius in Q8 steps from its square.
inline __attribute__((noinline)) uint64_t radius_q8(uint64_t n) {
  return n < (uint64_t(1) << 48) ? arc_detail::root64(n << 16) : uint64_t(arc_detail::root64(n)) << 8;
}

}  // namespace arc_detail

// Centre offsets (i, j) from the start (0, 0) of the arc to (x, y) of radius
// |r| (G-code R form): r > 0 the arc of at most 180 degrees, r < 0 the longer
// one. The centre is the exact one rounded to the nearest step (exact 128-bit
// comparisons, no floating point). A radius shorter than half the chord by
// less than half a step is taken as a half circle (the chord's rounding);
// shorter still, or end == start, is bad_radius. |x|, |y|, |r| < 2^27.
inline ArcError arc_centre_from_radius(int32_t x, int32_t y, int32_t r, ArcDir dir, int32_t* i,
                                       int32_t* j) {
  constexpr int32_t kMax = (int32_t(1) << 27) - 1;
  if (x > kMax || x < -kMax || y > kMax || y < -kMax || r > kMax || r < -kMax)
    return ArcError::out_of_range;
  if ((x == 0 && y == 0) || r == 0) return ArcError::bad_radius;
  const int64_t ar = r < 0 ? -int64_t(r) : r;
  const uint64_t d2 = uint64_t(int64_t(x) * x + int64_t(y) * y);
  int64_t h = 4 * ar * ar - int64_t(d2);  // (2 * distance centre-chord)^2 * d2 / d2
  if (h < 0) {
    if (uint64_t((2 * ar + 1) * (2 * ar + 1)) < d2) return ArcError::bad_radius;
    h = 0;
  }
  // Centre = chord midpoint + s sqrt(h) / (2 d) * (-y, x); s = +1 puts it on
  // the left of the chord: the short counter-clockwise arc.
  const int s = (dir == ArcDir::ccw ? 1 : -1) * (r > 0 ? 1 : -1);
  // floor(sqrt(c^2 h / d2)): floor(sqrt(floor(q))) = floor(sqrt(q)), and the
  // 128-bit c^2 h divided exactly by d2 (the quotient, <= 4 r^2, fits 64 bits).
  const auto floor_root = [&](int64_t c, bool* exact) -> int64_t {
    uint64_t rem;
    const uint64_t q = arc_detail::div128(arc_detail::mul128(uint64_t(c * c), uint64_t(h)), d2, &rem);
    const uint64_t k = arc_detail::root64(q);
    *exact = rem == 0 && k * k == q;
    return int64_t(k);
  };
  // round((a + sign * sqrt(c^2 h / d2)) / 2), halves rounded up.
  const auto half_round = [&](int64_t a, int64_t c, int sign) -> int32_t {
    if (c == 0 || h == 0 || sign == 0) return int32_t((a + 1) >> 1);
    bool exact;
    const int64_t k = floor_root(c, &exact);
    if (sign > 0) return int32_t((a + 1 + k) >> 1);       // (a + 1 + Z) / 2, Z in [k, k + 1)
    return int32_t(exact ? (a + 1 - k) >> 1 : (a - k) >> 1);  // (a + 1 - Z) / 2
  };
  const int sy = y > 0 ? 1 : (y < 0 ? -1 : 0), sx = x > 0 ? 1 : (x < 0 ? -1 : 0);
  *i = half_round(x, y, -s * sy);  // x/2 - s y sqrt(h) / (2 d)
  *j = half_round(y, x, s * sx);   // y/2 + s x sqrt(h) / (2 d)
  return ArcError::none;
}

}  // namespace am
