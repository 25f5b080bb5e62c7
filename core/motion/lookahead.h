// Look-ahead planner: a ring of straight blocks, each with a trapezoidal speed
// profile whose entry and exit speeds are chosen so that a polyline of short
// segments runs through its vertices instead of stopping at every one.
// (The method and the measured figures: docs/planner.md.)
//
// Contract
//   Lookahead<N, Size>(axes, deviation) plans for N axes (1..4) in a ring of
//   Size blocks (2..64). axes[i] gives the axis's scale (steps per metre),
//   its top rate (steps/s) and its top acceleration (steps/s^2); deviation
//   is the junction deviation in 1/10000 mm (default 100 = 0.01 mm).
//
//   add(steps, lengths, feed, rapid) queues one straight block:
//     steps[i]    signed steps of axis i (the interpreter's target minus the
//                 previous target: LineDda's delta);
//     lengths[i]  the program coordinate's change on axis i, in 1/10000 mm
//                 ("lu": the interpreter's coord[] minus the previous
//                 coord[]): the path's length and direction. All zero, or
//                 add_steps(steps, feed, rapid): from steps / steps per metre;
//     feed        1/10000 mm/min along the path (GcodeAction::feed), >= 1;
//     rapid       G0: the feed is ignored, the limiting axis's rate rules.
//   Result: queued; empty (no axis steps: nothing queued, not an error);
//   full (nothing changed: call again after finish()); bad_feed (feed <= 0
//   on a G1); out_of_range (an INT32_MIN step or length, or a length derived
//   from steps beyond int32). Every queued block replans the queue.
//
//   Units. A block's profile counts events: steps of its dominant axis (the
//   one with most steps, the first of equals), LineDda's clock. Per block the
//   step generator gets (move(), begin()): the event count, the dominant
//   axis, the signed steps and direction bits, and
//       entry, cruise, exit, nominal    events/s (integers)
//       accel                           events/s^2, up and down
//       final                           entry, cruise and exit are settled.
//   cruise is the top of the profile: nominal, or the peak of a triangle that
//   cannot reach it. Consecutive blocks count different axes at different
//   ratios, so the planner keeps junction speeds as path speeds, lu/s,
//   squared (LookaheadSqr, a uint64 as two halves); a block's events/s are
//   its path speed times events / length, each rounded down.
//
//   Limits per block.
//     nominal  min(feed along the path, each axis i's rate * events /
//              |steps[i]|), at least 1 event/s, at most 2^28 - 1 lu/s (26.8
//              m/s) along the path. A rapid has no feed term.
//     accel    min over axes of max_accel[i] * events / |steps[i]|. So no
//              axis ever exceeds its rate or its acceleration; the axis that
//              gives the minimum is the limiting one.
//     junction grbl's junction deviation: theta the angle between the
//              reversed previous direction and the new one (180 deg = on
//              straight, 0 = reversal), h = sin(theta/2), v^2 = a d h /
//              (1 - h), a = the largest acceleration along the change of
//              direction (new unit vector - old) that every axis allows, d =
//              the deviation; capped by both blocks' nominal speeds. Host-
//              tested over 0..180 deg within 0.05 % of v^2 + 1 (lu/s)^2
//              (measured 0.02 %); within about 2e-6 rad of straight on it is
//              the nominal speed, of a reversal 0.
//     ramps    entry^2 <= exit^2 + 2 a L and exit^2 <= entry^2 + 2 a L in
//              path units, a = accel * L / events rounded down, so a
//              feasible path plan is feasible in events.
//   The last block of the queue always plans to stop: its exit is 0.
//   Rounding: L is the path length within 1 lu (rounded down, and within
//   2^-23 beyond 1.6 m); each speed the generator gets is at most 2^-15 of
//   itself (the square root) plus (1 + events / L) events/s below the plan,
//   and then exactly feasible in integers, |entry^2 - exit^2| <= 2 accel
//   events and max(entry, exit) <= cruise <= nominal (a profile generator
//   may check that strictly): where the rounding misses, the exit moves by
//   that much, never the entry.
//
//   Replanning (grbl's method, written from its description): a reverse pass
//   from the newest block lowers each entry to what its block can shed
//   before the next entry (the newest stops), a forward pass to what the
//   block before can reach. Entries only rise as blocks are added, so an
//   entry at its junction limit or reached at full acceleration is final,
//   and so is every one before it: planned() is the last block of that
//   prefix, add() replans only the blocks after it, and the forward pass
//   tests its bound only after a final block (see plan_from()). replan()
//   recomputes everything after the fixed entries from scratch and gives the
//   same plan; so does a plain two-pass reference (host-tested).
//
//   The step generator, in the same context as add() (the main loop; nothing
//   here is for an interrupt):
//     begin(out)    takes the oldest block: busy from now on, its entry is
//                   fixed; out is its profile. Its exit may still rise while
//                   blocks arrive (never fall);
//     refresh(out)  true, and out refilled, if the busy exit changed since
//                   begin / refresh. A higher exit leaves the profile as it
//                   was up to its deceleration, so a change can be taken at
//                   any point before the generator starts slowing down;
//     lock(out)     fixes the busy block's exit (out refilled if it changed,
//                   out.final set): call it at the latest where the
//                   deceleration toward the exit begins, the point of no
//                   return. After it nothing in the block changes;
//     finish()      the busy block ran its last event: drops it (locking it
//                   first if lock() was not called: then the exit is what
//                   the planner holds now, so refresh() just before).
//   The next block then starts exactly at the locked exit (as a path speed).
//
// Why this form
//   No float anywhere: the simulator tests recompute the chip's schedule on
//   the host with this code, which needs bit-identical results. The passes
//   only add and compare squared speeds (about 150 cycles a block on the
//   AVR); divisions and square roots happen once per block when it is added
//   (length, direction, limits, junction) and when the generator takes it
//   (the events/s conversion, whose entry reuses the previous exit's root).
//   32-bit arithmetic where it fits: avr-gcc's 64-bit operations are library
//   calls (lookahead_math.h has the measured costs).
//
// Cost (ATmega32 at 16 MHz, avr-gcc 5.4 -Os, simavr; docs/planner.md)
//   add() with replanning in a 16-block ring, polylines of 0.1 mm segments:
//   10k..18k cycles (mean), 21k at most; taking a block (begin, lock,
//   finish): 3.4k..6.4k, 7.6k at most. Flash about 13 KB (3 or 4 axes, with
//   the library's 64-bit helpers), stack about 350 bytes at the deepest.
// RAM: sizeof(LookaheadBlock<N>) = 4 N + 37 bytes on the AVR (49 for 3 axes,
//   53 for 4); a Lookahead<N, Size> is Size (4 N + 37) + 20 N + 39 bytes:
//   883 for 3 axes and 16 blocks, 967 for 4, 491 for 3 axes and 8 blocks.
//
// Limits: axis rates 1 .. 2^24 - 1 steps/s, accelerations 1 .. 2^31 - 1
// steps/s^2, steps per metre >= 1 (values outside are clamped); steps and
// lengths |x| <= 2^31 - 1 (the path at most 2^32 - 1 lu); deviation <= 100000
// (10 mm, clamped); path accelerations above 2^31 - 1 lu/s^2 (214 m/s^2) are
// planned at that value; squared speeds saturate at 2^58. Host and avr-g++
// 5.4; no allocation, no standard library.
#pragma once
#include <stdint.h>

