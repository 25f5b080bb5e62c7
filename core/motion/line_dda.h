// Multi-axis linear DDA (Bresenham): a block that moves up to eight axes in a
// fixed ratio, one event at a time, ending exactly on its target step.
//
// Contract
//   start(delta) plans a block of N = max_i |delta[i]| events (the dominant
//   axis steps at every one of them). next() yields each event: the axes that
//   step (bit i = axis i) and their directions (bit i set = forward, from the
//   sign of delta[i]; constant over the block). After event e (1 <= e <= N)
//   axis i has made exactly
//       p_i(e) = floor((e |delta_i| + h) / N)      h = floor(N / 2)
//   steps, i.e. its position rounded to the nearest step of the ideal line
//   e |delta_i| / N (ties, possible only for even N, round up). So every
//   axis stays within 0.5 step of the straight line at every event, its k-th
//   step falls on event ceil((k N - h) / |delta_i|), no axis steps twice in
//   one event, and p_i(N) = |delta_i| exactly: the block ends on its target.
//
//   start(delta, shift) runs the same line over N 2^shift events, every axis
//   a minor in late phase (below): the smoothing of core/motion/amass.h,
//   where the dominant axis steps on every 2^shift-th event.
//
//   start(delta, events, phase) does the same over a given number of events
//   N >= max |delta| (each axis is then a "minor" of an outside clock): that
//   is how axes ride along another interpolator's events (the linear axes of
//   a helix on the arc's events, core/motion/arc_dda.h), and with
//   DdaPhase::late (h = 0: the k-th step on event ceil(k N / |delta|)) it is
//   the seed printer's DDA (seed-002 §3: N = round(sqrt(A^2 + B^2)), one
//   iteration per BLU of path), whose pulse lists the host tests reproduce.
//
// Why this form
//   Per event and axis: one subtraction, a sign test, and on a step one
//   addition. No division, no multiplication, no 64-bit arithmetic: the
//   accumulator a_i = N - 1 - ((e |delta_i| + h) mod N) lives in [0, N) and
//   is decremented by |delta_i|; it goes negative exactly when p_i
//   increments. A sign test is one bit on the AVR (a 32-bit compare would be
//   four instructions). Division happens only in seek(), a setup call.
//
// Cost (ATmega32, avr-gcc 5.4 -Os, measured in simavr with next() inlined
// into its caller): 74 cycles an event for a dominant axis and one minor, 80
// with two idle axes besides, 142 for a dominant and three minors, about 110
// for two minors of an outside clock; an axis that steps at every event or
// never costs one bit test. RAM 45 bytes (4 axes), flash about 0.9 KB.
//
// Limits: |delta_i| and N <= 2^31 - 1 (INT32_MIN is rejected); N = 0 (all
// deltas zero) is a valid empty block. Host and avr-g++ 5.4; no allocation.
#pragma once
#include <stdint.h>
#include "step_event.h"

namespace am {

// Where in each event period a minor axis steps.
//   nearest: Bresenham rounding; every axis within 0.5 step of the line.
//   late:    the step comes at the first event its accumulator overflows
//            (seed-002's DDA); up to 1 step behind the line.
enum class DdaPhase : uint8_t { nearest, late };

template <uint8_t Axes>
class LineDda {
  static_assert(Axes >= 1 && Axes <= 8, "LineDda drives 1..8 axes (one bit each in StepEvent)");

 public:
  static constexpr uint32_t kMaxCount = 0x7FFFFFFFul;
  static constexpr int32_t kInt32Min = -0x7FFFFFFFl - 1;

  // A block with N = max |delta| events and Bresenham (nearest) phase.
  bool start(const int32_t (&delta)[Axes]) { return begin(delta, 0, DdaPhase::nearest, 0); }

  // The same line over N 2^shift events (shift 0: start(delta)), every axis
  // a minor in late phase when shift > 0: the smoothing of
  // core/motion/amass.h. The caller keeps N 2^shift within kMaxCount.
  bool start(const int32_t (&delta)[Axes], uint8_t shift) {
    return begin(delta, 0, shift ? DdaPhase::late : DdaPhase::nearest, shift);
  }

  // A block over `events` events (0 = the dominant count). Returns false, and
  // leaves an empty block, when a delta is INT32_MIN or events is nonzero and
  // smaller than the largest |delta| or above kMaxCount.
  bool start(const int32_t (&delta)[Axes], uint32_t events, DdaPhase phase) { return begin(delta, events, phase, 0); }

