// Exact trapezoid profile for one planner block, as runs of equal timer
// intervals for the step queue. Runs in the main loop, in single-precision
// float (avr-libc's float routines are small).
//
// Contract
//   start(block, tick_hz) takes a block of N events (steps of its dominant
//   axis) and its speeds; next_run() then hands the block out as StepRuns
//   {interval ticks, count}, and {0, 0} once all N events are out. Time 0
//   is the previous block's last event (or the start from rest); event e
//   (1..N) comes after the sum of the intervals handed out up to it.
//   events_done() counts the events handed out so far.
//
//   The ideal motion starts at x = 0 with speed `entry`, accelerates at
//   `accel` to the cruise speed, cruises, and decelerates at `accel` to reach
//   x = N at speed `exit`; a block too short for the cruise is a triangle.
//   The cruise speed is tick_hz / c with c = ceil(tick_hz / cruise), exact:
//   no interval is ever shorter than c ticks, so no step is faster than
//   `cruise`; entry and exit are capped at that speed. An exit the block
//   cannot reach is changed: too high, it is lowered to what accelerating all
//   the way reaches; too low (entry^2 > exit^2 + 2 accel N: float rounding
//   upstream), the block decelerates from its entry all the way and ends
//   faster (the entry is never raised). exit_speed() is the ideal motion's
//   speed at event N, the next block's entry (exactly `exit` when it is
//   reachable).
//
//   Every event comes within 3/16 event of the ideal motion at its actual
//   tick, plus half a tick at each end of its run, a few percent for the
//   speed change over a run, and float rounding: 0.206 measured,
//   docs/profile.md. The last event of every run, so the block's last
//   event too, lands within half a tick of its ideal time (plus float
//   rounding): chained blocks do not drift apart from their ideal chain.
//   start() refuses a block (returns false, changes nothing) with no events
//   or more than 2^24, a speed or accel that is negative, not finite or
//   (cruise, accel) zero, tick_hz 0, a cruise slower than one event per
//   kMaxSegmentInterval ticks, or an accel so low that the first event from
//   rest, tick_hz sqrt(2 / accel) ticks, would not fit one interval
//   (accel < 2 (tick_hz / 2^24)^2).
//
// Why
//   Runs, not intervals: a queue slot holds a run, and the planner has no
//   time to spend per event. Each ramp run of k events is planned once, in
//   float: it is aimed at the exact ideal time of its last event from the
//   tick actually reached (late_ carries the difference, at most half a
//   tick), so rounding never adds up. Its T ticks, rounded to the tick, are
//   handed out as parts of q and q + 1 ticks (q = T / k, r = T - q k events
//   at q + 1), one part per next_run() call, the later ones with integer
//   work only. Two parts, k - r then r, would be exact at the run's end but
//   (k - r) r / k ticks off the straight line at the bend: up to k / 4
//   ticks, half an event for a 200-event run at 100 ticks an interval. So
//   the parts alternate, each as long as a window allows: the partial sums
//   stay between the straight line and 3/16 of an interval on the side where
//   the ideal motion is. That side is later while accelerating (the ideal
//   intervals shrink over the run: long intervals first) and earlier while
//   decelerating (short ones first). A run of duration tau deviates from the
//   ideal motion by accel tau^2 / 8 at most, always on that side, kept at
//   kBand = 3/16 event: so neither the window nor the chord costs more than
//   3/16 event, whatever the run's length, which only the chord (and 65535)
//   bounds. Two parts are enough while r (k - r) / k <= 3/16 interval; the
//   parts per run grow with k / interval.
//
//   The cruise is runs of exactly c ticks, each of fewer than 2^17 ticks
//   (65535 >> floor(log2 c) events, at least one), or 2^(17 - h) after
//   shorten_cruise(h): the ideal cruise speed tick_hz / c makes it exact,
//   and a feed hold, which can only change what is not queued yet, waits
//   less than that (8.2 ms at 16 MHz, 2 ms with h = 2) per queued cruise
//   segment.
//
//   No time is ever absolute (a block can last hours at a low speed): a
//   ramp run lasts 2 k / (w1 + w2) between the speeds at its ends, with
//   w^2 = v^2 + 2 accel d at the distance d from the ramp's slow end (the
//   block's start when accelerating, its end when decelerating), with no
//   cancellation anywhere; the one event across a phase boundary adds up its
//   pieces. A planned ramp run costs one sqrt, one division and 15 other
//   float operations (about 3800 cycles on the AVR, its first part
//   included), a later part about 550 (a 16-step division), a cruise run
//   270.
//
//   The chip's schedule must be recomputed bit for bit on the host (the
//   simulator tests do): x86-64 g++ or clang with SSE float, and avr-gcc 5.4
//   with avr-libc's float routines, give the same results because every
//   float value is made by + - * /, sqrtf and conversions, each correctly
//   rounded on both, from float literals only (a double literal is float on
//   the AVR but not on the host), in one fixed order, and nothing else.
//   So: no fmaf, no library function whose rounding may differ, no x87
//   (refused below), no -ffast-math, and no a * b + c fused into one
//   rounding: the pragmas below switch contraction off for this header on
//   hosts with FMA (GCC contracts by default in GNU mode).
#pragma once
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include "speed_ramp.h"
#include "step_queue.h"

