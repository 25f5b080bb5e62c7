// The spindle encoder: edges on INT1 (and INT0) in, signed spindle counts out.
//
// Contract
//   Two modes (init() selects one; the lathe front end's ENCODER command):
//   - single: the seed's slotted disc, one channel on INT1 (PD3), counted on
//     its falling edge; it has no direction, so every count is forward (a
//     reversing spindle cannot be followed in this mode).
//   - quadrature, x4: channel A on INT1 (PD3), channel B on INT0 (PD2), both
//     on any change, so a line of the encoder is four counts. Forward is A
//     leading B (A rises while B is low). INT0 is the seed's motor-encoder
//     input; the stepper leadscrew does not use it, so this variant of the
//     board takes it for B (firmware/boards/m16-lathe.h claims it).
//   The decode runs in the lathe's spindle vectors (firmware/apps/lathe/
//   spindle_vectors.S: INT1 for A, INT0 for B), on the State below, which
//   the leadscrew owns (it is the first part of the vectors' data); each
//   edge adds its count (+1, -1 or none) to `count`, the sum of every count
//   since init() (after the vector's urgent work: the leadscrew's step).
//   `lost` counts edges the decoder could not be sure of (below). The index
//   (PD6) is read by the leadscrew at its counts.
//
// Quadrature decode
//   The decoder keeps each channel's level in software (`known`: A's in bit
//   3, B's in bit 2, PIND's positions). Channel A's vector
//   takes the pin's level now; if it equals the level known, A changed an
//   even number of times since its last service (the flag latches only one
//   edge): no net count, but a pair was missed, so `lost` counts it. Else
//   the level is taken and the count's direction follows from A's new level
//   against B's known one. B's edges are the same with the roles swapped.
//   Both lines latched at once: INT0 (B) has the higher priority, so when A's
//   vector finds B changed too, B changed after A's vector was chosen and
//   is served next, in order; when B's vector finds A changed, the two edges'
//   order is unknown and `lost` counts it. So `lost` stays 0 exactly while
//   every edge is served before the next one on either channel, which is
//   what the benchmark's highest edge rate measures.
#pragma once
#include <stdint.h>

#include "../board.h"

namespace spindle_encoder {

enum class Mode : uint8_t { single, quadrature };

struct State {
  Mode mode;
  uint8_t known;           // the levels last served: A (PD3) in bit 3, B (PD2) in bit 2
  volatile uint16_t lost;
  volatile int32_t count;
};

// Selects the mode, takes the levels as they are and enables the vectors.
void init(Mode m, State& s);
// Counts per spindle turn the mode gives for an encoder of `lines` lines.
inline uint16_t counts_per_line(Mode m) { return m == Mode::quadrature ? 4 : 1; }

}  // namespace spindle_encoder