  // Puts the block at event `e` (0 <= e <= events()): the state it has after
  // e calls of next(). For resuming a block part-way and for tests; it
  // divides (64-bit), so it belongs in the main loop.
  void seek(uint32_t e) {
    if (e > uint32_t(events_)) e = uint32_t(events_);
    const uint64_t n_events = uint32_t(events_);
    const uint64_t h = phase_ == DdaPhase::nearest ? n_events / 2 : 0;
    for (uint8_t i = 0; i < Axes; ++i) {
      const uint64_t r = n_events ? (uint64_t(e) * uint32_t(count_[i]) + h) % n_events : 0;
      acc_[i] = n_events ? int32_t(n_events - 1 - r) : 0;
    }
    remaining_ = uint32_t(events_) - e;
  }

  // Steps axis i has made after event e (0 <= e <= events()): p_i(e) of
  // the contract, in closed form (64-bit; for the main loop, which counts
  // where the motors are while the interrupt steps).
  __attribute__((noinline)) uint32_t steps_after(uint8_t axis, uint32_t e) const {
    const uint64_t n_events = uint32_t(events_);
    if (n_events == 0) return 0;
    const uint64_t h = phase_ == DdaPhase::nearest ? n_events / 2 : 0;
    return uint32_t((uint64_t(e) * uint32_t(count_[axis]) + h) / n_events);
  }
  uint32_t events() const { return uint32_t(events_); }
  uint32_t remaining() const { return remaining_; }
  bool finished() const { return remaining_ == 0; }
  // Steps axis i makes over the whole block (|delta_i|).
  uint32_t count(uint8_t axis) const { return uint32_t(count_[axis]); }
  uint8_t dominant() const { return dominant_; }
  uint8_t dirs() const { return dirs_; }

  // The next event; call only while !finished().
  StepEvent next() {
    uint8_t axes = always_;
    minors(axes, events_, Idx<0>());
    --remaining_;
    return StepEvent{axes, dirs_};
  }

 private:
  // The starts' common part: `events` 0 stands for the dominant count
  // times 2^shift.
  bool begin(const int32_t (&delta)[Axes], uint32_t events, DdaPhase phase, uint8_t shift) {
    uint32_t dominant = 0;
    uint8_t dirs = 0;
    for (uint8_t i = 0; i < Axes; ++i) {
      if (delta[i] == kInt32Min) return fail();
      const uint32_t n = delta[i] < 0 ? uint32_t(-delta[i]) : uint32_t(delta[i]);
      count_[i] = int32_t(n);
      if (delta[i] > 0) dirs |= uint8_t(1u << i);
      if (n > dominant) {
        dominant = n;
        dominant_ = i;
      }
    }
    if (events == 0) events = dominant << shift;
    if (events < dominant || events > kMaxCount) return fail();
    events_ = int32_t(events);
    dirs_ = dirs;
    phase_ = phase;
    const int32_t first = events ? int32_t(events - 1 - (phase == DdaPhase::nearest ? events / 2 : 0)) : 0;
    for (uint8_t i = 0; i < Axes; ++i) acc_[i] = first;
    remaining_ = events;
    classify();
    return true;
  }

  // Compile-time unrolled walk over the minor axes (an axis that steps at
  // every event, e.g. the dominant one, and an idle axis cost one bit test).
  template <uint8_t I>
  struct Idx {};
  void minors(uint8_t&, int32_t, Idx<Axes>) {}
  template <uint8_t I>
  void minors(uint8_t& axes, int32_t n, Idx<I>) {
    if (minor_mask_ & (1u << I)) {
      int32_t a = acc_[I] - count_[I];
      if (a < 0) {
        a += n;
        axes |= uint8_t(1u << I);
      }
      acc_[I] = a;
    }
    minors(axes, n, Idx<I + 1>());
  }

  void classify() {
    always_ = minor_mask_ = 0;
    for (uint8_t i = 0; i < Axes; ++i) {
      if (count_[i] == 0) continue;
      if (count_[i] == events_) always_ |= uint8_t(1u << i);
      else minor_mask_ |= uint8_t(1u << i);
    }
  }

  bool fail() {
    for (uint8_t i = 0; i < Axes; ++i) count_[i] = 0, acc_[i] = 0;
    events_ = 0;
    remaining_ = 0;
    dirs_ = 0;
    dominant_ = 0;
    always_ = minor_mask_ = 0;
    return false;
  }

  int32_t acc_[Axes] = {};
  int32_t count_[Axes] = {};
  int32_t events_ = 0;
  uint32_t remaining_ = 0;
  uint8_t dirs_ = 0;
  uint8_t always_ = 0;      // axes that step at every event (count == events)
  uint8_t minor_mask_ = 0;  // axes that step at some events
  uint8_t dominant_ = 0;
  DdaPhase phase_ = DdaPhase::nearest;
};

}  // namespace am
