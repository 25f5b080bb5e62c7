// The step queue: the only channel between the planner (main loop) and the
// step interrupt.
//
// Contract
//   A StepSegment is a run of `count` steps, each preceded by `interval` timer
//   ticks, on the axes in `axes` (bit i = axis i) with directions `dirs`
//   (bit i set = forward). The main loop pushes, the step interrupt pops; the
//   queue is single-producer single-consumer and lock-free because each index
//   is written by one side only and is one byte wide (atomic on the AVR).
//
//   `chain` is the consumer's own mark (make() leaves it 0): the AVR engine
//   sets it on a segment that its assembly fast path may switch to without
//   the C handler (docs/step-engine.md). `block` names the coordinated block
//   (its interpolator) whose events a segment of several axes times: which
//   of `axes` step at each event is that interpolator's answer.
//
//   The interval is stored pre-split for a 16-bit timer: `wraps` periods of
//   wrap_compare + 1 ticks followed by a final period of compare + 1 ticks.
//   The interrupt therefore never divides or compares 32-bit numbers; all of
//   that happens in make().
#pragma once
#include <stddef.h>
#include <stdint.h>

namespace am {

struct StepSegment {
  uint16_t count;         // steps in this segment, >= 1
  uint16_t compare;       // compare value of the final period of an interval
  uint16_t wrap_compare;  // compare value of each earlier period
  uint8_t wraps;          // periods before the final one
  uint8_t axes;           // which axes step
  uint8_t dirs;           // forward bits
  uint8_t chain;          // see the contract
  uint8_t block;          // see the contract

  // Splits `interval` ticks (1 .. kMaxSegmentInterval) into wraps + 1 timer
  // periods of near-equal length. Equal periods, rather than full 65536-tick
  // wraps plus a remainder, keep every period of a long interval above 32768
  // ticks, so a period never ends before the interrupt that started it has
  // written its compare value.
  static StepSegment make(uint32_t interval, uint16_t count, uint8_t axes, uint8_t dirs) {
    StepSegment s;
    s.count = count;
    s.wraps = uint8_t((interval - 1) >> 16);
    const uint32_t period = interval / (s.wraps + 1u);
    s.wrap_compare = uint16_t(period - 1);
    s.compare = uint16_t(interval - s.wraps * period - 1);
    s.axes = axes;
    s.dirs = dirs;
    s.chain = 0;
    s.block = 0;
    return s;
  }
  uint32_t interval() const { return uint32_t(wraps) * (wrap_compare + 1u) + compare + 1u; }
};

// Longest interval a segment can hold (about 1.07 s at 16 MHz).
constexpr uint32_t kMaxSegmentInterval = 256ul * 65536ul;

template <uint8_t Size>
class StepQueue {
  static_assert((Size & (Size - 1)) == 0 && Size >= 2, "size must be a power of two");

 public:
  bool empty() const { return head_ == tail_; }
  bool full() const { return uint8_t(head_ - tail_) == Size; }
  uint8_t size() const { return uint8_t(head_ - tail_); }

  // Producer side. Returns false when full.
  bool push(const StepSegment& s) {
    if (full()) return false;
    slots_[head_ & (Size - 1)] = s;
    // The slot must be written before the index that publishes it: only
    // volatile accesses are ordered among themselves, so fence the plain
    // stores (a compiler barrier: the AVR itself does not reorder).
    __atomic_signal_fence(__ATOMIC_RELEASE);
    head_ = uint8_t(head_ + 1);
    return true;
  }

  // Consumer side: the oldest segment, valid while !empty().
  StepSegment& front() { return slots_[tail_ & (Size - 1)]; }
  uint8_t tail() const { return tail_; }
  uint8_t head() const { return head_; }
  // The slot that ring index `index` (any value; it wraps) refers to.
  const StepSegment* slot(uint8_t index) const { return &slots_[index & (Size - 1)]; }
  void pop() { tail_ = uint8_t(tail_ + 1); }
  // pop(), then the next front, or nullptr when that emptied the queue: one
  // read of each index, for the step interrupt's segment change.
  const StepSegment* pop_and_front() {
    const uint8_t tail = uint8_t(tail_ + 1);
    tail_ = tail;
    return tail == head_ ? nullptr : &slots_[tail & (Size - 1)];
  }

  // Layout, for a consumer written in assembly (the AVR step engine's fast
  // path reads the ring directly). The class is standard-layout, so offsetof
  // is well defined.
  static constexpr size_t slots_offset() { return offsetof(StepQueue, slots_); }
  static constexpr size_t head_offset() { return offsetof(StepQueue, head_); }
  static constexpr size_t tail_offset() { return offsetof(StepQueue, tail_); }

 private:
  StepSegment slots_[Size];
  volatile uint8_t head_ = 0;
  volatile uint8_t tail_ = 0;
};

}  // namespace am
