// Integer circular interpolator (one plane): one event per step, every point
// within half a step of the circle, ending exactly on the programmed end
// point, with the exact number of events known before the first one.
//
// Contract
//   start(end, centre, dir) plans an arc from the current point (0, 0) to
//   `end`, around `centre` (the G-code I, J offsets from the start), all in
//   steps, clockwise or counter-clockwise; end == start is a full circle
//   (the caller drops an arc whose programmed end differs from its start but
//   rounds onto it). events() is then the exact number of events: planning
//   is closed-form, nothing is simulated. next() yields each event: the axes
//   that step (first, second or both: a king move, never more than one step
//   per axis per event) and their directions. After events() events the
//   position is `end` exactly, and not before.
//   The path never turns back needlessly: within a quadrant of the circle
//   each axis moves one way only, so an axis reverses only where the
//   circle's tangent does (at the quadrant boundaries).
//
// Accuracy (proofs, checks and measurements in docs/interpolation.md)
//   - End point on the start circle (|end - centre| = |centre| exactly, as in
//     every seed-002 vector): every point within 0.5 step of the circle,
//     strictly. Proven for the rows and columns inside each octant, checked
//     for every integer radius^2 <= 3e6 at the diagonals, and run: every
//     full circle from every start point of radius <= 632, both directions
//     (2.5 million circles, worst 0.4998).
//   - End point rounded to steps (|r_end - r_start| <= 0.71): the arc's
//     segments (below) may each follow a circle of their own radius between
//     r_start and r_end, changed only at a junction point that lies on both
//     circles, so the path runs exactly through the start and the end point
//     and every point is within 0.5 step of a radius in [r_start, r_end]
//     (measured 0.4999), hence within 0.5 + |r_end - r_start| of the start
//     circle (measured worst 0.85 step over 2.2 million arcs).
//   - Larger mismatches (G-code radius tolerances): the same, and where a
//     junction cannot take the whole step the last segment's counters steer
//     it onto the end point; a short arc with several steps of mismatch is
//     finished by a straight tail from the end point's projection on the
//     start circle (an arc within one segment: the straight line). Always
//     exact; measured within 0.83 step of the radius band for mismatches up
//     to 5 steps. Rounded end points never need the tail.
//
// How (integer only; 64-bit arithmetic and square roots only in start())
//   In each quadrant the motion maps to one canonical case: (u, v) with
//   u > 0 decreasing and v >= 0 increasing. Below the diagonal (u > v) v is
//   the fast axis: it steps at every event, and u steps when that lands
//   nearer the circle (midpoint test on the residual F = u^2 + v^2 - r^2,
//   kept exactly by adding 2v + 1 and the like); above it u is fast. That
//   path is the digital circle of nearest lattice points per row / per
//   column, so a segment's (half a quadrant's) event count is its fast-axis
//   distance and its end points (the diagonal switch point, the axis point)
//   have closed forms: one or two isqrt64 per segment, at most 11 segments.
//   next() also counts the fast and slow steps each segment still owes; if
//   the midpoint test would make the segment's end unreachable the slow step
//   is forced (or withheld). On the circle that never triggers; it is what
//   makes the end point and the count exact by construction, whatever the
//   end point.
//   Per event: 32-bit additions, compares and decrements; no multiplication
//   or division. ATmega32 (avr-gcc 5.4 -Os, simavr): 148 cycles a event on
//   average, 125..498 (the maximum at a segment change); planning 45k cycles
//   a quarter circle, 129k a full one. 230 bytes of RAM, about 9 KB of flash
//   (mostly 64-bit planning code); path_length_q8() about 2 KB more if used.
//
// Planning for speed: events are axis steps (length 1) or diagonal steps
// (length sqrt 2). events() is what a ramp is planned over,
// path_length_q8() converts a feed rate into time, diagonal_events() counts
// the sqrt 2 events. Timing every event alike makes the tool speed vary by
// 41 % around a circle; stretching diagonal events by sqrt 2 leaves 8 %;
// scaling the interval by r / max(|x|, |y|) (x(), y() give the position)
// leaves 1.5 % (see the doc). A helical axis and the extruder ride along as
// LineDda minors over events() (core/motion/line_dda.h).
//
// Limits: every coordinate relative to the centre below 2^28 steps in
// magnitude; |r_end^2 - r_start^2| <= 2^29; at least one step of radius at
// both ends; one revolution at most (split multi-turn arcs). start()
// returns an ArcError otherwise.
#pragma once
#include <stddef.h>
#include <stdint.h>
#include "../math/isqrt.h"
#include "step_event.h"

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

