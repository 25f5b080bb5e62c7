// The ATmega16 lathe controller's wiring (seed-004 section 4), shared by the
// two programs it can run: firmware/boards/m16.h (the step/dir protocol
// image, app cnc) and firmware/boards/m16-lathe.h (the electronic leadscrew,
// app lathe).
//
// Leadscrew on a step/dir driver: step PC0, direction PC1, enable PC7
// (active low) on the 3.175 mm (8 TPI) leadscrew. HD44780 on PORTA (PA0-PA3
// data D4-D7, PA4 RS, PA5 RW, PA6 E), 4x4 keypad on PORTB (PB7..PB4 columns
// out, PB3..PB0 rows in): declared here for the operator interface, claimed
// by no part of the leadscrew. Motor encoder INT0 (PD2), spindle encoder INT1
// (PD3), spindle index PD6, limit switch PD7 (normally high, pulled up),
// L298 enable PWM on OC1A (PD5). The thesis put the L298 direction on
// PD0/PD1, which are the UART here: the m16-servo (firmware/boards/
// m16-servo.h) puts them on PC0/PC1, the stepper's pins it does not use. PC2..PC5 need JTAG off (main() does that
// on every ATmega16/32).
#pragma once
#include "../../../hal/avr/claims.h"
#include "../../../hal/avr/gpio.h"

namespace m16_wiring {

using hal::Pin;

using LeadStep = Pin<'C', 0>;
using LeadDir = Pin<'C', 1>;
using LeadEnable = Pin<'C', 7>;  // active low
using MotorEncoder = Pin<'D', 2>;    // INT0
using SpindleEncoder = Pin<'D', 3>;  // INT1
using L298Enable = Pin<'D', 5>;      // OC1A
using SpindleIndex = Pin<'D', 6>;
using LimitSwitch = Pin<'D', 7>;

// The operator interface (LCD on PORTA, keypad on PORTB).
using LcdD4 = Pin<'A', 0>;
using LcdD5 = Pin<'A', 1>;
using LcdD6 = Pin<'A', 2>;
using LcdD7 = Pin<'A', 3>;
using LcdRs = Pin<'A', 4>;
using LcdRw = Pin<'A', 5>;
using LcdE = Pin<'A', 6>;
using KeypadColumn0 = Pin<'B', 7>;  // columns PB7..PB4, driven
using KeypadColumn3 = Pin<'B', 4>;
using KeypadRow0 = Pin<'B', 3>;     // rows PB3..PB0, inputs with pull-ups
using KeypadRow3 = Pin<'B', 0>;

// Timer0 is the time base (firmware/engine/clock.h; keypad debounce, the
// lathe program's timeouts): its own, in normal mode with prescaler 64, one
// tick per 4 us at 16 MHz (8 us at 8 MHz), an overflow interrupt every 16384
// cycles (28 of them, 0.2 % of the CPU); OC0 (PB3, a keypad row) stays a
// port pin. Timer2 is free.
constexpr uint32_t kClock = hal::claim::timer0_ovf | hal::claim::timer0 | hal::claim::timer0_div64;

// 115200 at 16 MHz (UBRR 16 with U2X: 117647 baud, +2.1 %); at 8 MHz the
// nearest divisor for 115200 gives 111111 (-3.5 %, outside the datasheet's
// recommended +-2 %), so the 8 MHz image talks at 38400 (38462, +0.2 %).
constexpr uint32_t kBaud = F_CPU >= 16000000UL ? 115200 : 38400;

// The inputs, pulled up, and the L298's enable low (motor free) before
// anything else runs.
inline void init_inputs() {
  L298Enable::low();
  L298Enable::output();
  MotorEncoder::input_pullup();
  SpindleEncoder::input_pullup();
  SpindleIndex::input_pullup();
  LimitSwitch::input_pullup();
}

}  // namespace m16_wiring