#include "lookahead_math.h"

namespace am {

constexpr uint32_t kLookaheadLengthPerM = 10000000;     // lu (1/10000 mm) per metre
constexpr uint32_t kLookaheadDefaultDeviation = 100;    // lu: 0.01 mm
constexpr uint32_t kLookaheadMaxDeviation = 100000;     // lu: 10 mm
constexpr uint32_t kLookaheadMaxRate = 0xFFFFFFu;       // steps/s and events/s
constexpr uint32_t kLookaheadMaxAccel = 0x7FFFFFFFu;    // steps/s^2
constexpr uint32_t kLookaheadMaxSpeed = 0xFFFFFFFu;     // lu/s along the path
constexpr uint32_t kLookaheadMaxPathAccel = 0x7FFFFFFFu;  // lu/s^2
constexpr uint64_t kLookaheadMaxSqr = uint64_t(1) << 58;  // saturation of squared speeds

struct LookaheadAxis {
  uint32_t steps_per_m;  // steps per metre of travel (as GcodeAxis)
  uint32_t max_rate;     // steps/s
  uint32_t max_accel;    // steps/s^2
};

enum class LookaheadStatus : uint8_t { queued, empty, full, bad_feed, out_of_range };

// A squared path speed, (lu/s)^2, as two 32-bit halves: the replanning
// passes add and compare these, which avr-gcc does inline, where a uint64
// costs library calls and register shuffles (30 % of the pass time).
struct LookaheadSqr {
  uint32_t lo, hi;
  uint64_t value() const { return lookahead_detail::make64(lo, hi); }
  static LookaheadSqr of(uint64_t v) { return LookaheadSqr{uint32_t(v), lookahead_detail::hi32(v)}; }
  bool operator==(const LookaheadSqr& o) const { return lo == o.lo && hi == o.hi; }
  bool operator!=(const LookaheadSqr& o) const { return !(*this == o); }
  bool operator<(const LookaheadSqr& o) const { return hi != o.hi ? hi < o.hi : lo < o.lo; }
  LookaheadSqr operator+(const LookaheadSqr& o) const {  // no overflow: both <= 2^58
    const uint32_t l = lo + o.lo;
    return LookaheadSqr{l, hi + o.hi + (l < lo)};
  }
};

// One queued block, as the planner keeps it.
template <uint8_t N>
struct LookaheadBlock {
  int32_t steps[N];             // signed steps per axis
  uint32_t length;              // path length, lu (1/10000 mm)
  uint32_t nominal;             // events/s
  uint32_t accel;               // events/s^2
  LookaheadSqr entry_sqr;       // planned entry speed^2, (lu/s)^2
  LookaheadSqr max_entry_sqr;   // junction limit (and both nominals)^2
  LookaheadSqr delta_sqr;       // 2 a L: what the block can gain or shed
  uint8_t dominant;             // axis with the most steps
};

// One block as the step generator sees it.
template <uint8_t N>
struct LookaheadMove {
  int32_t steps[N];  // signed steps per axis (LineDda::start's delta)
  uint32_t events;   // |steps[dominant]|
  uint8_t dominant;  // the axis that steps at every event
  uint8_t dirs;      // bit i set: axis i moves forward
  uint32_t entry;    // events/s
  uint32_t cruise;   // events/s
  uint32_t exit;     // events/s
  uint32_t nominal;  // events/s
  uint32_t accel;    // events/s^2
  bool final;        // entry, cruise and exit will not change
};

template <uint8_t N, uint8_t Size>
class Lookahead {
  static_assert(N >= 1 && N <= 4, "Lookahead plans 1..4 axes");
  static_assert(Size >= 2 && Size <= 64, "Lookahead rings hold 2..64 blocks");