class ArcDda {
 public:
  static constexpr int32_t kMaxCoord = (int32_t(1) << 28) - 1;
  static constexpr int64_t kMaxMismatch = int64_t(1) << 29;
  static constexpr uint8_t kMaxSegments = 11;  // 9 arc + 1 neighbour + 1 tail

  // Plans the arc. `x_axis`, `y_axis` (0..7) are the event bits of the
  // plane's first and second axis (G17: X, Y; G18: Z, X; G19: Y, Z; the
  // direction is seen from the positive third axis, as in G-code). On error
  // the arc is empty (finished, no events).
  ArcError start(int32_t end_x, int32_t end_y, int32_t centre_i, int32_t centre_j, ArcDir dir,
                 uint8_t x_axis = 0, uint8_t y_axis = 1) {
    clear();
    // Start and end relative to the centre; clockwise = counter-clockwise
    // mirrored in y.
    const bool cw = dir == ArcDir::cw;
    int32_t x0, y0, xe, ye;
    if (!offset(0, centre_i, false, &x0) || !offset(0, centre_j, cw, &y0) ||
        !offset(end_x, centre_i, false, &xe) || !offset(end_y, centre_j, cw, &ye))
      return ArcError::out_of_range;
    if ((x0 == 0 && y0 == 0) || (xe == 0 && ye == 0)) return ArcError::zero_radius;
    x_bit_ = uint8_t(1u << x_axis);
    y_bit_ = uint8_t(1u << y_axis);
    mirror_ = cw;
    const arc_detail::Canon p0 = arc_detail::canon(x0, y0);
    const arc_detail::Canon pe = arc_detail::canon(xe, ye);
    n0_ = uint64_t(norm(p0));
    const int64_t mismatch = norm(pe) - int64_t(n0_);
    if (mismatch > kMaxMismatch || mismatch < -kMaxMismatch) return ArcError::out_of_range;
    x0_ = x0;
    y0_ = cw ? -y0 : y0;
    const bool full = x0 == xe && y0 == ye;
    const uint8_t s0 = uint8_t(2 * p0.q + (p0.u > p0.v ? 0 : 1));
    // The segment count the end point's own side of the diagonal names fixes
    // how far round the arc goes; alternatives may only move its last
    // junction by one segment, never add or drop a turn.
    const uint8_t m_ref = segment_count(p0, s0, pe, pe.u > pe.v ? 0 : 1, full);
    const uint64_t r0_q8 = arc_detail::radius_q8(n0_);
    const uint64_t re_q8 = arc_detail::radius_q8(uint64_t(norm(pe)));
    if (!plan(p0, s0, pe, full, m_ref) && !plan_with_tail(p0, s0, xe, ye, full, m_ref, r0_q8, re_q8))
      return fail(ArcError::unreachable);
    xe_ = xe;
    ye_ = ye;
    f_ = -delta0_;  // u^2 + v^2 - (r_start^2 + delta0) at the start point
    u_ = p0.u;
    v_ = p0.v;
    seg_ = 0;
    enter(0);
    return ArcError::none;
  }

