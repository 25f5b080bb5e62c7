// G2/G3 on the chip as a sequence of short straight chords, each one a move
// for the look-ahead planner like a G1, so that an arc runs at its planned
// speed with acceleration instead of stopping at every chord.
//
// Contract
//   All lengths are integers of one unit on every axis: the firmware gives
//   machine steps, so a chord end is a point the motors can stand on.
//   start(from, to, plane0, plane1, centre, clockwise, tolerance) plans the
//   arc from `from` to `to` (N axes) around from + centre in the plane of
//   axes plane0 and plane1; counter-clockwise turns from plane0 towards
//   plane1, clockwise (G2) the other way. The sweep runs from the start's
//   angle to the end's in that direction, in (0, 360] degrees: an end on the
//   start's ray (from == to in the plane) is a full circle. The radius goes
//   linearly with the angle from the start radius r0 to the end radius r1,
//   and every other axis (a helix's Z, the extruder) linearly from `from` to
//   `to`. chords() is then n, the smallest n >= 1 with
//   max(r0, r1) (1 - cos(sweep / 2n)) <= tolerance (units, a fraction of one
//   is fine): every chord's sag within `tolerance`. start() returns false
//   and changes nothing for tolerance <= 0, a bad plane, a zero start or end
//   radius, n > 65535, or a circle that leaves the int32 range
//   (|centre| + radius >= 2^31 - 3648 on a plane axis; this covers every
//   overflow of from + centre, to - centre).
//   next(point) gives the end of chord k = 1..n, then false (done() is
//   then true): the lattice
//   point nearest the spiral across it, near the spiral's point at angle
//   k sweep / n and radius r0 + (r1 - r0) k / n. The plane axis nearer the
//   tangent there is rounded (at most half a unit along the arc), the other
//   is the rounded crossing of the spiral with that grid line, so the point
//   is within half a unit of the spiral radially (plus 0.01 of float error),
//   where rounding both axes would allow 0.71. The last point is `to`
//   exactly. Every point comes from k alone, nothing accumulates: before
//   rounding it is within 0.01 unit of the spiral (|r1 - r0| up to the
//   interpreter's 0.5 mm, any radius the range allows); the float angle
//   moves it along the arc by a few 1e-7 rad (3 units at 5e6 units).
//
// Why this form
//   The chip cannot hold the integer circular DDA (arc_dda.h, 9.8 KB); this
//   is float trigonometry once per chord, in the main loop. Float alone is
//   not enough: a rounding costs 0.3 unit of radius at 5e6 units, and avr-libc's
//   sinf/cosf are not correctly rounded. So only the angle is float. cos and
//   sin become Q30 integers C, S, the exact start vector s = start - centre
//   is rotated exactly in 64 bits, (s0 C - s1 S, s0 S + s1 C), and since
//   C^2 + S^2 = 2^60 (1 + e) is exact too, scaling by
//   (1 + delta) / sqrt(1 + e) (first order in the tiny e, a float term of at
//   most |r1 - r0| and a fraction of a unit) puts the point on the spiral's
//   radius whatever the trig error. r1 - r0 comes from the exact
//   r1^2 - r0^2, the sweep's sign from the exact cross product. The other
//   axes step exactly with a quotient and remainder by n (one add and a
//   compare per chord); the plane axes do the same and are then replaced,
//   so the last point is `to` by construction.
//
// Cost (ATmega32, avr-gcc 5.4 -Os, N = 5; docs/interpolation.md, "Arcs on
// the chip: chords"): next() about 10,200 cycles (0.63 ms at 16 MHz),
// start() about 18,500; flash 2.66 KB of its own, 4.97 KB with what it
// takes from libm and libgcc (3.68 KB in a program that already uses float
// arithmetic); RAM 12 N + 31 bytes. Host g++ and avr-g++ 5.4; no
// allocation, <stdint.h> and <math.h> only.
#pragma once
#include <math.h>
#include <stdint.h>

namespace am {

template <uint8_t N>
class ArcChords {
  static_assert(N >= 2 && N <= 8, "ArcChords takes 2..8 axes");

