// Look-ahead path planner: a ring of straight blocks whose entry and exit
// speeds are chosen so that a polyline of short segments runs through its
// vertices as fast as the junctions, the feed and the queue allow, instead of
// stopping at every one. Single-precision float, for the main loop only.
// (Method, limits and measured figures: docs/planner.md.)
//
// Contract
//   PathPlanner<N, Size>(axes, deviation_mm, max_event_rate) plans N axes
//   (1..5) in a ring of Size blocks (2..32). axes[i]: steps per mm, top rate
//   (steps/s), top acceleration (steps/s^2), all > 0, and in_path (false for
//   an extruder: its travel is not part of the path unless it moves alone).
//   deviation_mm is grbl's junction deviation, max_event_rate the step
//   generator's top rate of events (steps of a block's dominant axis) per s.
//
//   add(steps, delta_mm, feed, rapid) queues one straight block and replans:
//     steps[i]     signed steps of axis i;
//     delta_mm[i]  the program coordinate's change on axis i, mm, finite: the
//                  path's length L (the norm over the in_path axes, or over
//                  the others when only they move) and its direction. All
//                  zero with steps: taken from steps / steps_per_mm;
//     feed         mm/min along the path, > 0 and finite unless rapid (then
//                  ignored: the limiting axis's rate rules).
//   Result: queued; empty (no axis steps: nothing queued, not an error);
//   full (nothing changed); bad_feed (nothing queued).
//
//   Per block (k = events / L, events per mm of path):
//     cruise  min(feed / 60 * k, max_event_rate, each moving axis i's
//             max_rate[i] * events / |steps[i]|): the nominal speed, events/s.
//             No axis exceeds its rate (counted in the steps it makes, not
//             in mm), nor the dominant axis the event cap.
//     accel   min over moving axes of max_accel[i] * events / |steps[i]|,
//             events/s^2: no axis exceeds its acceleration.
//     junction with the block before, in (mm/s)^2 along the path: grbl's
//             v^2 = a d h / (1 - h), h = sin(theta / 2), theta the angle
//             between the reversed previous direction and this block's, a
//             the largest acceleration along the change of direction that
//             every path axis allows, d the deviation; capped by both blocks'
//             nominal speeds (straight on: the nominal; a reversal: 0).
//             A block that moves no path axis (E alone) starts and ends at
//             rest, and so does the first block after an empty queue or
//             after a queue whose blocks are all taken.
//   Replanning (grbl's method): a reverse pass from the newest block (whose
//   exit is 0: the machine can always stop) and a forward pass, over squared
//   path speeds, each entry at most what the ramps allow both ways with
//   kPlanAccel of the block's acceleration (the rest is the room that float
//   rounding of the events/s conversion needs). Entries only rise as blocks
//   arrive, so an entry at its junction limit or reached at full
//   acceleration is final, and so is every entry before it: add() replans
//   only the blocks after the last final one. The plan equals a plain
//   two-pass from scratch (host-tested).
//
//   The step generator, in the same context as add() (the main loop):
//     take()  the oldest block not yet taken (nullptr if none). Its entry,
//             cruise and exit never change again, and
//               e * e <= x * x + 2.0f * accel * float(events)
//               x * x <= e * e + 2.0f * accel * float(events)
//             hold in float exactly as written (e entry, x exit), with
//             max(e, x) <= cruise; cruise is the nominal speed (a block too
//             short to reach it peaks where its two ramps meet). Where
//             rounding would break that, the exit is lowered, by units in
//             the last place. The next block then enters at exactly that
//             exit converted to its own events, x * (k_next / k), and the
//             planner holds its entry there. Only where the entry cannot
//             slow down to any lower exit (a block of a step or two at
//             speed, whose 2 accel events is below the rounding of entry^2)
//             does the exit rise instead, by the same walk upwards (a few
//             units in the last place; never above the entry), and the next
//             cruise rises with it if it must (by a unit in the last place).
//     done()  the oldest taken block has run: dropped.
//     slow_next_entry(factor)  the block taken last will end factor times
//             its planned exit (a feed hold restarted it from rest): the next
//             block's entry is lowered to match, final, and the blocks after
//             it are replanned.
//   count() includes taken blocks; clear() forgets everything.
//   newest_nominal() is the newest block's nominal speed, mm/s (its feed as
//   the limits hold it). set_steps_per_mm(i, v): axis i's steps per mm changed (a coil axis's
//   excitation mode, at rest); only lengths derived from steps and the
//   junction's acceleration use it. set_limits(i, rate, accel) and
//   set_junction_deviation(mm) change what the constructor was given (the
//   machine's settings, at rest; a printer's M201/M203/M205 at any time:
//   the blocks queued keep theirs); axis(i) is what axis i has now.
//   PathPlanner<N, Size, true>: set_accel_cap(a) caps the acceleration
//   along the path of the blocks added after it at a mm/s^2 (a printer's
//   M204; INFINITY, the default: the axes' limits alone).
//
// Why
//   The all-integer planner this replaces (the former lookahead.h) needed
//   about 13 KB of AVR flash, most of it inline 64-bit arithmetic. In float
//   every operation is one call into avr-libc's small routines: 4.4 KB with
//   them (1.1 KB of library; docs/planner.md has the measurement). Float is
//   allowed because nothing here runs in an interrupt. The plan is kept in
//   path units, (mm/s)^2, because consecutive blocks count different axes at
//   different ratios; a block's events/s are made only when it is taken.
//   Only the newest block's direction is kept, for the next junction.
//   Comparisons are on the floats' bit patterns (every compared value is
//   >= 0), which avr-gcc does inline. No standard library, no allocation;
//   host g++ and avr-gcc 5.4.
//
// Cost (ATmega32 at 16 MHz, avr-gcc 5.4 -Os, simavr; docs/planner.md)
//   add() with replanning, 16-block ring, polylines of 0.1 mm: 12k..18k
//   cycles (mean), take() + done() about 2.6k. RAM: sizeof(PathBlock<N>) =
//   4 N + 20; sizeof(PathPlanner<N, Size>) = Size (4 N + 36) + 17 N + 17
//   bytes on the AVR (917 for 4 axes and 16 blocks).
#pragma once
#include <math.h>
#include <stdint.h>