#if defined(__FLT_EVAL_METHOD__) && __FLT_EVAL_METHOD__ != 0
#error "trapezoid.h: float must be evaluated in float (SSE, not x87) to match the AVR bit for bit"
#endif
#ifdef __FAST_MATH__
#error "trapezoid.h: -ffast-math changes float results; the AVR schedule could not be recomputed"
#endif
#if defined(__clang__)
#pragma float_control(push)
#pragma clang fp contract(off)
#elif defined(__GNUC__) && !defined(__AVR__)
#pragma GCC push_options
#pragma GCC optimize("fp-contract=off")
#endif

namespace am {

struct TrapezoidBlock {
  uint32_t events;  // N >= 1: steps of the block's dominant axis
  float entry;      // events/s at the block's start, >= 0
  float cruise;     // events/s, top speed, > 0
  float exit;       // events/s at the block's end, >= 0
  float accel;      // events/s^2, > 0, used both for speeding up and slowing down
};

struct TrapezoidProbe;  // tests only: reads the private state

namespace trapezoid_detail {
inline float root(float x) { return sqrtf(x); }
inline uint32_t bits(float x) {
  uint32_t u;
  __builtin_memcpy(&u, &x, sizeof u);
  return u;
}
// a < b for a or b >= +0 (-0 counts as below +0): the bits in integer order.
inline bool less(float a, float b) { return int32_t(bits(a)) < int32_t(bits(b)); }
#ifndef __AVR__
inline long double root(long double x) { return sqrtl(x); }
inline bool less(long double a, long double b) { return a < b; }
#endif
}  // namespace trapezoid_detail

// Real is float on the chip; the tests also run it in long double to
// separate float rounding from the method's own error.
template <typename Real>
class BasicTrapezoidRuns {
 public:
  static constexpr uint32_t kMaxEvents = uint32_t(1) << 24;  // positions exact in float

