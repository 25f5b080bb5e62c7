// Electronic leadscrew follower: spindle counts in, leadscrew counts out, at
// an exact rational ratio, with no accumulated error.
//
// Contract
//   Ratio num/den = leadscrew counts per spindle count, 1 <= den <= kMaxDen
//   (num may be anything a uint32_t holds, so ratios above 1 work: the whole
//   part is added on every edge and only the fraction is carried).
//   After reset(ratio, reversed, phase), with s = forward spindle edges minus
//   backward ones since the reset and phi = phase.num / phase.den spindle
//   counts, position() is exactly
//       floor( lambda (s - phi))      (reversed = false)
//       floor(-lambda (s - phi))      (reversed = true: left hand, or a
//                                      leadscrew wired the other way)
//   for every s, however long the run and however often the spindle reverses:
//   the state is position + residual / den, the exact value, not an estimate.
//   position() is a 32-bit count that wraps modulo 2^32 (2^31 counts is
//   8.7 km of carriage travel at the seed's 4.07 um per count).
//
// Integer width (the choice ratio.h approximates against)
//   residual < den <= 2^31 and every per-edge fraction is below den, so
//   residual + fraction < 2^32: the update is 32-bit adds, one compare and a
//   conditional subtract, never a multiplication, a division, a loop or a
//   table. State: 28 bytes whatever the ratio (the seed stored one list node
//   per unit of the denominator, which is what capped it at 150).
//
// Per edge, worst case, one code path for both directions: backward is the
// same update with -lambda = (-whole - 1) + (den - rem) / den, precomputed at
// reset. Operations: pick the step for the direction, one 32-bit add of the
// whole part to the position, one 32-bit add of the fraction to the
// residual, one 32-bit compare with den and, on a carry, one 32-bit subtract
// and one 32-bit increment. Measured on the ATmega16 (avr-g++ 5.4 -Os, inside
// an INT1 handler): 165 cycles worst case including interrupt entry and the
// register saves, docs/lathe.md.
//
// Multi-start threads
//   Start k of n begins k/n of a turn later than start 0: phi = k C / n for C
//   spindle counts per turn (start_phase()). When n does not divide k C the
//   follower works in a finer unit instead of rounding the phase: den is
//   scaled by phase.den (n / gcd(k C, n)), so the residual counts 1/(den
//   phase.den) of a leadscrew count and the offset lambda phi is held
//   exactly. reset() refuses (returns false) when den phase.den > kMaxDen or
//   lambda phi does not fit the position; ratio.h keeps den small enough for
//   every start of the requested thread. With reset() at the spindle index,
//   position() is negative until the spindle reaches the start's phase: the
//   controller holds the carriage until position() >= 0.
#pragma once
#include <stdint.h>

#include "rational.h"
#include "wide.h"

namespace am {

constexpr uint32_t kMaxDen = uint32_t(1) << 31;

struct Ratio {
  uint32_t num;  // leadscrew counts ...
  uint32_t den;  // ... per this many spindle counts
};

struct Phase {
  uint32_t num;  // spindle counts after the reset point, num / den
  uint32_t den;
};

// Spindle phase of start k of n (0 <= k < n) with C counts per turn:
// k C / n, reduced.
inline Phase start_phase(uint8_t k, uint8_t n, uint16_t counts_per_turn) {
  const uint32_t kc = uint32_t(k) * counts_per_turn;
  const uint32_t g = gcd32(kc, n);  // n >= 1, so g >= 1
  return {kc / g, n / g};
}

class Follower {
 public:
  bool reset(const Ratio& r, bool reversed, Phase phase = {0, 1}) {
    if (r.den == 0 || phase.den == 0) return false;
    U128 den = u128(r.den), t = u128(r.num), t_rem;
    mul_small(den, phase.den);
    if (!fits32(den) || den.w[0] > kMaxDen) return false;
    // lambda phi = num phi_n / (den phi_d): whole counts t, fraction rem / den.
    mul_small(t, phase.num);
    divmod(t, den, t, t_rem);
    if (!fits32(t) || t.w[0] >= (uint32_t(1) << 31)) return false;
    const uint32_t whole_offset = t.w[0], frac_offset = t_rem.w[0];
    const uint32_t whole = r.num / r.den, rem = (r.num % r.den) * phase.den;
    den_ = den.w[0];
    // -lambda = (-whole - 1) + (den - rem) / den when rem != 0, so both
    // directions are the same add-and-carry; reversed swaps the two entries.
    Step& plus = step_[reversed ? 0 : 1];
    Step& minus = step_[reversed ? 1 : 0];
    plus.whole = whole;
    plus.rem = rem;
    minus.whole = 0u - whole - (rem ? 1u : 0u);
    minus.rem = rem ? den_ - rem : 0u;
    // Value at s = 0: -lambda phi (forward), +lambda phi (reversed).
    if (reversed) {
      pos_ = whole_offset;
      residual_ = frac_offset;
    } else if (frac_offset) {
      pos_ = 0u - whole_offset - 1u;
      residual_ = den_ - frac_offset;
    } else {
      pos_ = 0u - whole_offset;
      residual_ = 0;
    }
    return true;
  }

  // One spindle edge; spindle_forward is the direction the encoder decoded.
  void edge(bool spindle_forward) { move(spindle_forward ? step_[1] : step_[0]); }
  void advance() { edge(true); }   // as a forward spindle count
  void retreat() { edge(false); }  // as a backward spindle count

  // What the next edge in that direction will add to position(), without
  // making it: a controller issues those steps first and runs edge() after
  // (the lathe's spindle vector: docs/lathe.md). Same arithmetic as move().
  int32_t next_delta(bool spindle_forward) const {
    const Step& s = step_[spindle_forward ? 1 : 0];
    return int32_t(s.whole + (residual_ + s.rem >= den_ ? 1u : 0u));
  }

  int32_t position() const { return int32_t(pos_); }
  // The exact fractional part: residual() / denominator() of a count.
  uint32_t residual() const { return residual_; }
  uint32_t denominator() const { return den_; }

 private:
  // The lathe's spindle vectors in assembly read the position by its offset
  // and their set-up the steps (firmware/apps/lathe/spindle_vectors.h).
  friend struct FollowerVectorAccess;

  struct Step {
    uint32_t whole;  // added to the position (mod 2^32)
    uint32_t rem;    // added to the residual, < den_
  };

  void move(const Step& s) {
    uint32_t p = pos_ + s.whole;
    uint32_t r = residual_ + s.rem;  // < 2 den_ <= 2^32: no overflow
    if (r >= den_) {
      r -= den_;
      ++p;
    }
    residual_ = r;
    pos_ = p;
  }

  uint32_t pos_ = 0;
  uint32_t residual_ = 0;  // 0 <= residual_ < den_
  uint32_t den_ = 1;
  Step step_[2] = {{0, 0}, {0, 0}};  // [spindle_forward]
};

}  // namespace am
