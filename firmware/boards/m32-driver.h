// Board: the seed-002 stepper driver board, an ATmega32 that is itself a
// step/dir driver for one unipolar motor (docs/driver-board.md).
// avrmotion-board: mcu=atmega32 f_cpu=16000000 app=driver_board
//
// Inputs (TTL from the motion controller): STEP on INT0 = PD2, every rising
// edge one step while ENABLE is high; DIR on PD0 (high = clockwise =
// forward); ENABLE on PD1 (high = coils powered). PD0/PD1 are the USART pins,
// so the UART stays off. Low-side coil transistors a, c, b, d on PB0..PB3;
// coil-pair current sense AC on ADC0 (PA0), BD on ADC1 (PA1).
//
// The descriptor names the coils in the sequencer's order IN1..IN4 = A+, B+,
// A-, B- = a, b, c, d = PB0, PB2, PB1, PB3, so the simulator decodes the rotor
// from PORTB.
#pragma once
#include "../../hal/avr/claims.h"
#include "../../hal/avr/gpio.h"
#include "../axes/axis_set.h"
#include "../axes/unipolar_axis.h"

namespace board {

using hal::Pin;
using StepIn = Pin<'D', 2>;    // INT0, rising edge
using DirIn = Pin<'D', 0>;
using EnableIn = Pin<'D', 1>;
using CoilA = Pin<'B', 0>;     // a = A+
using CoilC = Pin<'B', 1>;     // c = A-
using CoilB = Pin<'B', 2>;     // b = B+
using CoilD = Pin<'B', 3>;     // d = B-

constexpr uint8_t kSenseAC = 0;  // ADC channel of the a/c pair's sense resistor
constexpr uint8_t kSenseBD = 1;  // ADC channel of the b/d pair's
// Chopper threshold in 8-bit counts: 100/256 x 5 V (AVCC) = 1.95 V (seed-002 §7).
constexpr uint8_t kCurrentLimit = 100;

// One full step is one basic length unit of 1 um, as on the m32 controller.
using Axes = AxisSet<UnipolarAxis<'M', CoilA, CoilB, CoilC, CoilD, 1000000>>;

// Unused by this image (no UART: PD0/PD1 are DIR/ENABLE); descriptor.cpp
// records it and the simulator's serial model needs a non-zero rate.
// Hardware claims (hal/avr/claims.h, checked when the image compiles): STEP
// on INT0, the chopper's current sense on the ADC, the UART. No step clock,
// and no time base: the image follows its inputs and the ADC's conversion
// chain paces the chopper, so nothing in it waits for a time (its app does
// not link firmware/engine/clock.cpp). Timers 0, 1 and 2 are free.
using Claims = hal::ClaimSet<hal::claim::int0, hal::claim::adc, hal::claim::uart, Axes::Claims::all>;

constexpr uint32_t kBaud = 115200;

}  // namespace board