  [[gnu::noinline]] bool start(const TrapezoidBlock& b, uint32_t tick_hz) {
    if (!valid(b)) return false;
    const uint32_t c = whole_ticks(tick_hz, bits(b.cruise));
    const Real f = Real(tick_hz);
    // The first event from rest, f sqrt(2 / accel) ticks, fits a segment.
    if (!c || less(Real(b.accel), f * f * kFirstEventScale)) return false;

    n_ = b.events;
    c_ = c;
    cruise_run_ = uint16_t(0xFFFF >> shorter_);  // 2^16 / 2^floor(log2 c) events: 2^16 .. 2^17 ticks
    for (uint32_t t = c; t >>= 1;) cruise_run_ >>= 1;
    if (!cruise_run_) cruise_run_ = 1;
    done_ = 0;
    left_[0] = left_[1] = 0;
    late_ = 0;
    two_f_ = f + f;
    two_a_ = Real(b.accel) + Real(b.accel);
    h_ = 1 / two_a_;
    tau_ = root(h_ * kTauSqOverH);
    peak_ = f / Real(c);  // the top speed, for now
    w_ = less(Real(b.entry), peak_) ? Real(b.entry) : peak_;
    exit_ = less(Real(b.exit), peak_) ? Real(b.exit) : peak_;
    lowered_ = false;
    // The same code for both ramps and for the triangle and the trapezoid.
    const Real rise = span(w_, exit_);
    tail_[0] = ramp_length(w_, rise);
    tail_[1] = ramp_length(exit_, -rise);
    v0sq_ = w_ * w_;
    v1sq_ = exit_ * exit_;
    const Real peak_sq = v0sq_ + two_a_ * tail_[0];
    if (lowered_) {  // the exit cannot be reached: one ramp all the way
      v1sq_ = positive_part(peak_sq - two_a_ * tail_[1]);
      exit_ = root(v1sq_);
    }
    peak_ = root(peak_sq);
    // The ramps end inside events edge_[0] (from the start) and edge_[1]
    // (from the end); tail_ becomes the part of that event in the ramp.
    for (uint8_t j = 0; j < 2; ++j) {
      const uint32_t e = uint32_t(tail_[j]);
      const Real t = tail_[j] - Real(e);
      edge_[j] = e;
      tail_[j] = 1;
      if (less(0, t)) {
        edge_[j] = e + 1;
        tail_[j] = t;
      }
    }
    return true;
  }

  // Not inlined: its caller keeps the runs in a global, whose fields it would
  // reach by absolute address (4-byte LDS/STS) instead of through `this`
  // (about 70 bytes on the AVR images).
  [[gnu::noinline]] StepRun next_run() {
    if (!(left_[0] | left_[1])) {
      const uint32_t left = n_ - done_;
      if (left == 0) return StepRun{0, 0};
      if (done_ >= edge_[0] && left > edge_[1]) {  // cruise: exact, late_ stays as it is
        uint32_t k = left - edge_[1];
        if (k > cruise_run_) k = cruise_run_;
        done_ += k;
        return StepRun{c_, uint16_t(k)};
      }
      plan(left);
    }
    // The next part of the run planned: events of kind i (base_ + i ticks),
    // as many as room_ allows (k-scaled ticks the partial sums may still move
    // toward that kind's side of the window), or all the kind has left.
    uint8_t i = kind_;
    if (!left_[i]) {
      i ^= 1;
      room_ = width_ - room_;
    }
    uint16_t len = left_[i];
    const uint16_t step = step_[i];
    if (uint32_t(len) * step > room_) len = quotient(room_, step);
    left_[i] -= len;
    room_ = width_ - (room_ - uint32_t(len) * step);
    kind_ = i ^ 1;
    done_ += len;
    return StepRun{base_ + i, len};
  }

  Real exit_speed() const { return exit_; }
  uint32_t events_done() const { return done_; }
  uint32_t events_left() const { return n_ - done_; }
  // Cruise runs of blocks started from now on last under 2^(17 - halvings)
  // ticks (0..8): shorter runs, and a feed hold waits less for the queue.
  void shorten_cruise(uint8_t halvings) { shorter_ = halvings; }
  // Every part of the planned run handed out: start() may take over
  // from event events_done() (a feed hold does, firmware/engine/path.cpp).
  bool between_runs() const { return !(left_[0] | left_[1]); }

 private:
  friend struct TrapezoidProbe;
  static constexpr Real kBand = Real(0.1875f);       // chord deviation, events: 3/16, the window's width
  static constexpr Real kBulge = 4 * kBand;          // accel tau_^2 / 2: the ramp's distance beyond w tau_
  static constexpr Real kTauSqOverH = 16 * kBand;    // tau_^2 = 8 kBand / accel = 16 kBand h_
  static constexpr Real kFirstEventScale = Real(1.0f / 140737488355328.0f);  // 2^-47: accel >= f^2 2^-47

  static Real root(Real x) { return trapezoid_detail::root(x); }
  static bool less(Real a, Real b) { return trapezoid_detail::less(a, b); }
  static uint32_t bits(float x) { return trapezoid_detail::bits(x); }
  [[gnu::noinline]] static Real positive_part(Real x) { return less(0, x) ? x : 0; }