 public:
  bool start(const int32_t (&from)[N], const int32_t (&to)[N], uint8_t plane0, uint8_t plane1,
             const int32_t (&centre)[2], bool clockwise, float tolerance) {
    if (!(tolerance > 0) || plane0 >= N || plane1 >= N || plane0 == plane1) return false;
    // Centre, start and end relative to it, in wrapping arithmetic: a value that wraps puts the
    // circle beyond the int32 range (|c| + r > 2^31 on that axis), so inside() refuses it.
    int32_t c[2], e[2];
    c[0] = int32_t(uint32_t(from[plane0]) + uint32_t(centre[0]));
    c[1] = int32_t(uint32_t(from[plane1]) + uint32_t(centre[1]));
    e[0] = int32_t(uint32_t(to[plane0]) - uint32_t(c[0]));
    e[1] = int32_t(uint32_t(to[plane1]) - uint32_t(c[1]));
    const int32_t s0 = int32_t(0u - uint32_t(centre[0])), s1 = int32_t(0u - uint32_t(centre[1]));
    const float r0 = length(s0, s1), r1 = length(e[0], e[1]), rmax = r0 > r1 ? r0 : r1;
    if (r0 * r1 == 0 || !inside(c[0], rmax) || !inside(c[1], rmax)) return false;

    // The sweep from the exact cross and dot products: its sign is exact.
    float sweep = atan2f(float(dot2(s0, e[1], -s1, e[0])), float(dot2(s0, e[0], s1, e[1])));
    const float full = 6.2831853f;
    if (clockwise) sweep = sweep < 0 ? sweep : sweep - full;
    else sweep = sweep > 0 ? sweep : sweep + full;

    // The fewest chords with sag rmax (1 - cos(dphi / 2)) <= tolerance: dphi / 2 <= acos(1 - w).
    uint16_t n = 1;
    const float w = tolerance / rmax;
    if (w < 2) {
      const float q = fabsf(sweep) / (2 * atan2f(sqrtf(w * (2 - w)), 1 - w));
      if (q > 65535.0f) return false;
      n = uint16_t(q);
      if (n < q) ++n;
    }
    n_ = n;
    k_ = 0;
    lines(from, to);
    plane_[0] = plane0;
    plane_[1] = plane1;
    centre_[0] = c[0];
    centre_[1] = c[1];
    start_[0] = s0;
    start_[1] = s1;
    step_ = sweep / n;
    grow_ = float(dot2(e[0], e[0], e[1], e[1]) - dot2(s0, s0, s1, s1)) / ((r0 + r1) * r0 * n);
    return true;
  }

  uint16_t chords() const { return n_; }
  // Every chord given out (also before any start()).
  bool done() const { return k_ == n_; }

  bool next(int32_t (&point)[N]) {
    if (k_ == n_) return false;
    ++k_;
    // Linear in k for every axis: from + round((to - from) k / n).
    for (uint8_t i = 0, bit = 1; i < N; ++i, bit <<= 1) {
      uint32_t d = quot_[i];
      if (acc_[i] >= n_ - rem_[i]) {
        acc_[i] = uint16_t(acc_[i] - (n_ - rem_[i]));
        ++d;
      } else {
        acc_[i] = uint16_t(acc_[i] + rem_[i]);
      }
      pos_[i] = int32_t(uint32_t(pos_[i]) + (neg_ & bit ? 0u - d : d));
      point[i] = pos_[i];
    }
    if (k_ == n_) return true;

    // The plane axes: start_ rotated exactly by the angle of chord k in Q30, then scaled
    // from its exact length to r0 + (r1 - r0) k / n.
    const float k = float(k_), one = 1073741824.0f;  // 2^30
    const float angle = step_ * k, cf = cosf(angle), sf = sinf(angle);
    const int32_t cq = int32_t(cf * one), sq = int32_t(sf * one);
    int32_t norm;
    const float rest = split(dot2(cq, cq, sq, sq), norm);  // C^2 + S^2 = 2^60 (1 + excess)
    const float excess = (float(norm - (int32_t(1) << 30)) + rest) * (1 / one);
    const float delta = grow_ * k;
    const float scale = delta - 0.5f * excess * (1 + delta);  // (1 + delta) / sqrt(1 + excess) - 1
    int32_t w0, w1;  // the spiral's point, relative to the centre: w + p on each plane axis
    float p0 = split(dot2(start_[0], cq, start_[1], -sq), w0);
    float p1 = split(dot2(start_[0], sq, start_[1], cq), w1);
    p0 += scale * (float(w0) + p0);
    p1 += scale * (float(w1) + p1);
    int32_t n0, n1;
    if (magnitude(w0) <= magnitude(w1)) n0 = snap(w0, p0, w1, p1, n1);
    else n1 = snap(w1, p1, w0, p0, n0);
    point[plane_[0]] = int32_t(uint32_t(centre_[0]) + uint32_t(w0) + uint32_t(n0));
    point[plane_[1]] = int32_t(uint32_t(centre_[1]) + uint32_t(w1) + uint32_t(n1));
    return true;
  }