  uint32_t events() const { return events_; }
  // Events whose slow axis also steps (diagonal moves, length sqrt 2).
  uint32_t diagonal_events() const { return diagonal_; }
  // Length of the programmed path, 1/256 step: the mean of the start and end
  // radius times the swept angle, combined with the radius change as
  // sqrt(along^2 + radial^2) (exact for a circle; a spiral to first order).
  // Within 0.05 + 4e-9 r steps (Q8 radii, Q31-radian angles). Computed on
  // demand (two arctangents, about 2 KB of AVR code only if called); 0 when
  // no arc is planned.
  uint64_t path_length_q8() const {
    if (nseg_ == 0 && events_ == 0) return 0;
    const arc_detail::Canon p0 = arc_detail::canon(x0_, y0_mirrored());
    const arc_detail::Canon pe = arc_detail::canon(xe_, ye_);
    return length_q8(p0, pe, arc_detail::radius_q8(uint64_t(norm(p0))),
                     arc_detail::radius_q8(uint64_t(norm(pe))));
  }
  bool finished() const { return seg_ >= nseg_; }
  uint32_t remaining() const {
    if (finished()) return 0;
    uint32_t n = slack_ + dleft_;
    for (uint8_t k = uint8_t(seg_ + 1); k < nseg_; ++k) n += segs_[k].fast;
    return n;
  }
  // Current position relative to the start (setup/test use, not per event).
  int32_t x() const { return cx() - x0_; }
  int32_t y() const { return cy() - y0_; }

  // The next event; call only while !finished(). Written so that each 32-bit
  // member is loaded once and only the changed ones are stored: on the AVR
  // the memory traffic, not the arithmetic, is most of the cost.
  StepEvent next() {
    if (mode_ & 2) return next_tail();
    int32_t f = f_;
    uint32_t slack = slack_, dleft = dleft_;
    uint8_t axes = fast_bit_;
    if (mode_) {  // u fast: u - 1, then v + 1 if the midpoint (u, v + 1/2) is inside
      int32_t u = u_;
      f -= 2 * u - 1;
      u_ = --u;
      const int32_t v = v_;
      // Forced when every event left must step slow, barred when none may.
      if (slack == 0 || (dleft != 0 && f < -v)) {
        f += 2 * v + 1;
        v_ = v + 1;
        dleft_ = --dleft;
        axes |= slow_bit_;
      } else {
        slack_ = --slack;
      }
    } else {  // v fast: v + 1, then u - 1 if the midpoint (u - 1/2, v) is outside
      int32_t v = v_;
      f += 2 * v + 1;
      v_ = ++v;
      const int32_t u = u_;
      if (slack == 0 || (dleft != 0 && f >= u)) {
        f -= 2 * u - 1;
        u_ = u - 1;
        dleft_ = --dleft;
        axes |= slow_bit_;
      } else {
        slack_ = --slack;
      }
    }
    f_ = f;
    const StepEvent ev{axes, dirs_};
    if ((slack | dleft) == 0) advance();
    return ev;
  }

 private:
  // One event of the straight tail (rare: only after a mismatch fallback).
  // Kept out of line so that next()'s common path keeps its registers.
  __attribute__((noinline)) StepEvent next_tail() {
    int32_t f = f_ - line_slow_;
    const bool want = f < 0;
    if (want) f += line_fast_;
    f_ = f;
    uint8_t axes = fast_bit_;
    u_ += du_fast_;
    v_ += dv_fast_;
    if (slack_ == 0 || (dleft_ != 0 && want)) {
      axes |= slow_bit_;
      u_ += du_slow_;
      v_ += dv_slow_;
      --dleft_;
    } else {
      --slack_;
    }
    const StepEvent ev{axes, dirs_};
    if ((slack_ | dleft_) == 0) advance();
    return ev;
  }

  // A segment: half a quadrant (one fast axis), between two waypoints.
  struct Segment {
    uint32_t fast;  // events (fast-axis steps)
    uint32_t slow;  // of which also step the slow axis
    int32_t dt;     // radius^2 change at its start (the residual drops by it)
    uint8_t flags;  // bits 0-1 quadrant, then the k flags below
  };
  static constexpr uint8_t kUFast = 4, kNewQuadrant = 8;
  // A straight tail (Bresenham from the planned end to the end point), with
  // the signs of its u and v motion.
  static constexpr uint8_t kLine = 16, kUNeg = 32, kVNeg = 64;