 public:
  using Block = LookaheadBlock<N>;
  using Move = LookaheadMove<N>;

  explicit Lookahead(const LookaheadAxis (&axes)[N], uint32_t deviation = kLookaheadDefaultDeviation) {
    using namespace lookahead_detail;
    deviation_ = deviation > kLookaheadMaxDeviation ? kLookaheadMaxDeviation : deviation;
    for (uint8_t i = 0; i < N; ++i) {
      const LookaheadAxis& a = axes[i];
      steps_per_m_[i] = a.steps_per_m ? a.steps_per_m : 1;
      rate_[i] = clamp(a.max_rate, 1, kLookaheadMaxRate);
      accel_[i] = clamp(a.max_accel, 1, kLookaheadMaxAccel);
      // a_i d for the junctions: the axis's acceleration in lu/s^2 times
      // the deviation, (lu/s)^2.
      const uint64_t lu = uint64_t(accel_[i]) * kLookaheadLengthPerM / steps_per_m_[i];
      const uint32_t a_lu = lu > kLookaheadMaxPathAccel ? kLookaheadMaxPathAccel : lu ? uint32_t(lu) : 1;
      accel_dev_[i] = fp_make64(uint64_t(a_lu) * deviation_, 0);
    }
    equal_accel_ = true;
    for (uint8_t i = 1; i < N; ++i)
      if (accel_dev_[i].m != accel_dev_[0].m || accel_dev_[i].e != accel_dev_[0].e) equal_accel_ = false;
    clear();
  }

  // Drops every block (the machine is at rest).
  void clear() {
    tail_ = count_ = planned_ = 0;
    busy_ = locked_ = exit_changed_ = false;
    root_sqr_ = 0;
    root_ = 0;
    feed_ = 0;
    feed_lu_s_ = 0;
  }

  LookaheadStatus add(const int32_t (&steps)[N], const int32_t (&lengths)[N], int32_t feed, bool rapid) {
    for (uint8_t i = 0; i < N; ++i)
      if (lengths[i]) return add_block(steps, lengths, feed, rapid);
    return add_steps(steps, feed, rapid);  // no program lengths
  }