  // 1 <= N <= kMaxEvents, every speed finite and >= 0 (-0 too), cruise and
  // accel > 0: one check per speed, in a loop over the four.
  static bool valid(const TrapezoidBlock& b) {
    static_assert(offsetof(TrapezoidBlock, cruise) == offsetof(TrapezoidBlock, entry) + 4 &&
                      offsetof(TrapezoidBlock, exit) == offsetof(TrapezoidBlock, entry) + 8 &&
                      offsetof(TrapezoidBlock, accel) == offsetof(TrapezoidBlock, entry) + 12,
                  "the speeds are checked as four consecutive floats");
    uint32_t u[4];  // entry, cruise, exit, accel
    __builtin_memcpy(u, reinterpret_cast<const char*>(&b) + offsetof(TrapezoidBlock, entry), sizeof u);
    for (uint8_t i = 0; i < 4; ++i) {
      uint32_t x = u[i];
      if (x == 0x80000000u) x = 0;                           // -0
      if (x >= 0x7F800000u || (!x && (i & 1))) return false;  // negative, not finite, or a zero cruise or accel
    }
    return b.events - 1 < kMaxEvents;
  }

  // ceil(f / v), exact, for v > 0 given by its bits: v = m 2^e with m its
  // 24-bit significand, so f / v is f 2^-e / m, divided bit by bit. 0 when
  // above kMaxSegmentInterval.
  static uint32_t whole_ticks(uint32_t f, uint32_t v) {
    const uint32_t m = (v & 0x7FFFFFu) | 0x800000u;
    uint32_t q = 0, r = 0;
    for (int i = 182 - int(v >> 23); i > 0; --i) {  // the 32 - e bits of f 2^-e
      r = (r << 1) | (f >> 31);  // r < 2m < 2^25
      f <<= 1;
      q <<= 1;
      if (r >= m) {
        r -= m;
        ++q;
      }
      if (q > kMaxSegmentInterval) return 0;
    }
    q += (r | f) != 0;  // f keeps the bits below 2^e
    return q > kMaxSegmentInterval ? 0 : q;
  }

  // Events of a ramp from speed v: up to the top speed (peak_ holds it for
  // now), or to where it meets the other ramp (rise: the events over which
  // the speed changes from v to the other end's speed), within 0 .. N. Sets
  // lowered_ if the ramp would be longer than the block: the other end's
  // speed cannot be reached.
  [[gnu::noinline]] Real ramp_length(Real v, Real rise) {
    const Real n = Real(n_);
    Real d = (n + rise) * Real(0.5f);
    const Real to_top = span(v, peak_);
    if (less(to_top, d)) d = to_top;
    if (less(n, d)) {
      d = n;
      lowered_ = true;
    }
    return positive_part(d);
  }

  // Events over which the speed changes from v to u (negative if u < v), as
  // (u - v)(u + v) / 2 accel: no cancellation.
  [[gnu::noinline]] Real span(Real v, Real u) const { return (u - v) * (u + v) * h_; }

  // Ideal ticks over len events between speed w and the peak.
  [[gnu::noinline]] Real piece(Real len, Real w) const { return two_f_ * len / (w + peak_); }