  static bool in_range(int64_t c) { return c <= kMaxCoord && c >= -kMaxCoord; }
  static int64_t norm(const arc_detail::Canon& p) {
    return int64_t(p.u) * p.u + int64_t(p.v) * p.v;
  }
  // Planning works on radius^2 offsets from the start's, delta = r^2 -
  // r_start^2: within the limits every offset the planner meets (acceptance
  // intervals, blends, junction steps) is below 2^31 in magnitude, so only
  // the square roots see 64 bits. (On the AVR 64-bit code is large.)
  __attribute__((noinline)) int32_t rel_norm(const arc_detail::Canon& p) const {
    return int32_t(norm(p) - int64_t(n0_));
  }
  uint64_t abs_t(int32_t delta) const { return uint64_t(int64_t(n0_) + delta); }
  static int32_t clamp(int32_t t, int32_t lo, int32_t hi) { return t < lo ? lo : (t > hi ? hi : t); }
  // Offsets for which p is the nearest lattice point of its row (v-fast) or
  // column (u-fast): then the digital circle of that radius runs through p.
  __attribute__((noinline)) void accept(const arc_detail::Canon& p, uint8_t mode, int32_t* lo,
                                        int32_t* hi) const {
    const int32_t n = rel_norm(p), w = mode ? p.v : p.u;
    *lo = n - w + 1;
    *hi = n + w;
  }

  ArcError fail(ArcError e) {
    clear();
    return e;
  }

  // *out = (a - b), negated if `neg`; false beyond kMaxCoord.
  __attribute__((noinline)) static bool offset(int32_t a, int32_t b, bool neg, int32_t* out) {
    int64_t d = int64_t(a) - b;
    if (neg) d = -d;
    if (d > kMaxCoord || d < -kMaxCoord) return false;
    *out = int32_t(d);
    return true;
  }

  // Beyond what the blended radii can absorb (a radius mismatch well above
  // rounding on a short arc): the arc to the end point's projection on the
  // start circle, then a straight tail to the end; an arc too short for that
  // is the straight line alone.
  __attribute__((noinline)) bool plan_with_tail(const arc_detail::Canon& p0, uint8_t s0, int32_t xe,
                                                int32_t ye, bool full, uint8_t m_ref,
                                                uint64_t r0_q8, uint64_t re_q8) {
    const int32_t xp = scale_round(xe, r0_q8, re_q8), yp = scale_round(ye, r0_q8, re_q8);
    const bool planned = (xp != 0 || yp != 0) &&
                         plan(p0, s0, arc_detail::canon(xp, yp), full || (xp == x0_ && yp == y0_mirrored()),
                              m_ref);
    if (!planned) {
      if (m_ref != 1) return false;
      nseg_ = 0;  // no arc: the line from the start
      events_ = diagonal_ = 0;
      end_q_ = p0.q;
      end_u_ = p0.u;
      end_v_ = p0.v;
      delta0_ = 0;
    }
    return add_tail(xe, ye);
  }
  int32_t y0_mirrored() const { return mirror_ ? -y0_ : y0_; }

  // The programmed path's length (see path_length_q8()).
  __attribute__((noinline)) static uint64_t length_q8(const arc_detail::Canon& p0,
                                                           const arc_detail::Canon& pe,
                                                           uint64_t r0_q8, uint64_t re_q8) {
    constexpr uint64_t kHalfPiQ31 = 3373259426u;
    const uint64_t a0 = p0.q * kHalfPiQ31 + arc_detail::canon_angle_q31(p0);
    const uint64_t ae = pe.q * kHalfPiQ31 + arc_detail::canon_angle_q31(pe);
    const uint64_t swept = ae > a0 ? ae - a0 : ae + 4 * kHalfPiQ31 - a0;  // equal: a full turn
    const uint64_t r_q8 = (r0_q8 + re_q8 + 1) / 2;
    const uint64_t along = ((r_q8 * (swept >> 16)) >> 15) + ((r_q8 * (swept & 0xFFFF)) >> 31);
    const uint64_t radial = r0_q8 > re_q8 ? r0_q8 - re_q8 : re_q8 - r0_q8;
    if (radial == 0) return along;
    // A spiral's length, to first order: sqrt(along^2 + radial^2).
    uint8_t shift = 0;
    uint64_t a = along, b = radial;
    while (a >= (uint64_t(1) << 31) || b >= (uint64_t(1) << 31)) a >>= 1, b >>= 1, ++shift;
    return uint64_t(arc_detail::root64(a * a + b * b)) << shift;
  }