namespace am {

struct PathAxis {
  float steps_per_mm;  // > 0
  float max_rate;      // steps/s, > 0
  float max_accel;     // steps/s^2, > 0
  bool in_path;        // false for an extruder (E)
};

// What the step generator gets.
template <uint8_t N>
struct PathBlock {
  int32_t steps[N];            // signed steps per axis
  uint32_t events;             // steps of the dominant axis (most steps; the first of equals)
  float entry, cruise, exit;   // events/s; max(entry, exit) <= cruise
  float accel;                 // events/s^2
};

template <uint8_t N, uint8_t Size, bool AccelCap = false>
class PathPlanner {
  static_assert(N >= 1 && N <= 5, "PathPlanner plans 1..5 axes");
  static_assert(Size >= 2 && Size <= 32, "PathPlanner rings hold 2..32 blocks");

 public:
  // The share of each block's acceleration the passes plan with.
  static constexpr float kPlanAccel = 1.0f - 1.0f / 1024;

  enum class Status : uint8_t { queued, empty, full, bad_feed };

  PathPlanner(const PathAxis (&axes)[N], float junction_deviation_mm, float max_event_rate)
      : deviation_(junction_deviation_mm), max_event_rate_(max_event_rate) {
    for (uint8_t i = 0; i < N; ++i) axes_[i] = axes[i];
  }

  Status add(const int32_t (&steps)[N], const float (&delta_mm)[N], float feed_mm_per_min, bool rapid) {
    if (!rapid && !(key(feed_mm_per_min) > 0 && key(feed_mm_per_min) < key(INFINITY))) return Status::bad_feed;
    uint32_t events = 0;
    bool given = false;
    for (uint8_t i = 0; i < N; ++i) {
      const uint32_t m = magnitude(steps[i]);
      if (m > events) events = m;
      given |= nonzero(delta_mm[i]);
    }
    if (events == 0) return Status::empty;
    if (full()) return Status::full;
    const uint8_t at = index(count_);
    Slot& s = slots_[at];
    float mm[N], path = 0, other = 0;
    for (uint8_t i = 0; i < N; ++i) {
      mm[i] = given ? delta_mm[i] : float(steps[i]) / axes_[i].steps_per_mm;
      (axes_[i].in_path ? path : other) += mm[i] * mm[i];
    }
    const bool along = key(path) > 0;
    const float length = sqrtf(along ? path : other);
    s.per_mm = float(events) / length;
    limit(s.out, steps, events, rapid ? INFINITY : feed_mm_per_min / 60 * s.per_mm);
    if (AccelCap) s.out.accel = lesser(s.out.accel, accel_cap_ * s.per_mm);
    s.two_al = 2 * kPlanAccel * (s.out.accel / s.per_mm) * length;
    const float nominal = s.out.cruise / s.per_mm, cap = lesser(nominal, nominal_);
    const float turned = turn(mm, length);
    const bool from_rest = taken_ == count_;
    s.entry = s.max_entry = from_rest || !(along && along_) ? 0 : lesser(cap * cap, turned);
    if (from_rest) planned_ = at;
    along_ = along;
    nominal_ = nominal;
    ++count_;
    replan();
    return Status::queued;
  }