 private:
  __attribute__((noinline)) void lines(const int32_t (&from)[N], const int32_t (&to)[N]) {
    neg_ = 0;
    for (uint8_t i = 0, bit = 1; i < N; ++i, bit <<= 1) {
      uint32_t d = uint32_t(to[i]) - uint32_t(from[i]);
      if (to[i] < from[i]) {
        d = 0u - d;
        neg_ |= bit;
      }
      pos_[i] = from[i];
      quot_[i] = d / n_;
      rem_[i] = uint16_t(d % n_);
      acc_[i] = uint16_t(n_ / 2);
    }
  }
  // Out of line: one copy of each 64-bit operation is far smaller on the AVR.
  __attribute__((noinline)) static int64_t dot2(int32_t a, int32_t b, int32_t c, int32_t d) {
    return int64_t(a) * b + int64_t(c) * d;
  }
  __attribute__((noinline)) static float length(int32_t a, int32_t b) {
    return sqrtf(float(dot2(a, a, b, b)));
  }
  // Every point of a circle of radius r around c within int32 (2147480000 = 2^31 - 3648).
  __attribute__((noinline)) static bool inside(int32_t c, float r) {
    return fabsf(float(c)) + r < 2147480000.0f;
  }
  // v / 2^30 = whole + the result: whole rounded to nearest, the result in [-0.5, 0.5). Taken
  // from the two words of 4 v (|v| < 2^61): avr-gcc makes every constant 64-bit shift a loop.
  __attribute__((noinline)) static float split(int64_t v, int32_t& whole) {
    const int64_t twice = v + v;
    const uint64_t u = uint64_t(twice + twice);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    union {
      uint64_t all;
      uint32_t word[2];
    } w;
    w.all = u;
    const int32_t low = int32_t(w.word[0]), high = int32_t(w.word[1]);
#else
    const int32_t low = int32_t(uint32_t(u)), high = int32_t(uint32_t(u >> 32));
#endif
    whole = high + (low < 0);
    return float(low) * (1 / 4294967296.0f);
  }
  static int32_t nearest(float v) { return int32_t(v < 0 ? v - 0.5f : v + 0.5f); }
  // The lattice point nearest the circle through (xw + xp, yw + yp) across it, x being the
  // axis nearer the tangent (the smaller coordinate): x rounded (the result, an offset from
  // xw), the point moved along the circle onto that grid line, y rounded (`y_near`, from yw).
  // On a circle y^2 changes by -dx (2 x + dx) when x moves by dx.
  __attribute__((noinline)) static int32_t snap(int32_t xw, float xp, int32_t yw, float yp, int32_t& y_near) {
    const int32_t xn = nearest(xp);
    const float dx = float(xn) - xp, x = float(xw) + xp, y = float(yw) + yp;
    const float change = -dx * (2 * x + dx), ya = fabsf(y), yy = ya * ya + change;
    if (yy > 0) {
      const float dy = change / (ya + sqrtf(yy));
      yp += y < 0 ? -dy : dy;
    }
    y_near = nearest(yp);
    return xn;
  }
  static uint32_t magnitude(int32_t v) { return v < 0 ? 0u - uint32_t(v) : uint32_t(v); }

  int32_t pos_[N] = {};    // point k, before the plane axes are replaced
  uint32_t quot_[N] = {};  // |to - from| / n
  uint16_t rem_[N] = {};   // |to - from| % n
  uint16_t acc_[N] = {};   // remainder of |to - from| k + n / 2
  int32_t centre_[2] = {};
  int32_t start_[2] = {};  // start - centre
  float step_ = 0;         // sweep / n, radians, negative clockwise
  float grow_ = 0;         // (r1 - r0) / (r0 n)
  uint16_t n_ = 0, k_ = 0;
  uint8_t neg_ = 0;        // axes that move backwards
  uint8_t plane_[2] = {};
};

}  // namespace am
