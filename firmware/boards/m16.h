// Board: ATmega16 lathe controller (seed-004 section 4).
// avrmotion-board: mcu=atmega16 f_cpu=16000000,8000000 app=cnc
//
// Leadscrew on a step/dir driver (axis Z): step PC0, direction PC1, enable
// PC7 (active low); a 200-step motor on the 3.175 mm leadscrew gives
// 62992 steps per metre. Also on the board: HD44780 on PORTA (PA0-PA3 data,
// PA4 RS, PA5 RW, PA6 E), 4x4 keypad on PORTB (PB7..PB4 columns out, PB3..PB0
// rows in), motor encoder INT0 (PD2), spindle encoder INT1 (PD3), spindle index
// PD6, limit switch PD7, L298 enable PWM on OC1A (PD5). The thesis put the L298
// direction on PD0/PD1, which are the UART here; the servo option will move
// them. Axis U: a ULN2003 unipolar motor on PC2..PC5, which need JTAG off
// (main() does that on every ATmega16/32).
#pragma once
#include "../../hal/avr/claims.h"
#include "../../hal/avr/gpio.h"
#include "../axes/axis_set.h"
#include "../axes/step_dir_axis.h"
#include "../axes/unipolar_axis.h"

namespace board {

using hal::Pin;
using Axes = AxisSet<StepDirAxis<'Z', Pin<'C', 0>, Pin<'C', 1>, Pin<'C', 7>, true, 62992>,
                     UnipolarAxis<'U', Pin<'C', 2>, Pin<'C', 3>, Pin<'C', 4>, Pin<'C', 5>, 4096>>;

// 115200 at 16 MHz (UBRR 16 with U2X: 117647 baud, +2.1 %); at 8 MHz the
// nearest divisor for 115200 gives 111111 (-3.5 %, outside the datasheet's
// recommended +-2 %), so the 8 MHz image talks at 38400 (38462, +0.2 %).
// Hardware claims (hal/avr/claims.h, checked when the image compiles): Timer1
// is the step clock, the UART talks to the host, Timer0 is the time base
// (firmware/engine/clock.h; keypad debounce, the lathe program's timeouts):
// its own, in normal mode with prescaler 64, one tick per 4 us at 16 MHz
// (8 us at 8 MHz), an overflow interrupt every 16384 cycles (28 of them,
// 0.2 % of the CPU); OC0 (PB3, a keypad row) stays a port pin. Timer2 is
// free. The seed's DC-servo leadscrew drives its L298 from OC1A (PD5), which
// needs Timer1 for PWM: a servo variant of this board cannot also claim
// Timer1 as a step clock.
constexpr uint32_t kStepClock = hal::claim::timer1;
constexpr uint32_t kClock = hal::claim::timer0_ovf | hal::claim::timer0 | hal::claim::timer0_div64;
using Claims = hal::ClaimSet<kStepClock, kClock, hal::claim::uart, Axes::Claims::all>;

constexpr uint32_t kBaud = F_CPU >= 16000000UL ? 115200 : 38400;
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
  Pin<'D', 5>::low();  // L298 enable: motor free until the servo runs
  Pin<'D', 5>::output();
  Pin<'D', 2>::input_pullup();
  Pin<'D', 3>::input_pullup();
  Pin<'D', 6>::input_pullup();
  Pin<'D', 7>::input_pullup();
  Axes::init();
}

}  // namespace board