  // An axis's steps per mm changed (an excitation mode, at rest).
  void set_steps_per_mm(uint8_t axis, float steps_per_mm) { axes_[axis].steps_per_mm = steps_per_mm; }
  // An axis's limits (settings, at rest: the blocks planned so far keep
  // theirs) and the junction deviation.
  void set_limits(uint8_t axis, float max_rate, float max_accel) {
    axes_[axis].max_rate = max_rate;
    axes_[axis].max_accel = max_accel;
  }
  void set_junction_deviation(float mm) { deviation_ = mm; }
  // The acceleration along the path of the blocks added from now on,
  // mm/s^2 (INFINITY: the axes' limits alone; a printer's M204).
  void set_accel_cap(float mm_per_s2) { accel_cap_ = mm_per_s2; }
  const PathAxis& axis(uint8_t i) const { return axes_[i]; }

  // The newest block's nominal speed along its path, mm/s: its feed as the
  // axes' limits hold it.
  float newest_nominal() const { return nominal_; }

  bool full() const { return count_ == Size; }
  bool empty() const { return count_ == 0; }
  uint8_t count() const { return count_; }

  const PathBlock<N>* take() {
    if (taken_ == count_) return nullptr;
    const uint8_t at = index(taken_++);
    PathBlock<N>& b = slots_[at].out;
    if (taken_ == count_) {
      b.exit = settle(b, 0, 0, 0);
      return &b;
    }
    const uint8_t next = ahead(at);
    Slot& n = slots_[next];
    const float to_next = n.per_mm / slots_[at].per_mm;
    b.exit = settle(b, sqrtf(n.entry) * slots_[at].per_mm, to_next, n.out.cruise);
    n.out.entry = b.exit * to_next;
    if (key(n.out.entry) > key(n.out.cruise)) n.out.cruise = n.out.entry;  // an exit settle() raised
    if (planned_ == at) planned_ = next;
    return &b;
  }

  void done() {
    if (taken_ == 0) return;
    tail_ = index(1);
    --taken_;  // before count_: taken_ <= count_ at every instant (a probe reads both mid-update)
    --count_;
  }

  void clear() { tail_ = count_ = taken_ = planned_ = 0; }

  // The block taken last ends slower than planned, by `factor` (0 .. 1: a
  // feed hold stopped it and it restarted from rest): the oldest block not
  // taken yet enters that much slower, final, and the rest is replanned.
  void slow_next_entry(float factor) {
    if (taken_ == count_ || !(key(factor) < key(1.0f))) return;
    const uint8_t at = index(taken_);
    Slot& s = slots_[at];
    s.out.entry *= factor;
    s.entry *= factor * factor;
    s.max_entry = s.entry;
    planned_ = at;
    replan();
  }

 private:
  struct Slot {
    PathBlock<N> out;
    float per_mm;     // events per mm of path
    float two_al;     // 2 a L with kPlanAccel of the acceleration, (mm/s)^2
    float max_entry;  // junction limit, (mm/s)^2
    float entry;      // planned entry, (mm/s)^2
  };

  // Comparisons, of floats >= 0 (speeds, squares, limits, INFINITY) except
  // in nonzero(): IEEE bit patterns of such floats order like their values,
  // and the AVR compares 32-bit integers inline where a float comparison is
  // a library call with its operands shuffled into place.
  static int32_t key(float x) {
    int32_t k;
    __builtin_memcpy(&k, &x, sizeof k);
    return k;
  }
  static float value(uint32_t k) {
    float x;
    __builtin_memcpy(&x, &k, sizeof x);
    return x;
  }
  static bool nonzero(float x) { return (uint32_t(key(x)) << 1) != 0; }
  static float lesser(float a, float b) { return key(b) < key(a) ? b : a; }
  static uint32_t magnitude(int32_t v) { return v < 0 ? 0u - uint32_t(v) : uint32_t(v); }

  uint8_t index(uint8_t offset) const {
    const uint8_t i = uint8_t(tail_ + offset);
    return i >= Size ? uint8_t(i - Size) : i;
  }
  static uint8_t ahead(uint8_t i) { return i + 1 == Size ? 0 : uint8_t(i + 1); }
  static uint8_t back(uint8_t i) { return i == 0 ? uint8_t(Size - 1) : uint8_t(i - 1); }

