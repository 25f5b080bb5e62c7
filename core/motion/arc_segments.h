// The circular DDA's plan (arc_dda.h): an arc cut into segments, each half a
// quadrant with one fast axis, with the exact number of events known before
// the first one.
//
// Contract
//   plan_arc(end, centre, cw, &p0) plans the arc from (0, 0) to `end`
//   around `centre` (offsets from the start, in steps; clockwise arcs are
//   planned mirrored in y) and gives the start point in its canonical frame.
//   Afterwards count() segments, each a Segment: its events (fast-axis
//   steps), how many of them also step the slow axis, the radius^2 step at
//   its start and its quadrant and kind. events() and diagonal_events() are
//   their totals, path_length_q8() the programmed path's length. On an
//   error the plan is empty (ArcDda clears it).
//
// How (closed form, nothing is simulated)
//   In each quadrant the motion maps to one canonical case: (u, v) with
//   u > 0 decreasing and v >= 0 increasing; below the diagonal (u > v) v is
//   the fast axis, above it u is. The digital circle of nearest lattice
//   points per row / per column then has closed-form waypoints (the
//   diagonal switch point, the axis point): one or two isqrt64 per segment,
//   at most 11 segments (9 arc + 1 neighbour + 1 tail). A segment's event
//   count is its fast-axis distance.
//   An end point off the start circle (rounded to steps, or a G-code radius
//   tolerance): each segment may follow a circle of its own radius between
//   r_start and r_end, changed only at a junction point that lies on both
//   circles, so the path runs exactly through the start and the end point.
//   Beyond what the blended radii can absorb, a short arc is finished by a
//   straight tail from the end point's projection on the start circle (an
//   arc within one segment: the straight line). Accuracy and proofs:
//   arc_dda.h and docs/interpolation.md.
//
// Why a class of its own
//   The planning is setup code (64-bit arithmetic, square roots, about 9 KB
//   of AVR code); the per-event stepping (ArcDda::next()) only reads the
//   finished plan, a segment at a time, from after its own per-event state.
#pragma once
#include <stdint.h>
#include "arc_math.h"

namespace am {

class ArcSegments {
 public:
  static constexpr int32_t kMaxCoord = (int32_t(1) << 28) - 1;
  static constexpr int64_t kMaxMismatch = int64_t(1) << 29;
  static constexpr uint8_t kMaxSegments = 11;  // 9 arc + 1 neighbour + 1 tail

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

  // Plans the arc (the order of the checks is ArcDda::start()'s contract:
  // coordinates, zero radius, mismatch, reachability). *p0 is the start
  // point, canonical and mirrored for clockwise arcs.
  ArcError plan_arc(int32_t end_x, int32_t end_y, int32_t centre_i, int32_t centre_j, bool cw,
                    arc_detail::Canon* p0_out) {
    // Start and end relative to the centre; clockwise = counter-clockwise
    // mirrored in y.
    int32_t x0, y0, xe, ye;
    if (!offset(0, centre_i, false, &x0) || !offset(0, centre_j, cw, &y0) ||
        !offset(end_x, centre_i, false, &xe) || !offset(end_y, centre_j, cw, &ye))
      return ArcError::out_of_range;
    if ((x0 == 0 && y0 == 0) || (xe == 0 && ye == 0)) return ArcError::zero_radius;
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
      return ArcError::unreachable;
    xe_ = xe;
    ye_ = ye;
    *p0_out = p0;
    return ArcError::none;
  }

  uint8_t count() const { return nseg_; }
  const Segment& segment(uint8_t k) const { return segs_[k]; }
  bool mirrored() const { return mirror_; }
  uint32_t events() const { return events_; }
  uint32_t diagonal_events() const { return diagonal_; }
  // The first segment's radius^2 offset from the start's: the residual at
  // the start point is its negative.
  int32_t delta0() const { return delta0_; }
  // Start point relative to the centre (y mirrored back for clockwise arcs).
  int32_t x0() const { return x0_; }
  int32_t y0() const { return y0_; }

  // See ArcDda::path_length_q8().
  uint64_t path_length_q8() const {
    if (nseg_ == 0 && events_ == 0) return 0;
    const arc_detail::Canon p0 = arc_detail::canon(x0_, y0_mirrored());
    const arc_detail::Canon pe = arc_detail::canon(xe_, ye_);
    return length_q8(p0, pe, arc_detail::radius_q8(uint64_t(norm(p0))),
                     arc_detail::radius_q8(uint64_t(norm(pe))));
  }

  __attribute__((noinline)) void clear() {
    nseg_ = 0;
    events_ = diagonal_ = 0;
    xe_ = ye_ = 0;
    x0_ = y0_ = 0;
    n0_ = 0;
    delta0_ = 0;
    end_q_ = 0;
    end_u_ = end_v_ = 0;
  }

 private:
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

  bool mirror_ = false;  // clockwise: planned mirrored in y
  uint8_t nseg_ = 0;
  uint32_t events_ = 0, diagonal_ = 0;
  int32_t x0_ = 0, y0_ = 0;  // start point relative to the centre
  uint64_t n0_ = 0;      // start radius^2
  int32_t delta0_ = 0;   // first segment's radius^2 offset from it
  uint8_t end_q_ = 0;  // the planned end (before a tail), canonical
  int32_t end_u_ = 0, end_v_ = 0;
  int32_t xe_ = 0, ye_ = 0;  // end point relative to the centre (mirrored frame)
  Segment segs_[kMaxSegments] = {};
};

}  // namespace am