  // round(c * num / den), num and den > 0; Q8 radii up to 2^36 times a
  // coordinate below 2^28 would overflow, so both are shifted down first.
  __attribute__((noinline)) static int32_t scale_round(int32_t c, uint64_t num, uint64_t den) {
    while (num >= (uint64_t(1) << 34) || den >= (uint64_t(1) << 34)) num >>= 1, den >>= 1;
    const uint64_t a = uint64_t(c < 0 ? -int64_t(c) : c) * num, q = (a + den / 2) / den;
    return c < 0 ? -int32_t(q) : int32_t(q);
  }

  // Segments from the start's (s0) to the end's segment (quadrant and mode):
  // 1 when the end is ahead within the start's segment, 9 when it is behind
  // it there (round the circle), otherwise the segments in between plus one.
  __attribute__((noinline)) static uint8_t segment_count(const arc_detail::Canon& p0, uint8_t s0,
                               const arc_detail::Canon& pe, uint8_t mode_e, bool full) {
    const uint8_t se = uint8_t(2 * pe.q + mode_e);
    const int64_t cross = int64_t(p0.u) * pe.v - int64_t(p0.v) * pe.u;
    if (!full && se == s0 && cross > 0) return 1;
    return se == s0 ? 9 : uint8_t(((se - s0) & 7) + 1);
  }

  // Plans the arc from p0 to pe: the end closes the segment its own side of
  // the diagonal names or, if that is not monotonically reachable (a point
  // rounded across the diagonal), the neighbouring one; a point on its
  // quadrant's start axis may also close the previous quadrant. Only plans
  // within one segment of m_ref count.
  __attribute__((noinline)) bool plan(const arc_detail::Canon& p0, uint8_t s0, const arc_detail::Canon& pe, bool full,
            uint8_t m_ref) {
    const uint8_t mode_e = pe.u > pe.v ? 0 : 1;
    if (try_end(p0, s0, pe, mode_e, full, m_ref)) return true;
    if (try_end(p0, s0, pe, uint8_t(1 - mode_e), full, m_ref)) return true;
    if (pe.v == 0) {
      const arc_detail::Canon on_axis{uint8_t((pe.q + 3) & 3), 0, pe.u};
      if (try_end(p0, s0, on_axis, 1, full, m_ref)) return true;
    }
    return false;
  }

  __attribute__((noinline)) bool try_end(const arc_detail::Canon& p0, uint8_t s0, const arc_detail::Canon& pe,
               uint8_t mode_e, bool full, uint8_t m_ref) {
    const uint8_t m = segment_count(p0, s0, pe, mode_e, full);
    if (m + 1 < m_ref || m > m_ref + 1) return false;
    return build(p0, pe, s0, m, mode_e);
  }

  // Appends a straight (Bresenham) segment from the planned end to (xe, ye)
  // (relative to the centre, mirrored frame), in the last segment's
  // canonical frame.
  __attribute__((noinline)) bool add_tail(int32_t xe, int32_t ye) {
    if (nseg_ >= kMaxSegments) return false;
    int32_t ue, ve;  // the end in quadrant end_q_'s frame (linear map)
    switch (end_q_) {
      case 0: ue = xe, ve = ye; break;
      case 1: ue = ye, ve = -xe; break;
      case 2: ue = -xe, ve = -ye; break;
      default: ue = -ye, ve = xe; break;
    }
    const int32_t du = ue - end_u_, dv = ve - end_v_;  // |.| < 2^29
    const uint32_t au = uint32_t(du < 0 ? -du : du), av = uint32_t(dv < 0 ? -dv : dv);
    const bool u_fast = au >= av;
    uint8_t flags = uint8_t(end_q_ | kLine | (u_fast ? kUFast : 0));
    if (du < 0) flags |= kUNeg;
    if (dv < 0) flags |= kVNeg;
    const uint32_t fast = u_fast ? au : av, slow = u_fast ? av : au;
    segs_[nseg_++] = Segment{fast, slow, 0, flags};
    events_ += fast;
    diagonal_ += slow;
    return true;
  }