  // The same with the lengths derived from the steps and steps per metre
  // (rounded, at least 1 lu for a moving axis): for moves given in steps.
  LookaheadStatus add_steps(const int32_t (&steps)[N], int32_t feed, bool rapid) {
    constexpr int32_t kMin = -0x7FFFFFFF - 1;
    int32_t len[N];
    for (uint8_t i = 0; i < N; ++i) {
      if (steps[i] == kMin) return LookaheadStatus::out_of_range;
      const uint32_t mag = lookahead_detail::abs32(steps[i]);
      uint64_t l = (uint64_t(mag) * kLookaheadLengthPerM + steps_per_m_[i] / 2) / steps_per_m_[i];
      if (mag && l == 0) l = 1;
      if (l > 0x7FFFFFFFu) return LookaheadStatus::out_of_range;
      len[i] = steps[i] < 0 ? -int32_t(l) : int32_t(l);
    }
    return add_block(steps, len, feed, rapid);
  }

  uint8_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == Size; }
  static constexpr uint8_t capacity() { return Size; }

  // Block i of the queue, 0 = the oldest (i < size()).
  const Block& block(uint8_t i) const { return blocks_[index(i)]; }
  // Planned exit of block i: the next block's entry, 0 for the newest.
  uint64_t exit_sqr(uint8_t i) const { return i + 1 < count_ ? block(uint8_t(i + 1)).entry_sqr.value() : 0; }
  // Last block of the final prefix (entries at or before it never change).
  uint8_t planned() const { return planned_; }
  bool busy() const { return busy_; }
  bool locked() const { return locked_; }

  // The step generator's view of block i (i < size()).
  void move(uint8_t i, Move& out) const {
    using namespace lookahead_detail;
    const Block& b = block(i);
    uint8_t dirs = 0;
    for (uint8_t k = 0; k < N; ++k) {
      out.steps[k] = b.steps[k];
      if (b.steps[k] > 0) dirs = uint8_t(dirs | (1u << k));
    }
    const uint32_t events = abs32(b.steps[b.dominant]);
    out.events = events;
    out.dominant = b.dominant;
    out.dirs = dirs;
    out.nominal = b.nominal;
    out.accel = b.accel;
    uint32_t entry = to_events(root(b.entry_sqr.value()), events, b.length);
    uint32_t exit = to_events(root(exit_sqr(i)), events, b.length);
    if (entry > b.nominal) entry = b.nominal;
    if (exit > b.nominal) exit = b.nominal;
    // Exactly feasible in integers, as a profile generator checks it:
    // |entry^2 - exit^2| <= 2 a events. The rounding above can miss that by
    // a hair; the exit takes it up (the entry is fixed once the block is
    // busy): raised to what the block can slow down to, or lowered to what
    // it can reach. (Equal speeds, as in steady cruising, need no test.)
    uint64_t e2 = 0, x2 = 0, room = 0;
    bool squares = false;
    if (entry != exit) {
      e2 = uint64_t(entry) * entry;
      x2 = uint64_t(exit) * exit;
      room = 2 * (uint64_t(b.accel) * events);  // < 2^63
      squares = true;
      if (x2 + room < e2) {
        exit = isqrt_exact(e2 - room);
        if (uint64_t(exit) * exit < e2 - room) ++exit;  // rounded up, <= entry
        x2 = uint64_t(exit) * exit;
      } else if (x2 > e2 + room) {
        exit = isqrt_exact(e2 + room);
        x2 = uint64_t(exit) * exit;
      }
    }
    // The top: nominal, unless the block is a triangle whose peak is below
    // it, (entry^2 + exit^2 + 2 a events) / 2 (nothing to test when it
    // enters or leaves at nominal, as cruising blocks do).
    uint32_t cruise = b.nominal;
    if (entry != b.nominal && exit != b.nominal) {
      if (!squares) {
        e2 = x2 = uint64_t(entry) * entry;
        room = 2 * (uint64_t(b.accel) * events);
      }
      const uint64_t peak = (e2 + x2 + room) >> 1;
      if (uint64_t(b.nominal) * b.nominal > peak) cruise = isqrt_approx(peak);
    }
    if (cruise < entry) cruise = entry;
    if (cruise < exit) cruise = exit;
    out.entry = entry;
    out.exit = exit;
    out.cruise = cruise;
    out.final = (i == 0 && locked_) || (i + 1 < count_ && i + 1 <= planned_);
  }

