// Board: ATmega16 lathe controller (seed-004 section 4) as an electronic
// leadscrew with a stepper on the leadscrew (docs/lathe.md). Wiring:
// firmware/boards/common/m16_wiring.h, the same as the m16 image's.
// avrmotion-board: mcu=atmega16 f_cpu=16000000 app=lathe
//
// The leadscrew (axis Z): step PC0, direction PC1 (high = +Z, away from the
// headstock), enable PC7 (active low); 200 full steps x 4 microsteps on the
// 3.175 mm (8 TPI) screw: 800 steps per turn, 3.97 um per step. The spindle
// encoder: the seed's 40-slot disc on INT1 (PD3), or in this variant a
// quadrature encoder with A on INT1 and B on INT0 (PD2, the seed's motor
// encoder input, which a stepper leadscrew does not need), index on PD6.
// Limit switch PD7 (low = hit).
#pragma once
#include "../../core/lathe/ratio.h"
#include "../axes/axis_set.h"
#include "../axes/step_dir_axis.h"
#include "common/m16_wiring.h"

namespace board {

using namespace m16_wiring;
using SpindleQuadratureB = MotorEncoder;  // INT0
constexpr bool kSpindleEncoder = true;  // its pins in the descriptor, for the simulator
struct SpindlePins {
  using A = SpindleEncoder;
  using B = SpindleQuadratureB;
  using Index = SpindleIndex;
  using Limit = LimitSwitch;
};

// 800 steps per 3.175 mm: 251968.5 steps per metre, rounded for the
// descriptor (the simulator's mm); the firmware converts with the exact
// rational below.
using Axes = AxisSet<StepDirAxis<'Z', LeadStep, LeadDir, LeadEnable, true, 251969>>;

// The machine for the gearing core (core/lathe/ratio.h). Positive steps move
// +Z (away from the chuck), so with the spindle forward a right-hand thread
// needs negative steps: leadscrew_reversed.
constexpr am::Pitch kLeadscrewPitch = am::pitch_tpi(8);
constexpr am::CountsPerTurn kLeadscrewCounts = am::stepper_counts(200, 4);
constexpr bool kLeadscrewReversed = true;
// The encoder the image starts with (the seed's disc); the ENCODER command
// selects another.
constexpr uint16_t kSpindleLines = 40;
constexpr bool kSpindleQuadrature = false;

// Step/dir driver timing (DRV8825: 1.9 us high, 1.9 us low, 650 ns direction
// set-up; A4988 needs less): 2 us, 2 us, 1 us.
constexpr uint8_t kStepHighCycles = F_CPU / 1000000 * 2;
constexpr uint8_t kStepLowCycles = F_CPU / 1000000 * 2;
constexpr uint8_t kDirSetupCycles = F_CPU / 1000000;
// Moves and engagement: the carriage's acceleration and top rate (steps/s^2,
// steps/s: 79 mm/s^2, 79 mm/s); a ratio of kMaxStepsPerCount steps per
// spindle count or more is refused (the steps of one count go out as a
// burst from the spindle vector, spindle_vectors.S: 92 cycles a step, 32
// high and 60 low, so up to 15 of them take 86 us).
constexpr uint32_t kLeadscrewAccel = 20000;
constexpr uint32_t kLeadscrewMaxRate = 20000;
constexpr uint8_t kMaxStepsPerCount = 16;

// Hardware claims (hal/avr/claims.h, checked when the image compiles):
// Timer1 paces the leadscrew's own moves (positioning and catching up with
// the spindle; CTC at F_CPU / 8), INT1 and INT0 are the spindle encoder, the
// UART talks to the host, Timer0 is the time base (m16_wiring.h). PORTA (the
// LCD) and PORTB (the keypad) are the operator interface's. A DC-servo
// leadscrew (the seed's L298 on OC1A) would need Timer1 for its PWM and
// INT0 for its motor encoder: it is a different variant of this board.
constexpr uint32_t kLeadscrewClaims = hal::claim::timer1 | hal::claim::int1 | hal::claim::int0;
using Claims = hal::ClaimSet<kLeadscrewClaims, kClock, hal::claim::uart, Axes::Claims::all>;

inline void init() {
  init_inputs();
  Axes::init();
}

}  // namespace board
