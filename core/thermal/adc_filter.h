// Integer conditioning of 10-bit ADC samples before the thermistor table:
// oversampling to more bits, and a first-order low-pass.
//
// Contract
//   AdcOversampler<E> sums 4^E samples of a 10-bit converter and yields one
//   (10 + E)-bit value per set: (sum + 4^E / 2) >> E. The added half of a
//   10-bit step makes the result the floor code of an ideal (10 + E)-bit
//   converter (the mean of truncating samples lies half a step low), so the
//   thermistor's bin-centre convention holds at every E; what is left is a
//   mean bias of +2^-(E+1) of an output step (1/8 at E = 2), from the
//   quantisation of the sum itself. The extra bits are
//   real only when the input carries at least about one step of noise
//   (dither); a quiet input at code c gives 2^E c + 2^(E-1), which the
//   thermistor lookup places 2^-(E+1) of a 10-bit step above the centre of
//   c's bin (1/8 step at E = 2). add() returns true when a set completes;
//   value() holds the last completed set (0 before the first).
//
//   AdcSmoother<K> is y += (x - y) / 2^K with K fractional bits kept: a time
//   constant of about 2^K samples and unity gain. The state moves by x minus
//   the *rounded* output, so a constant input always settles to an output of
//   exactly x, from above or below (no dead band). The first sample after
//   reset() sets y = x (no slow start from 0). Inputs up to 16 bits, K <= 15.
//
//   Both are plain state: when add() runs in the ADC interrupt and value() in
//   the main loop, read the 16-bit value with interrupts off.
#pragma once
#include <stdint.h>

namespace am {

template <uint8_t ExtraBits>
class AdcOversampler {
  static_assert(ExtraBits <= 5, "at most 1024 samples a set");

 public:
  static constexpr uint8_t kBits = uint8_t(10 + ExtraBits);
  static constexpr uint16_t kSamples = uint16_t(1u << (2 * ExtraBits));

  bool add(uint16_t sample) {
    sum_ += sample & 0x3FFu;
    if (++count_ < kSamples) return false;
    value_ = uint16_t((sum_ + kSamples / 2) >> ExtraBits);
    sum_ = 0;
    count_ = 0;
    return true;
  }
  uint16_t value() const { return value_; }
  void reset() { sum_ = 0, count_ = 0, value_ = 0; }

 private:
  uint32_t sum_ = 0;
  uint16_t count_ = 0;
  uint16_t value_ = 0;
};

template <uint8_t K>
class AdcSmoother {
  static_assert(K <= 15, "K <= 15");

 public:
  uint16_t add(uint16_t x) {
    if (!primed_) {
      acc_ = uint32_t(x) << K;
      primed_ = true;
    } else {
      acc_ = acc_ + x - value();  // acc = 2^K y; never below 0
    }
    return value();
  }
  uint16_t value() const { return uint16_t((acc_ + (1ul << K) / 2) >> K); }
  void reset() { acc_ = 0, primed_ = false; }

 private:
  uint32_t acc_ = 0;
  bool primed_ = false;
};

}  // namespace am
