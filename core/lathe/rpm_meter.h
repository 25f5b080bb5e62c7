// The spindle's speed for the lathe's display and status: the spindle count
// sampled every kSampleMs by the main loop, the rpm from its change over the
// last kSamples samples (512 ms).
//
// Contract
//   sample(count, counts_per_turn) once every kSampleMs; rpm() is then
//   (count - the count kSamples samples ago) x 60000 / (512 counts_per_turn),
//   truncated toward zero, negative while the spindle turns backwards.
//   reset(count) forgets the history (another encoder: every old sample reads
//   as `count`, so rpm() reads 0 until the spindle has moved). Integer only;
//   host and avr-g++. Limit: at most 1145324 counts in a window (2^31 /
//   1875), 2.2 million counts/s, far above the 50000 counts/s the follower
//   tracks (docs/lathe.md).
#pragma once
#include <stdint.h>

namespace am {

class RpmMeter {
 public:
  static constexpr uint8_t kSamples = 8;
  static constexpr uint16_t kSampleMs = 64;

  void sample(int32_t count, uint16_t counts_per_turn) {
    // counts in 512 ms -> rpm: x 60000 / (512 C)
    rpm_ = int16_t((count - ring_[at_]) * 1875 / (16 * int32_t(counts_per_turn)));
    ring_[at_] = count;
    at_ = uint8_t((at_ + 1) % kSamples);
  }
  void reset(int32_t count) {
    for (int32_t& c : ring_) c = count;
  }
  int16_t rpm() const { return rpm_; }

 private:
  int32_t ring_[kSamples] = {};
  uint8_t at_ = 0;
  int16_t rpm_ = 0;
};

}  // namespace am
