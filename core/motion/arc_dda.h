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
//   have closed forms: one or two isqrt64 per segment, at most 11 segments
//   (the planning: arc_segments.h).
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
//
// Files: this class is the per-event stepping (start(), next() and the
// segment changes), reading the plan it holds as a member after its
// per-event state; the plan is ArcSegments (arc_segments.h), the arithmetic
// and the R form's arc_centre_from_radius() are arc_math.h. Host only: the
// chip runs arcs as chords (arc_chords.h).
#pragma once
#include <stdint.h>
#include "arc_math.h"
#include "arc_segments.h"
#include "step_event.h"

namespace am {

class ArcDda {
 public:
  static constexpr int32_t kMaxCoord = ArcSegments::kMaxCoord;
  static constexpr int64_t kMaxMismatch = ArcSegments::kMaxMismatch;
  static constexpr uint8_t kMaxSegments = ArcSegments::kMaxSegments;

  // Plans the arc. `x_axis`, `y_axis` (0..7) are the event bits of the
  // plane's first and second axis (G17: X, Y; G18: Z, X; G19: Y, Z; the
  // direction is seen from the positive third axis, as in G-code). On error
  // the arc is empty (finished, no events).
  ArcError start(int32_t end_x, int32_t end_y, int32_t centre_i, int32_t centre_j, ArcDir dir,
                 uint8_t x_axis = 0, uint8_t y_axis = 1) {
    clear();
    arc_detail::Canon p0;
    const ArcError e = plan_.plan_arc(end_x, end_y, centre_i, centre_j, dir == ArcDir::cw, &p0);
    if (e == ArcError::unreachable) return fail(e);
    if (e != ArcError::none) return e;
    x_bit_ = uint8_t(1u << x_axis);
    y_bit_ = uint8_t(1u << y_axis);
    f_ = -plan_.delta0();  // u^2 + v^2 - (r_start^2 + delta0) at the start point
    u_ = p0.u;
    v_ = p0.v;
    seg_ = 0;
    enter(0);
    return ArcError::none;
  }

  uint32_t events() const { return plan_.events(); }
  // Events whose slow axis also steps (diagonal moves, length sqrt 2).
  uint32_t diagonal_events() const { return plan_.diagonal_events(); }
  // Length of the programmed path, 1/256 step: the mean of the start and end
  // radius times the swept angle, combined with the radius change as
  // sqrt(along^2 + radial^2) (exact for a circle; a spiral to first order).
  // Within 0.05 + 4e-9 r steps (Q8 radii, Q31-radian angles). Computed on
  // demand (two arctangents, about 2 KB of AVR code only if called); 0 when
  // no arc is planned.
  uint64_t path_length_q8() const { return plan_.path_length_q8(); }
  bool finished() const { return seg_ >= plan_.count(); }
  uint32_t remaining() const {
    if (finished()) return 0;
    uint32_t n = slack_ + dleft_;
    for (uint8_t k = uint8_t(seg_ + 1); k < plan_.count(); ++k) n += plan_.segment(k).fast;
    return n;
  }
  // Current position relative to the start (setup/test use, not per event).
  int32_t x() const { return cx() - plan_.x0(); }
  int32_t y() const { return cy() - plan_.y0(); }

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
  // The plan's segment flags (arc_segments.h).
  static constexpr uint8_t kUFast = ArcSegments::kUFast, kNewQuadrant = ArcSegments::kNewQuadrant;
  static constexpr uint8_t kLine = ArcSegments::kLine, kUNeg = ArcSegments::kUNeg,
                           kVNeg = ArcSegments::kVNeg;

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

  // Loads segment k's counters and outputs (applying its quadrant change and
  // radius step), skipping empty segments.
  __attribute__((noinline)) void enter(uint8_t k) {
    for (; k < plan_.count(); ++k) {
      const ArcSegments::Segment& s = plan_.segment(k);
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
      if (plan_.mirrored()) dirs ^= y_bit_;
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
    return plan_.mirrored() ? -y : y;
  }
  int32_t cx() const { return canon_x(arc_detail::Canon{quadrant_, u_, v_}); }
  int32_t cy() const { return canon_y(arc_detail::Canon{quadrant_, u_, v_}); }

  ArcError fail(ArcError e) {
    clear();
    return e;
  }

  __attribute__((noinline)) void clear() {
    seg_ = 0;
    slack_ = dleft_ = 0;
    f_ = u_ = v_ = 0;
    quadrant_ = mode_ = 0;
    line_fast_ = line_slow_ = 0;
    du_fast_ = dv_fast_ = du_slow_ = dv_slow_ = 0;
    plan_.clear();
  }

  // Per-event state first (the step interrupt touches only these).
  int32_t f_ = 0;  // u^2 + v^2 - r_k^2
  int32_t u_ = 0, v_ = 0;
  uint32_t slack_ = 0;  // events of the segment left that need not step slow
  uint32_t dleft_ = 0;  // slow steps of the segment left
  uint8_t mode_ = 0, quadrant_ = 0;
  uint8_t fast_bit_ = 0, slow_bit_ = 0, dirs_ = 0;
  uint8_t seg_ = 0;
  uint8_t x_bit_ = 0, y_bit_ = 0;  // set by start(); zero defaults keep a global in .bss
  int32_t line_fast_ = 0, line_slow_ = 0;  // the tail's totals
  int8_t du_fast_ = 0, dv_fast_ = 0, du_slow_ = 0, dv_slow_ = 0;
  // The plan, read at segment changes only.
  ArcSegments plan_;
};

}  // namespace am