  // Plans m segments from s0, the last one (of mode mode_e) ending at pe.
  __attribute__((noinline)) bool build(const arc_detail::Canon& p0, const arc_detail::Canon& pe,
                                       uint8_t s0, uint8_t m, uint8_t mode_e) {
    if (m < 1 || m > kMaxSegments) return false;
    int32_t p_lo, p_hi, e_lo, e_hi;
    accept(p0, uint8_t(s0 & 1), &p_lo, &p_hi);
    accept(pe, mode_e, &e_lo, &e_hi);
    // One radius for the whole arc when both ends allow it (nearest the start
    // radius); otherwise the closest pair, blended over the segments.
    int32_t t0, te;
    const int32_t lo = p_lo > e_lo ? p_lo : e_lo, hi = p_hi < e_hi ? p_hi : e_hi;
    if (lo <= hi) {
      t0 = te = clamp(0, lo, hi);
    } else if (p_hi < e_lo) {
      t0 = p_hi, te = e_lo;
    } else {
      t0 = p_lo, te = e_hi;
    }
    const int32_t span = te - t0;  // |span| <= 2^30
    arc_detail::Canon cur = p0;
    int32_t t_prev = t0;
    uint32_t total = 0, diagonal = 0;
    for (uint8_t k = 0; k < m; ++k) {
      const uint8_t s = uint8_t(s0 + k), mode = s & 1, q = (s >> 1) & 3;
      uint8_t flags = uint8_t(q | (mode ? kUFast : 0));
      if (k > 0 && mode == 0) {  // the previous segment ended on the axis: (0, v) -> (v, 0)
        cur = arc_detail::Canon{q, cur.v, 0};
        flags |= kNewQuadrant;
      }
      int32_t t = t0;
      if (k > 0) {
        int32_t a_lo, a_hi;
        accept(cur, mode, &a_lo, &a_hi);
        if (k == m - 1) {
          const int32_t l2 = a_lo > e_lo ? a_lo : e_lo, h2 = a_hi < e_hi ? a_hi : e_hi;
          t = l2 <= h2 ? clamp(te, l2, h2) : te;
        } else {
          const int32_t parts = m - 1;  // t0 + span k / parts without overflow
          t = clamp(t0 + span / parts * k + span % parts * k / parts, a_lo, a_hi);
        }
      }
      arc_detail::Canon end = pe;
      if (k < m - 1) {
        if (mode == 0) {
          arc_detail::switch_point(abs_t(t), &end.u, &end.v);
        } else {
          end.u = 0;
          end.v = int32_t(arc_detail::round_sqrt(abs_t(t)));
        }
      }
      const int32_t fast = mode ? cur.u - end.u : end.v - cur.v;
      const int32_t slow = mode ? end.v - cur.v : cur.u - end.u;
      if (slow < 0 || slow > fast) return false;
      segs_[k] = Segment{uint32_t(fast), uint32_t(slow), t - t_prev, flags};
      total += uint32_t(fast);
      diagonal += uint32_t(slow);
      t_prev = t;
      cur = end;
    }
    nseg_ = m;
    events_ = total;
    diagonal_ = diagonal;
    delta0_ = t0;
    end_q_ = cur.q;
    end_u_ = cur.u;
    end_v_ = cur.v;
    return true;
  }