  // Plans the next run (a ramp run, or the one event across a phase
  // boundary) and sets up its parts.
  [[gnu::noinline]] void plan(uint32_t left) {
    const int32_t ahead = int32_t(edge_[0] - 1 - done_);  // events left to the acceleration's runs
    const bool accel = ahead > 0, ramp = accel || left < edge_[1];
    uint16_t k = 1;
    if (ramp) {  // as many events as the chord allows
      uint32_t fit = uint32_t(positive_part(w_ * tau_ + (accel ? kBulge : -kBulge)));
      const uint32_t most = accel ? uint32_t(ahead) : left;
      if (fit > most) fit = most;
      if (fit > 0xFFFF) fit = 0xFFFF;
      if (fit) k = uint16_t(fit);
    }
    // The speed at the run's end, d events from its ramp's slow end. An event
    // across a boundary that ends before the deceleration gets a speed past
    // the peak here, which nothing uses: its down piece is 0, and what comes
    // next is a cruise or an event with no acceleration piece.
    const uint32_t d = accel ? done_ + k : left - k;
    const Real w = root((accel ? v0sq_ : v1sq_) + two_a_ * Real(d));
    Real mean;  // ideal ticks per event over the run
    if (ramp) {
      mean = two_f_ / (w_ + w);
    } else {  // the event across a phase boundary: its pieces of ramp, cruise, ramp
      const Real up = done_ < edge_[0] ? tail_[0] : 0, down = left == edge_[1] ? tail_[1] : 0;
      mean = piece(up, w_) + piece(1 - up - down, peak_) + piece(down, w);
    }
    w_ = w;
    // Ticks to the run's last event from the tick actually reached, and
    // their q, r: total / k is within one of the mean (late_ is at most half
    // a tick, except after a clamp below).
    const Real to_go = mean * Real(k) - late_;
    const uint32_t total = uint32_t(positive_part(to_go + Real(0.5f)));
    uint32_t q = uint32_t(mean);
    int32_t r = int32_t(total - times(q, k));
    if (r < 0) {
      --q;
      r += int32_t(k);
    }
    if (r >= int32_t(k)) {
      ++q;
      r -= int32_t(k);
    }
    if (uint32_t(r) >= k) r = 0;  // only after a clamp: late_ takes it
    if (q < c_) {
      q = c_;
      r = 0;
    }
    if (q >= kMaxSegmentInterval) {
      q = kMaxSegmentInterval;
      r = 0;
    }
    late_ = Real(times(q, k) + uint32_t(r)) - to_go;
    // The window: 3/16 of the mean interval, k-scaled (an event at q + 1
    // moves the partial sum (k - r) / k ticks off the straight line, one at
    // q moves it back r / k), at least one tick so that every part gets an
    // event. It starts full for the first kind: long intervals when
    // accelerating, short ones otherwise.
    uint32_t lim = (total * 3) >> 4;
    if (lim < k) lim = k;
    width_ = room_ = lim;
    base_ = q;
    left_[0] = step_[1] = uint16_t(k - uint32_t(r));
    left_[1] = step_[0] = uint16_t(r);
    kind_ = accel;
  }

  // q k, by the 32 x 16 bit multiplication (no 32 x 32 one is linked).
  [[gnu::noinline]] static uint32_t times(uint32_t q, uint16_t k) { return q * k; }

  // num / den for num < den 2^16 (the quotient fits 16 bits).
  static uint16_t quotient(uint32_t num, uint16_t den) {
    uint16_t q = 0;
    uint32_t d = uint32_t(den) << 16;
    for (uint16_t bit = 0x8000; bit; bit >>= 1) {
      d >>= 1;
      if (num >= d) {
        num -= d;
        q |= bit;
      }
    }
    return q;
  }

  // The run being handed out (the most used first: shorter code on the AVR).
  uint32_t room_ = 0, width_ = 0, base_ = 0;
  uint16_t left_[2] = {0, 0};  // events still to go at base_ and at base_ + 1 ticks
  uint16_t step_[2] = {0, 0};  // their k-scaled ticks off the straight line per event
  uint8_t kind_ = 0;           // the kind of the next part
  // The block.
  uint32_t n_ = 0, done_ = 0, c_ = 0;
  uint16_t cruise_run_ = 0;    // events of a cruise run: below 2^(17 - shorter_) ticks
  uint8_t shorter_ = 0;        // halvings of the cruise runs (a feed hold waits for the queue)
  uint32_t edge_[2] = {0, 0};  // the events in which the ramps end, from the start and from the end
  Real w_ = 0;                 // speed at event done_ (after the last run planned)
  Real late_ = 0;              // ticks the last planned run's end is behind its ideal time
  Real two_f_ = 0, two_a_ = 0, v0sq_ = 0, v1sq_ = 0, peak_ = 0;
  Real tau_ = 0;               // seconds: a run this long deviates kBand from the parabola
  Real tail_[2] = {0, 0};      // the part of events edge_ in their ramp
  Real exit_ = 0, h_ = 0;      // h_ = 1 / (2 accel)
  bool lowered_ = false;
};

using TrapezoidRuns = BasicTrapezoidRuns<float>;

}  // namespace am

#if defined(__clang__)
#pragma float_control(pop)
#elif defined(__GNUC__) && !defined(__AVR__)
#pragma GCC pop_options
#endif