  bool begin(Move& out) {
    if (count_ == 0) return false;
    busy_ = true;
    exit_changed_ = false;
    move(0, out);
    return true;
  }

  bool refresh(Move& out) {
    if (!busy_ || !exit_changed_) return false;
    exit_changed_ = false;
    move(0, out);
    return true;
  }

  // out: what begin() or refresh() filled; refilled only if the exit
  // changed since.
  bool lock(Move& out) {
    if (!busy_) return false;
    const bool changed = exit_changed_;
    lock();
    if (changed) move(0, out);
    out.final = true;
    return true;
  }

  bool finish() {
    if (!busy_) return false;
    lock();
    tail_ = index(1);
    --count_;
    if (planned_) --planned_;
    busy_ = locked_ = false;
    return true;
  }

  // Recomputes every entry after the fixed ones from scratch.
  void replan() {
    const uint8_t first = locked_ ? 2 : 1;
    if (first >= count_) return;
    planned_ = uint8_t(first - 1);
    plan_from(first);
  }

 private:
  using Fp16 = lookahead_detail::Fp16;
  static constexpr uint32_t kSnap = uint32_t(1) << 9;  // Q29: 2^-20

  static uint32_t clamp(uint32_t v, uint32_t lo, uint32_t hi) { return v < lo ? lo : v > hi ? hi : v; }

  uint8_t index(uint8_t i) const {
    const uint8_t k = uint8_t(tail_ + i);
    return k >= Size ? uint8_t(k - Size) : k;
  }
  Block& at(uint8_t i) { return blocks_[index(i)]; }

  void lock() {
    locked_ = true;
    exit_changed_ = false;
    if (count_ > 1 && planned_ < 1) planned_ = 1;
  }

  // sqrt of a squared path speed (within 2^-15 below the root); one result
  // remembered, since the last exit is the next block's entry.
  uint32_t root(uint64_t sqr) const {
    if (sqr == 0) return 0;
    if (sqr != root_sqr_) {
      root_sqr_ = sqr;
      root_ = lookahead_detail::isqrt_approx(sqr);
    }
    return root_;
  }

  // lu/s -> events/s of a block, rounded down.
  static uint32_t to_events(uint32_t v, uint32_t events, uint32_t length) {
    return v ? uint32_t(lookahead_detail::div_u64(uint64_t(v) * events, length)) : 0;
  }

  // The axis whose limit / |steps| is smallest (some mag[i] != 0).
  static uint8_t limiting(const uint32_t (&limit)[N], const uint32_t (&mag)[N]) {
    uint8_t best = 0;
    while (best + 1 < N && mag[best] == 0) ++best;
    for (uint8_t i = uint8_t(best + 1); i < N; ++i) {
      if (mag[i] && uint64_t(limit[i]) * mag[best] < uint64_t(limit[best]) * mag[i]) best = i;
    }
    return best;
  }

  // Path length (lu, rounded down, at most 1 lu off) and unit vector (Q29)
  // of len[] (not all zero), from a 24-bit norm and its reciprocal (within
  // about 2^-23): a junction between nearly parallel moves needs their unit
  // vectors to have equal lengths, or the difference w - u, whose direction
  // sets the junction acceleration, tilts by the mismatch over the angle.
  static void geometry(const int32_t* len, uint32_t& length, int32_t (&unit)[N]) {
    using namespace lookahead_detail;
    uint32_t mag[N];
    uint32_t any = 0;
    for (uint8_t i = 0; i < N; ++i) {
      mag[i] = abs32(len[i]);
      any |= mag[i];
    }
    uint64_t sum = 0;
    if (any < 0x8000u) {  // 16-bit products, the sum below 2^32
      uint32_t sum32 = 0;
      for (uint8_t i = 0; i < N; ++i)
        if (mag[i]) sum32 += uint32_t(uint16_t(mag[i])) * uint16_t(mag[i]);
      sum = sum32;
    } else {
      for (uint8_t i = 0; i < N; ++i)
        if (mag[i]) sum += uint64_t(mag[i]) * mag[i];
    }
    // x = sum 2^(2s) in [2^30, 2^32), dropping low bits of a long move's
    // sum (s < 0); n = norm 2^(s + 8), 24 bits; r = 2^48 / n.
    const uint8_t b = bit_length(sum);
    int8_t s;
    uint32_t x;
    if (b <= 32) {
      s = int8_t((32 - b) >> 1);
      x = uint32_t(sum) << (2 * s);
    } else {
      s = int8_t(-int8_t((b - 31) >> 1));
      x = shr_to32(sum, uint8_t(-2 * s));
    }
    uint32_t n, r;
    norm24(x, n, r);
    const int8_t e = int8_t(s + 8);  // norm = n 2^-e
    length = e >= 0 ? shr32(n, uint8_t(e)) : shl32(n, uint8_t(-e));
    // Q29 = |len| 2^29 2^e / n = |len| r 2^(e - 19).
    const int8_t shift = int8_t(19 - e);  // -4 .. 27
    for (uint8_t i = 0; i < N; ++i) {
      uint32_t u = 0;
      if (mag[i]) {
        const uint64_t p = uint64_t(mag[i]) * r;
        u = shift >= 0 ? shr_to32(p, uint8_t(shift)) : shl32(uint32_t(p), uint8_t(-shift));
      }
      unit[i] = len[i] < 0 ? -int32_t(u) : int32_t(u);
    }
  }

