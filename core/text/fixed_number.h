// Decimal numbers in fixed point for the text protocols, and the conversions
// the G-code interpreter needs: inch to mm, length to steps, steps to length.
// Integer only (no float on the chip), so the AVR and the host give the same
// answer to the last digit.
//
// Contract
//   parse_fixed(p, frac_digits, out) reads a number at p:
//     [+|-] digits [. [digits]]   or   [+|-] . digits
//   (no blanks inside, no exponent) and stores value * 10^frac_digits in
//   `out`, rounded half away from zero on the first digit beyond frac_digits
//   (4 digits: "0.00005" -> 1, "-0.00005" -> -1, "0.000049999" -> 0). Any
//   number of leading zeros and of further digits is accepted. |out| is at
//   most 2^31 - 1 (kFixedMax); a larger value, also one that only rounding
//   makes larger, is out_of_range, never wrapped. A number without digits
//   ("", "-", ".", "+.") or followed at once by a second '.' is bad. On ok,
//   `p` points just past the number (and `had_point` tells whether it had a
//   decimal point, for words that must be whole); otherwise `p` is unchanged.
//   frac_digits <= 9.
//
//   Lengths are held in kLengthScale units per mm (1/10000 mm = 0.1 um) in an
//   int32: +-214748.3647 mm. A scale is given as steps per metre (uint32, the
//   board descriptor's unit: 80 steps/mm = 80000), so any steps/mm with three
//   decimals is exact.
//     inch_to_length(in, out)          in: 1/10000 inch; out = round(in * 25.4)
//                                      (1 inch = 25.4 mm exactly)
//     length_to_steps(len, spm, out)   out = round(len * spm / 10^7)
//     steps_to_length(steps, spm, out) out = round(steps * 10^7 / spm), spm > 0
//     scale_round(v, num, den, out)    out = round(v * num / den), den > 0
//   All round half away from zero and return false (out untouched) when the
//   result would not fit an int32 with |out| <= kFixedMax.
//
//   format_fixed(buf, v, frac_digits) writes v / 10^frac_digits with exactly
//   frac_digits decimals ("-12.3400" for -123400 at 4, "0.0005" for 5) and a
//   NUL, and returns the length: at most 12 characters plus the NUL, so
//   buf[13] always suffices (frac_digits <= 9).
//
// Cost on the AVR: parsing is 32-bit only (one multiply by 10 per digit).
// scale_round and the conversions use one 32x32->64 multiply and one 64-bit
// division (libgcc's __udivdi3); figures in docs/gcode.md.
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace am {

constexpr int32_t kFixedMax = 2147483647;     // |value| limit of every fixed-point number
constexpr uint8_t kLengthDigits = 4;          // fractional digits of a parsed word
constexpr int32_t kLengthScale = 10000;       // length units per mm (0.1 um)

enum class NumberStatus : uint8_t { ok, bad, out_of_range };

namespace fixed_detail {
inline bool digit(char c) { return c >= '0' && c <= '9'; }
}  // namespace fixed_detail

inline NumberStatus parse_fixed(const char*& p, uint8_t frac_digits, int32_t& out, bool& had_point) {
  using fixed_detail::digit;
  const char* q = p;
  bool negative = false;
  if (*q == '+' || *q == '-') negative = (*q++ == '-');
  uint32_t v = 0;
  bool any_digit = false;
  uint8_t kept = 0;       // fraction digits kept in v
  bool point = false;
  bool round_up = false;  // first dropped digit >= 5
  bool dropped = false;   // a fraction digit beyond frac_digits was seen
  bool overflow = false;
  for (;; ++q) {
    const char c = *q;
    if (digit(c)) {
      any_digit = true;
      if (!point || kept < frac_digits) {
        // v * 10 + d stays below 2^32 while v < 429496729; beyond kFixedMax is
        // an overflow whatever follows.
        if (v > uint32_t(kFixedMax) / 10) {
          overflow = true;
        } else {
          v = v * 10 + uint8_t(c - '0');
          if (v > uint32_t(kFixedMax)) overflow = true;
        }
        if (point) ++kept;
      } else if (!dropped) {
        dropped = true;
        round_up = c >= '5';
      }
    } else if (c == '.' && !point) {
      point = true;
    } else {
      break;
    }
  }
  if (!any_digit || *q == '.') return NumberStatus::bad;
  if (overflow) return NumberStatus::out_of_range;
  for (; kept < frac_digits; ++kept) {
    if (v > uint32_t(kFixedMax) / 10) return NumberStatus::out_of_range;
    v *= 10;
  }
  if (round_up && ++v > uint32_t(kFixedMax)) return NumberStatus::out_of_range;
  out = negative ? -int32_t(v) : int32_t(v);
  had_point = point;
  p = q;
  return NumberStatus::ok;
}

inline NumberStatus parse_fixed(const char*& p, uint8_t frac_digits, int32_t& out) {
  bool had_point;
  return parse_fixed(p, frac_digits, out, had_point);
}

// round(v * num / den), half away from zero; false if |result| > kFixedMax.
// Not inlined: one copy of the 64-bit multiply and divide on the AVR.
__attribute__((noinline)) inline bool scale_round(int32_t v, uint32_t num, uint32_t den, int32_t& out) {
  const bool negative = v < 0;
  const uint32_t mag = negative ? 0u - uint32_t(v) : uint32_t(v);
  const uint64_t q = (uint64_t(mag) * num + den / 2) / den;
  if (q > uint64_t(kFixedMax)) return false;
  out = negative ? -int32_t(q) : int32_t(q);
  return true;
}

// 1/10000 inch -> 1/10000 mm: round(in * 25.4).
inline bool inch_to_length(int32_t in, int32_t& out) { return scale_round(in, 254, 10, out); }

inline bool length_to_steps(int32_t length, uint32_t steps_per_m, int32_t& out) {
  return scale_round(length, steps_per_m, 10000000ul, out);
}

inline bool steps_to_length(int32_t steps, uint32_t steps_per_m, int32_t& out) {
  if (steps_per_m == 0) return false;
  return scale_round(steps, 10000000ul, steps_per_m, out);
}

inline uint8_t format_fixed(char* buf, int32_t v, uint8_t frac_digits) {
  char tmp[12];
  uint8_t n = 0;
  uint32_t mag = v < 0 ? 0u - uint32_t(v) : uint32_t(v);
  do {
    tmp[n++] = char('0' + mag % 10);
    mag /= 10;
  } while (mag != 0 || n <= frac_digits);
  uint8_t len = 0;
  if (v < 0) buf[len++] = '-';
  while (n > 0) {
    if (n == frac_digits) buf[len++] = '.';
    buf[len++] = tmp[--n];
  }
  buf[len] = '\0';
  return len;
}

}  // namespace am