  // The block's steps, events, nominal speed (cruise) and acceleration.
  void limit(PathBlock<N>& out, const int32_t (&steps)[N], uint32_t events, float feed_rate) const {
    float rate = lesser(feed_rate, max_event_rate_), accel = INFINITY;
    for (uint8_t i = 0; i < N; ++i) {
      out.steps[i] = steps[i];
      if (steps[i] == 0) continue;
      const float ratio = float(events) / float(magnitude(steps[i]));
      rate = lesser(rate, axes_[i].max_rate * ratio);
      accel = lesser(accel, axes_[i].max_accel * ratio);
    }
    out.events = events;
    out.entry = out.exit = 0;
    out.cruise = rate;
    out.accel = accel;
  }

  // The junction limit from the newest block's direction (unit_) to this
  // block's, (mm/s)^2, uncapped; unit_ becomes this block's direction (zero
  // when it moves no path axis). With u, w the unit directions, D = |w - u|^2
  // and S = |w + u|^2: h = sqrt(S) / 2, h / (1 - h) = (2 sqrt(S) + S) / D,
  // and the junction acceleration is min_i a_i / |j_i| with j = (w - u) /
  // sqrt(D).
  float turn(const float (&mm)[N], float length) {
    float d = 0, s = 0, a = INFINITY;
    for (uint8_t i = 0; i < N; ++i) {
      const float w = axes_[i].in_path ? mm[i] / length : 0;
      const float change = w - unit_[i], sum = w + unit_[i];
      unit_[i] = w;
      d += change * change;
      s += sum * sum;
      if (nonzero(change)) a = lesser(a, axes_[i].max_accel / (axes_[i].steps_per_mm * fabsf(change)));
    }
    if (key(d) == 0) return INFINITY;  // straight on
    const float root = sqrtf(s);
    return deviation_ * a * (2 * root + s) / sqrtf(d);
  }

  // Reverse pass down to the last final entry, then forward from it.
  [[gnu::noinline]] void replan() {
    const uint8_t newest = index(count_ - 1);
    float next = 0;
    for (uint8_t i = newest; i != planned_; i = back(i)) {
      Slot& s = slots_[i];
      next = s.entry = lesser(s.max_entry, next + s.two_al);
    }
    for (uint8_t i = planned_; i != newest;) {
      const float reach = slots_[i].entry + slots_[i].two_al;
      i = ahead(i);
      Slot& n = slots_[i];
      if (key(reach) < key(n.entry)) {  // full acceleration from a final entry: final
        n.entry = reach;
        planned_ = i;
      } else if (key(n.entry) == key(n.max_entry)) {
        planned_ = i;
      }
    }
  }

  // The exit of taken block b from the plan's: at most b's cruise, lowered
  // until it is feasible from b's entry and, converted to the next block's
  // events, at most its cruise; then, if the entry cannot slow down to it
  // (2 accel events below the rounding of entry^2), raised until it can.
  // Each walk moves the float's bit pattern by 1, 2, 4, ... units in the
  // last place: it stops within twice the distance it had to go, and ends
  // whatever the input (at 0, at the entry).
  static float settle(const PathBlock<N>& b, float exit, float to_next, float next_cruise) {
    const float e2 = b.entry * b.entry, ramp = 2.0f * b.accel * float(b.events), room = e2 + ramp;
    uint32_t at = key(lesser(exit, b.cruise)), step = 1;
    for (float x = value(at); key(x * x) > key(room) || key(x * to_next) > key(next_cruise); x = value(at)) {
      at = at > step ? at - step : 0;
      step += step;
    }
    const uint32_t top = key(b.entry);
    for (step = 1; at < top && key(e2) > key(value(at) * value(at) + ramp); step += step) {
      at = top - at > step ? at + step : top;
    }
    return value(at);
  }

  // The small members first: the AVR reaches 64 bytes past a pointer
  // without arithmetic.
  uint8_t tail_ = 0;     // the oldest block
  uint8_t count_ = 0;    // blocks in the ring, taken ones included
  uint8_t taken_ = 0;    // blocks given to the step generator
  uint8_t planned_ = 0;  // the last block whose entry is final
  bool along_ = false;   // the newest block moves along the path
  float nominal_ = 0;    // the newest block's nominal speed, mm/s
  float deviation_;
  float max_event_rate_;
  float accel_cap_ = INFINITY;  // mm/s^2
  float unit_[N] = {};   // the newest block's direction
  PathAxis axes_[N];
  Slot slots_[Size];
};

}  // namespace am