  // Junction speed^2, (lu/s)^2, between unit vectors u (before) and w
  // (after), at most cap. With D = |w - u|^2 and S = |w + u|^2 (D + S = 4):
  // sin(theta/2) = sqrt(S) / 2, and h / (1 - h) = (2 sqrt(S) + S) / D for
  // h = sin(theta/2). The junction acceleration is min_i a_i sqrt(D) /
  // |w_i - u_i| (the limit along (w - u) / sqrt(D)), so
  //   v^2 = min_i (a_i d / |w_i - u_i|) sqrt(S) (2 + sqrt(S)) / sqrt(D).
  // Differences keep all 29 bits before they are cut to 15 for the sums of
  // squares; the rest is Fp16 (about 3e-4 relative in all). Smooth paths
  // mostly end at the cap: a junction acceleration is at least the smallest
  // a_i of the axes in w - u, and 2 sqrt(S) + S > 4.8 when D <= 2, so
  // 4 min a_i d / D >= cap settles it without roots or division.
  uint64_t junction_sqr(const int32_t (&u)[N], const int32_t (&w)[N], uint64_t cap) const {
    using namespace lookahead_detail;
    uint32_t d[N], s[N];
    uint32_t d_any = 0, s_any = 0;
    for (uint8_t i = 0; i < N; ++i) {
      d[i] = abs32(w[i] - u[i]);
      s[i] = abs32(w[i] + u[i]);
      d_any |= d[i];
      s_any |= s[i];
    }
    // A unit vector's length is known to about 2^-23, so parallel moves of
    // different lengths differ by up to about 2^6 in Q29: below 2^9 the
    // junction is a reversal or straight on (within 2e-6 rad).
    if (s_any < kSnap) return 0;    // reversal
    if (d_any < kSnap) return cap;  // straight on
    const uint8_t bd = bit_length32(d_any);
    const uint8_t kd = bd > 15 ? uint8_t(bd - 15) : 0;
    uint32_t dd = 0;  // D 2^(58 - 2 kd)
    for (uint8_t i = 0; i < N; ++i) {
      if (d[i] == 0) continue;
      const uint16_t di = uint16_t(shr32(d[i], kd));
      dd += uint32_t(di) * di;
    }
    // The limiting axis j (smallest a_i d / |d_i|) and the smallest a_i d.
    uint8_t j = 0;
    while (j + 1 < N && d[j] == 0) ++j;
    Fp16 k_min = accel_dev_[j];
    if (equal_accel_) {
      for (uint8_t i = uint8_t(j + 1); i < N; ++i)
        if (d[i] > d[j]) j = i;
    } else {
      Fp16 dj = fp_make(d[j], 0);
      for (uint8_t i = uint8_t(j + 1); i < N; ++i) {
        if (d[i] == 0) continue;
        const Fp16 di = fp_make(d[i], 0);
        if (fp_less(accel_dev_[i], k_min)) k_min = accel_dev_[i];
        if (fp_less(fp_mul(accel_dev_[i], dj), fp_mul(accel_dev_[j], di))) {
          j = i;
          dj = di;
        }
      }
    }
    const Fp16 big_d = fp_make(dd, int16_t(2 * kd - 58));
    const Fp16 cap_fp = fp_make64(cap, 0);
    if (big_d.e < -15 + 1 && !fp_less(Fp16{k_min.m, int16_t(k_min.e + 2)}, fp_mul(cap_fp, big_d))) return cap;
    uint32_t ss = 0;  // S 2^(58 - 2 ks)
    const uint8_t bs = bit_length32(s_any);
    const uint8_t ks = bs > 15 ? uint8_t(bs - 15) : 0;
    for (uint8_t i = 0; i < N; ++i) {
      if (s[i] == 0) continue;
      const uint16_t si = uint16_t(shr32(s[i], ks));
      ss += uint32_t(si) * si;
    }
    const Fp16 root_s = fp_make(isqrt32(ss), int16_t(ks - 29));
    const Fp16 root_d = fp_make(isqrt32(dd), int16_t(kd - 29));
    const Fp16 x = fp_mul(root_s, fp_add(Fp16{0x8000u, -14}, root_s));
    return fp_to_u64(fp_div(fp_mul(accel_dev_[j], x), fp_mul(fp_make(d[j], -29), root_d)), cap);
  }

