// The driver-board app: the ATmega32 follows STEP/DIR/ENABLE and drives one
// unipolar motor two-phase-on, with a threshold current chopper
// (seed-002 §1, §7; docs/driver-board.md).
//
// Contract
//   - Power-up: phase state AB, all coils off until ENABLE is high.
//   - INT0 (STEP rising edge): one step in the direction DIR reads at that
//     moment, only while ENABLE reads high; ignored otherwise.
//   - ENABLE, polled by the main loop: high energises the current state, low
//     switches every coil off and keeps the phase.
//   - ADC: a chain of single conversions, each restarted by the
//     conversion-complete interrupt, alternating AC (ADC0) and BD (ADC1). A
//     reading above board::kCurrentLimit cuts that pair until its next sample.
//     No timer triggers it, so there is no trigger to forget to start.
//   - PORTB low nibble = state AND NOT cut, written in one OUT with interrupts
//     off (inside an ISR, or cli in the main loop); PB4..PB7 are read back
//     and kept.
//   - No time base (firmware/engine/clock.h): nothing here waits for a time,
//     so the image leaves Timer0 off and links no clock.

// Speed over size for this file: at -Os the helpers below stay calls and
// both ISRs save every call-clobbered register; -O2 inlines them.
#pragma GCC optimize("O2")
#include <avr/interrupt.h>
#include <avr/io.h>

#include "../../../core/motor/phase_sequencer.h"
#include "../../../hal/avr/adc.h"
#include "../../../hal/avr/ext_int.h"
#include "../../../hal/avr/gpio.h"
#include "../../../hal/avr/uart.h"
#include "../../board.h"
#include "coil_drive.h"

namespace {

using Coils = driver::CoilMap<board::CoilA::mask, board::CoilB::mask, board::CoilC::mask, board::CoilD::mask>;
using CoilPort = hal::PortBits<board::CoilA::port>;
static_assert(board::CoilB::port == board::CoilA::port && board::CoilC::port == board::CoilA::port &&
                  board::CoilD::port == board::CoilA::port,
              "the four coils are written in one port write");

// Port bits of the four two-phase states in clockwise order, states[0] = AB.
// Filled once at start-up from core/motor/phase_sequencer.h, so the sequence has one
// definition; the step interrupt then only moves a 2-bit index (a sequencer
// step in the ISR cost 122 cycles entry to RETI, the table about half).
uint8_t states[4];
uint8_t phase;       // index into states; kept while disabled
uint8_t state_bits;  // states[phase] while enabled, 0 while disabled
driver::Chopper<board::kCurrentLimit> chopper;
// Shared between both ISRs and the main loop: ISRs do not nest and the main
// loop touches them only between cli() and sei() (both memory barriers).

// Callers hold interrupts off, so the read-modify-write of the port is atomic.
inline void write_coils() { CoilPort::write(Coils::all, uint8_t(state_bits & ~chopper.cut())); }

}  // namespace

ISR(INT0_vect) {
  if (!board::EnableIn::read()) return;
  phase = uint8_t((phase + (board::DirIn::read() ? 1 : 3)) & 3);  // +1 = clockwise
  state_bits = states[phase];
  write_coils();
}

ISR(ADC_vect) {
  const uint8_t channel = hal::adc::channel();
  const uint8_t reading = hal::adc::read8();
  // The converter is idle now: switch input and start the next conversion
  // first, so the sampling period is the conversion time plus this far.
  hal::adc::select(channel == board::kSenseAC ? board::kSenseBD : board::kSenseAC);
  hal::adc::start();
  chopper.sample(channel == board::kSenseAC ? Coils::pair_a : Coils::pair_b, reading);
  write_coils();
}

int main() {
  // STEP, DIR and ENABLE stay as reset leaves them: inputs without pull-ups
  // (a pull-up on ENABLE would power the coils with the cable unplugged).
  // The USART would take PD0/PD1 (RXD/TXD) from DIR/ENABLE: its reset state
  // is off, but a bootloader may have left TXEN set, which would drive ENABLE.
  hal::uart::off();

  // Index 1 of the half-step cycle is A+B+ = AB, the seed's power-up state.
  am::PhaseSequencer sequencer(am::StepMode::two_phase, 1);
  states[0] = Coils::port_bits(sequencer.hold());
  for (uint8_t i = 1; i < 4; ++i) states[i] = Coils::port_bits(sequencer.step(true));
  CoilPort::write(Coils::all, 0);  // coils off before the pins drive
  CoilPort::output(Coils::all);

  // ADC clock F_CPU/64 = 250 kHz: above the 200 kHz the datasheet asks for
  // 10-bit accuracy, within its range for the 8 bits used here; one
  // conversion is 13 x 64 = 832 cycles.
  hal::adc::init(hal::adc::Prescaler::div64, true);
  hal::adc::select(board::kSenseAC);
  hal::adc::start();
  hal::ext_int::enable_int0_rising();
  sei();

  bool enabled = false;
  for (;;) {
    if (board::EnableIn::read() == enabled) continue;
    cli();
    enabled = board::EnableIn::read();
    state_bits = enabled ? states[phase] : 0;
    write_coils();
    sei();
  }
}