  // Loads segment k's counters and outputs (applying its quadrant change and
  // radius step), skipping empty segments.
  __attribute__((noinline)) void enter(uint8_t k) {
    for (; k < nseg_; ++k) {
      const Segment& s = segs_[k];
      if (s.flags & kNewQuadrant) {
        const int32_t t = u_;
        u_ = v_;
        v_ = t;
      }
      f_ -= s.dt;
      const uint8_t q = s.flags & 3;
      quadrant_ = q;
      const uint8_t u_bit = (q & 1) ? y_bit_ : x_bit_, v_bit = (q & 1) ? x_bit_ : y_bit_;
      // Canonical u decreases, v increases; per quadrant that is:
      // q0 x-, y+; q1 y-, x-; q2 x+, y-; q3 y+, x+. A tail moves u and v by
      // its own signs.
      const bool u_down = !(s.flags & kLine) || (s.flags & kUNeg);
      const bool v_up = !(s.flags & kLine) || !(s.flags & kVNeg);
      const bool u_plus = (q >= 2) == u_down;          // u axis moves towards +
      const bool v_plus = (q == 0 || q == 3) == v_up;  // v axis moves towards +
      uint8_t dirs = uint8_t((u_plus ? u_bit : 0) | (v_plus ? v_bit : 0));
      if (mirror_) dirs ^= y_bit_;
      dirs_ = dirs;
      const bool u_fast = s.flags & kUFast;
      mode_ = uint8_t((u_fast ? 1 : 0) | (s.flags & kLine ? 2 : 0));
      fast_bit_ = u_fast ? u_bit : v_bit;
      slow_bit_ = u_fast ? v_bit : u_bit;
      slack_ = s.fast - s.slow;
      dleft_ = s.slow;
      if (s.flags & kLine) {
        line_fast_ = int32_t(s.fast);
        line_slow_ = int32_t(s.slow);
        f_ = int32_t(s.fast - 1 - s.fast / 2);  // Bresenham accumulator, nearest rounding
        const int8_t du = (s.flags & kUNeg) ? -1 : 1, dv = (s.flags & kVNeg) ? -1 : 1;
        du_fast_ = u_fast ? du : 0;
        dv_fast_ = u_fast ? 0 : dv;
        du_slow_ = u_fast ? 0 : du;
        dv_slow_ = u_fast ? dv : 0;
      }
      if (s.fast != 0) break;
    }
    seg_ = k;
  }
  void advance() { enter(uint8_t(seg_ + 1)); }

  // Canonical point -> coordinates relative to the centre (y mirrored back
  // for clockwise arcs).
  int32_t canon_x(const arc_detail::Canon& p) const {
    switch (p.q) {
      case 0: return p.u;
      case 1: return -p.v;
      case 2: return -p.u;
      default: return p.v;
    }
  }
  int32_t canon_y(const arc_detail::Canon& p) const {
    int32_t y;
    switch (p.q) {
      case 0: y = p.v; break;
      case 1: y = p.u; break;
      case 2: y = -p.v; break;
      default: y = -p.u; break;
    }
    return mirror_ ? -y : y;
  }
  int32_t cx() const { return canon_x(arc_detail::Canon{quadrant_, u_, v_}); }
  int32_t cy() const { return canon_y(arc_detail::Canon{quadrant_, u_, v_}); }

  __attribute__((noinline)) void clear() {
    nseg_ = 0;
    seg_ = 0;
    events_ = diagonal_ = 0;
    slack_ = dleft_ = 0;
    xe_ = ye_ = 0;
    f_ = u_ = v_ = 0;
    x0_ = y0_ = 0;
    quadrant_ = mode_ = 0;
    n0_ = 0;
    delta0_ = 0;
    line_fast_ = line_slow_ = 0;
    du_fast_ = dv_fast_ = du_slow_ = dv_slow_ = 0;
    end_q_ = 0;
    end_u_ = end_v_ = 0;
  }

  // Per-event state first (the step interrupt touches only these).
  int32_t f_ = 0;  // u^2 + v^2 - r_k^2
  int32_t u_ = 0, v_ = 0;
  uint32_t slack_ = 0;  // events of the segment left that need not step slow
  uint32_t dleft_ = 0;  // slow steps of the segment left
  uint8_t mode_ = 0, quadrant_ = 0;
  uint8_t fast_bit_ = 0, slow_bit_ = 0, dirs_ = 0;
  uint8_t seg_ = 0, nseg_ = 0;
  uint8_t x_bit_ = 0, y_bit_ = 0;  // set by start(); zero defaults keep a global in .bss
  bool mirror_ = false;
  uint32_t events_ = 0, diagonal_ = 0;
  int32_t x0_ = 0, y0_ = 0;  // start point relative to the centre
  uint64_t n0_ = 0;      // start radius^2
  int32_t delta0_ = 0;   // first segment's radius^2 offset from it
  int32_t line_fast_ = 0, line_slow_ = 0;  // the tail's totals
  int8_t du_fast_ = 0, dv_fast_ = 0, du_slow_ = 0, dv_slow_ = 0;
  uint8_t end_q_ = 0;  // the planned end (before a tail), canonical
  int32_t end_u_ = 0, end_v_ = 0;
  int32_t xe_ = 0, ye_ = 0;  // end point relative to the centre (mirrored frame)
  Segment segs_[kMaxSegments] = {};
};

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