  // F / 60: the feed in lu/s, remembered (a program's feed rarely changes).
  uint32_t feed_lu_s(int32_t feed) {
    if (feed != feed_) {
      feed_ = feed;
      feed_lu_s_ = uint32_t(feed) / 60u;
      if (feed_lu_s_ == 0) feed_lu_s_ = 1;
    }
    return feed_lu_s_;
  }

  // lengths not all zero.
  LookaheadStatus add_block(const int32_t (&steps)[N], const int32_t (&lengths)[N], int32_t feed, bool rapid) {
    using namespace lookahead_detail;
    if (count_ == Size) return LookaheadStatus::full;
    if (!rapid && feed <= 0) return LookaheadStatus::bad_feed;
    constexpr int32_t kMin = -0x7FFFFFFF - 1;
    uint32_t mag[N];
    uint32_t events = 0;
    uint8_t dominant = 0;
    for (uint8_t i = 0; i < N; ++i) {
      if (steps[i] == kMin || lengths[i] == kMin) return LookaheadStatus::out_of_range;
      mag[i] = abs32(steps[i]);
      if (mag[i] > events) {
        events = mag[i];
        dominant = i;
      }
    }
    if (events == 0) return LookaheadStatus::empty;

    uint32_t length;
    int32_t unit[N];
    geometry(lengths, length, unit);

    // Nominal speed: the limiting axis's rate or the feed, events/s, and
    // the same along the path, lu/s (rounded down: never above it).
    const uint8_t r = limiting(rate_, mag);
    uint32_t v = mag[r] == events ? rate_[r] : uint32_t(div_u64(uint64_t(rate_[r]) * events, mag[r]));
    uint32_t vp = 0;
    if (!rapid) {
      const uint64_t f = div_u64(uint64_t(uint32_t(feed)) * events, 60 * uint64_t(length));
      if (f < v) {
        v = f ? uint32_t(f) : 1;
        vp = feed_lu_s(feed);  // < 2^26
      }
    }
    if (vp == 0) {
      const uint64_t p = div_u64(uint64_t(v) * length, events);
      if (p > kLookaheadMaxSpeed) {
        v = uint32_t(div_u64(uint64_t(kLookaheadMaxSpeed) * events, length));
        if (v == 0) v = 1;
        vp = kLookaheadMaxSpeed;
      } else {
        vp = p ? uint32_t(p) : 1;
      }
    }

    // Acceleration, events/s^2, and along the path, lu/s^2 (rounded down,
    // so the path plan is feasible in events too).
    const uint8_t a = limiting(accel_, mag);
    const uint32_t acc = mag[a] == events ? accel_[a] : uint32_t(div_u64(uint64_t(accel_[a]) * events, mag[a]));
    const uint64_t ap64 = div_u64(uint64_t(acc) * length, events);
    const uint32_t ap = ap64 > kLookaheadMaxPathAccel ? kLookaheadMaxPathAccel : ap64 ? uint32_t(ap64) : 1;
    const uint64_t al = uint64_t(ap) * length;  // < 2^63
    const uint64_t nominal_sqr = uint64_t(vp) * vp;

    // The junction with the newest block, unless that one stops (it is
    // locked, or there is none: the machine is at rest).
    uint64_t max_entry = 0;
    if (count_ > 1 || (count_ == 1 && !locked_)) {
      const uint64_t cap = nominal_sqr < last_nominal_sqr_ ? nominal_sqr : last_nominal_sqr_;
      max_entry = junction_sqr(last_unit_, unit, cap);
    }

    Block& b = at(count_);
    for (uint8_t i = 0; i < N; ++i) {
      b.steps[i] = steps[i];
      last_unit_[i] = unit[i];
    }
    b.length = length;
    b.nominal = v;
    b.accel = acc;
    b.entry_sqr = LookaheadSqr{0, 0};
    b.max_entry_sqr = LookaheadSqr::of(max_entry);
    b.delta_sqr = LookaheadSqr::of(al >= kLookaheadMaxSqr / 2 ? kLookaheadMaxSqr : al * 2);
    b.dominant = dominant;
    last_nominal_sqr_ = nominal_sqr;
    ++count_;
    if (count_ > 1) plan_from(uint8_t(planned_ + 1));
    return LookaheadStatus::queued;
  }

