// The driver board's coil logic, free of hardware: which port bits a coil
// pattern drives and which pairs the current chopper has cut.
//
// Contract
//   CoilMap<APos, BPos, ANeg, BNeg> takes the port masks of the four coil
//   pins; port_bits(pattern) turns a sequencer pattern (bit0 = A+, bit1 = B+,
//   bit2 = A-, bit3 = B-; core/motor/phase_sequencer.h) into those port bits.
//   pair_a / pair_b are the bits of the two coil pairs that share a sense
//   resistor (A+/A- = a/c, B+/B- = b/d).
//
//   Chopper::sample(pair, reading) records one 8-bit current reading of a
//   pair: strictly above the limit cuts the pair, anything else releases it.
//   The decision stands until that pair's next sample. Readings are unsigned
//   bytes (0..255): a reading of 128 or more is a large current, never a
//   negative one.
#pragma once
#include <stdint.h>

namespace driver {

template <uint8_t APos, uint8_t BPos, uint8_t ANeg, uint8_t BNeg>
struct CoilMap {
  static constexpr uint8_t pair_a = APos | ANeg;
  static constexpr uint8_t pair_b = BPos | BNeg;
  static constexpr uint8_t all = pair_a | pair_b;

  static constexpr uint8_t port_bits(uint8_t pattern) {
    return uint8_t(((pattern & 0x1) ? APos : 0) | ((pattern & 0x2) ? BPos : 0) |
                   ((pattern & 0x4) ? ANeg : 0) | ((pattern & 0x8) ? BNeg : 0));
  }
};

template <uint8_t Limit>
class Chopper {
 public:
  void sample(uint8_t pair, uint8_t reading) {
    cut_ = reading > Limit ? uint8_t(cut_ | pair) : uint8_t(cut_ & uint8_t(~pair));
  }
  uint8_t cut() const { return cut_; }

 private:
  uint8_t cut_ = 0;
};

}  // namespace driver
