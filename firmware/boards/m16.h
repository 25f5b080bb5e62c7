// Board: ATmega16 lathe controller (seed-004 section 4), running the step/dir
// protocol (app cnc). Wiring: firmware/boards/common/m16_wiring.h; the
// electronic leadscrew program on the same wiring is firmware/boards/m16-lathe.h.
// avrmotion-board: mcu=atmega16 f_cpu=16000000,8000000 app=cnc
//
// Leadscrew on a step/dir driver (axis Z): a 200-step motor on the 3.175 mm
// leadscrew gives 62992 steps per metre. Axis U: a ULN2003 unipolar motor on
// PC2..PC5.
#pragma once
#include "../axes/axis_set.h"
#include "../axes/step_dir_axis.h"
#include "../axes/unipolar_axis.h"
#include "common/m16_wiring.h"

namespace board {

using namespace m16_wiring;
using Axes = AxisSet<StepDirAxis<'Z', LeadStep, LeadDir, LeadEnable, true, 62992>,
                     UnipolarAxis<'U', Pin<'C', 2>, Pin<'C', 3>, Pin<'C', 4>, Pin<'C', 5>, 4096>>;

// Hardware claims (hal/avr/claims.h, checked when the image compiles): Timer1
// is the step clock, the UART talks to the host, Timer0 is the time base
// (m16_wiring.h). The seed's DC-servo leadscrew drives its L298 from OC1A
// (PD5), which needs Timer1 for PWM: a servo variant of this board cannot
// also claim Timer1 as a step clock.
constexpr uint32_t kStepClock = hal::claim::timer1;
using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all>;

constexpr uint32_t kStepTimerHz = F_CPU;
constexpr uint32_t kMaxStepRate = F_CPU / 800;  // 20 kHz at 16 MHz, 10 kHz at 8 MHz
// No G-code: its front end (about 8 KB) does not fit beside the engine in
// the ATmega16's 16 KB; this board is for the lathe program.
constexpr bool kGcode = false;
constexpr bool kArcs = false;  // no G-code at all
constexpr uint8_t kPathBlocks = 4;  // look-ahead ring of G-code blocks (firmware/engine/path.h)
constexpr uint32_t kDefaultRate = 1000;
constexpr uint32_t kDefaultAccel = 4000;
// Fastest ramp the planner keeps ahead of (tests/sim/test_invariants.cpp;
// docs/step-engine.md).
constexpr uint32_t kMaxAccel = 800000;  // steps/s^2
constexpr uint8_t kStepPulsePadCycles = F_CPU / 1000000 * 3 / 2;  // >= 1.9 us with bookkeeping
constexpr uint8_t kTimerPulseCycles = 0;  // no timer-pulsed axis

inline void init() {
  init_inputs();
  Axes::init();
}

}  // namespace board