  // Reverse then forward pass over blocks first .. count_ - 1 (first >= 1;
  // the entry of block first - 1 is final).
  //
  // The forward pass only tests its bound after a block that is final: a
  // block that is not (neither at its junction limit nor reached at full
  // acceleration) has the entry the reverse pass gave it, next entry + its
  // delta, so the bound it passes on, that entry + its delta again, is
  // above the next entry by twice its delta and cannot bind.
  void plan_from(uint8_t first) {
    const uint8_t n = count_;
    if (first >= n) return;
    const LookaheadSqr busy_exit = at(1).entry_sqr;
    Block* const end = blocks_ + Size;
    // Reverse: each entry is what its block can shed before the next entry
    // (the newest block stops). Halves by hand: avr-gcc keeps them in
    // registers.
    Block* b = &at(uint8_t(n - 1));
    uint32_t lo = 0, hi = 0;
    for (uint8_t k = uint8_t(n - first); k; --k) {
      const uint32_t l = lo + b->delta_sqr.lo;
      hi = hi + b->delta_sqr.hi + (l < lo);
      lo = l;
      const uint32_t mhi = b->max_entry_sqr.hi;
      if (hi > mhi || (hi == mhi && lo > b->max_entry_sqr.lo)) {
        hi = mhi;
        lo = b->max_entry_sqr.lo;
      }
      b->entry_sqr.lo = lo;
      b->entry_sqr.hi = hi;
      b = b == blocks_ ? end - 1 : b - 1;
    }
    // Forward: and at most what the block before can reach.
    bool prev_final = true;
    for (uint8_t k = first; k < n; ++k) {
      const Block* prev = b;
      b = b + 1 == end ? blocks_ : b + 1;
      bool final = false;
      if (prev_final) {
        const uint32_t l = prev->entry_sqr.lo + prev->delta_sqr.lo;
        const uint32_t h = prev->entry_sqr.hi + prev->delta_sqr.hi + (l < prev->entry_sqr.lo);
        if (h < b->entry_sqr.hi || (h == b->entry_sqr.hi && l <= b->entry_sqr.lo)) {
          b->entry_sqr.lo = l;  // reached at full acceleration
          b->entry_sqr.hi = h;
          final = true;
        }
      }
      if (!final && b->entry_sqr.lo == b->max_entry_sqr.lo && b->entry_sqr.hi == b->max_entry_sqr.hi)
        final = true;  // at its junction limit
      if (final) planned_ = k;
      prev_final = final;
    }
    if (busy_ && at(1).entry_sqr != busy_exit) exit_changed_ = true;
  }

  Block blocks_[Size];
  uint32_t steps_per_m_[N];
  uint32_t rate_[N];    // steps/s
  uint32_t accel_[N];   // steps/s^2
  Fp16 accel_dev_[N];   // a_i (lu/s^2) times the deviation (lu)
  bool equal_accel_;    // every accel_dev_ the same
  int32_t last_unit_[N];  // newest block's direction, Q29
  uint64_t last_nominal_sqr_ = 0;
  uint32_t deviation_;  // lu
  int32_t feed_;        // the last feed and F / 60
  uint32_t feed_lu_s_;
  mutable uint64_t root_sqr_;
  mutable uint32_t root_;
  uint8_t tail_, count_, planned_;
  bool busy_, locked_, exit_changed_;
};

}  // namespace am
