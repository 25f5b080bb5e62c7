// The G-code interpreter's integer arithmetic (gcode_interpreter.h):
// overflow-checked sums, rounded scaling, the words' units (mm and inch to
// 1/10000 mm, M350 mode numbers) and the arc checks (an R arc's centre, an
// I/J/K arc's end on its circle within the tolerance), in 32- and 64-bit
// integers so that host and AVR agree to the bit.
#pragma once
#include <stdint.h>

#include "../math/isqrt.h"
#include "fixed_number.h"
#include "gcode_parser.h"

namespace am {

namespace gcode_detail {

// The helpers below are not inlined: on the AVR one copy of each 64-bit or
// overflow-checked operation is far smaller than avr-gcc's inline expansion.

// a^2 + b^2: below 2^63 for any int32 a, b.
__attribute__((noinline)) inline uint64_t sum_sq(int32_t a, int32_t b) {
  const uint32_t ua = a < 0 ? 0u - uint32_t(a) : uint32_t(a);
  const uint32_t ub = b < 0 ? 0u - uint32_t(b) : uint32_t(b);
  return uint64_t(ua) * ua + uint64_t(ub) * ub;
}

// out = a + b for |a|, |b| <= kFixedMax; false (out untouched) if the sum
// leaves +-kFixedMax (__builtin_add_overflow costs about 80 bytes a use).
__attribute__((noinline)) inline bool add_checked(int32_t a, int32_t b, int32_t& out) {
  const int32_t t = int32_t(uint32_t(a) + uint32_t(b));
  if (((a ^ t) & (b ^ t)) < 0 || t == -kFixedMax - 1) return false;
  out = t;
  return true;
}

// round((a + b) / 2), half away from zero; false if a + b leaves +-kFixedMax.
inline bool half_sum(int32_t a, int32_t b, int32_t& out) {
  int32_t t;
  if (!add_checked(a, b, t)) return false;
  out = t >= 0 ? int32_t((uint32_t(t) + 1) >> 1) : -int32_t((uint32_t(-t) + 1) >> 1);
  return true;
}

// Shifts both left by the same even count until one has bit 62 or 63 set
// (b > 0), so that their square roots keep 31 or more significant bits.
__attribute__((noinline)) inline void normalise(uint64_t& a, uint64_t& b) {
  while (((a | b) >> 62) == 0) {
    a <<= 2;
    b <<= 2;
  }
}

// Arc end-point tolerance in 1/10000 mm: max(0.005 mm, r / 1000), <= 0.5 mm.
inline uint32_t arc_tolerance(uint32_t radius) {
  const uint32_t t = radius / 1000;
  return t < 50 ? 50 : t > 5000 ? 5000 : t;
}

inline bool to_length(int32_t v, bool inches, int32_t& out) {
  if (!inches) {
    out = v;
    return true;
  }
  return inch_to_length(v, out);
}

// kMode* bit of an M350 value (1/10000), 0 if it is no mode.
inline uint8_t mode_bit(int32_t v) {
  if (v < 0 || v % kLengthScale != 0) return 0;
  const int32_t n = v / kLengthScale;
  if (n <= 2) return uint8_t(1u << n);
  if (n == 16 || n == 32 || n == 64) return uint8_t(n / 2);
  return 0;
}

// The centre - start (o[0], o[1]) of an R arc with chord (d[0], d[1]), and
// its radius.
__attribute__((noinline)) inline GcodeError r_arc_centre(const int32_t (&d)[2], int32_t r, bool ccw, int32_t (&o)[2],
                                                         uint32_t& radius) {
  if (r == 0) return GcodeError::arc_zero_radius;
  if (d[0] == 0 && d[1] == 0) return GcodeError::arc_full_circle_r;
  radius = r < 0 ? 0u - uint32_t(r) : uint32_t(r);
  // h = distance of the centre from the chord's middle. The centre is
  // middle + h * (-d[1], d[0]) / chord: left of the chord for a short
  // counter-clockwise arc. p[k] = d[k] * 2h / chord, and
  // 2h / chord = sqrt(4 r^2 - chord^2) / chord.
  const uint64_t d2 = sum_sq(d[0], d[1]);
  uint64_t nn = sum_sq(r, r) << 1;  // 4 r^2 < 2^64
  int32_t p[2] = {0, 0};
  if (nn < d2) {
    const uint32_t chord = isqrt64(d2);  // >= 2 * radius here
    if (chord - 2 * radius > 2 * arc_tolerance(radius)) return GcodeError::arc_radius_too_small;
    radius = chord / 2 + (chord & 1);  // a half circle
  } else {
    nn -= d2;
    uint64_t dd = d2;
    normalise(nn, dd);
    const uint32_t hs = isqrt64(nn), cs = isqrt64(dd);
    for (uint8_t k = 0; k < 2; ++k)
      if (!scale_round(d[k], hs, cs, p[k])) return GcodeError::target_out_of_range;
  }
  if (ccw == (r > 0)) p[1] = -p[1];
  else p[0] = -p[0];
  // o = (d + (-p[1], p[0])) / 2 for the short counter-clockwise arc.
  if (!half_sum(d[0], p[1], o[0]) || !half_sum(d[1], p[0], o[1])) return GcodeError::target_out_of_range;
  return GcodeError::none;
}

// Checks an I/J/K arc: centre - start o, chord d; sets the radius.
__attribute__((noinline)) inline GcodeError offset_arc_check(const int32_t (&d)[2], const int32_t (&o)[2],
                                                             uint32_t& radius) {
  if (o[0] == 0 && o[1] == 0) return GcodeError::arc_zero_radius;
  int32_t e[2];  // end - centre
  for (uint8_t k = 0; k < 2; ++k)
    if (!add_checked(d[k], -o[k], e[k])) return GcodeError::target_out_of_range;
  radius = isqrt64(sum_sq(o[0], o[1]));
  const uint32_t end_radius = isqrt64(sum_sq(e[0], e[1]));
  const uint32_t diff = end_radius > radius ? end_radius - radius : radius - end_radius;
  return diff > arc_tolerance(radius) ? GcodeError::arc_radius_mismatch : GcodeError::none;
}

}  // namespace gcode_detail

}  // namespace am
