// The hot end's heater service (docs/heater.md), for a board whose header
// declares a heater (board::kHeater, board::Heater: its PWM, TEMP_OK pin and
// ADC channel). The cnc program links it only there (apps/cnc/app.cmake);
// every call from shared code sits under `if (board::kHeater)`, a
// compile-time false elsewhere that avr-gcc removes with the call.
//
// Contract
//   init() once, after board::init() (which already drives the MOSFET low)
//   and before clock::init() and sei(): PWM off, a first reading taken (16
//   conversions, 1.9 ms, before the time base runs: with interrupts off it
//   would lose an overflow), the ADC converting the thermistor.
//   poll() from the main loop, as often as it turns. The ADC is polled, not
//   interrupt-driven (nothing is added to the step interrupt's latency):
//   every finished conversion goes into a 16-sample oversampler (12 bits).
//   Every 125 ms (kPeriodMs, clock::due: no drift) the latest 12-bit value
//   becomes a temperature (core/thermal/thermistor.h), the PID (or a running
//   autotune) asks for a duty, HeaterSafety decides what is applied, and
//   OC2 and TEMP_OK are set.
//   A fault (any HeaterSafety rule) latches until reset: the heater is off
//   whatever the PID or an autotune asks, the target 0 (a waiting M303 ends
//   at once and puts the PID back: heater_codes.h), and one line
//   `Error:<fault text>, heater halted until reset` goes out at once;
//   set_target() and autotune() refuse from then on.
//   Auto-report (M155): every `seconds` one line `T:<cur> /<target> @:<duty>`.
#pragma once
#include <stdint.h>

#include "../../core/thermal/autotune.h"
#include "../../core/thermal/pid.h"
#include "../../core/thermal/safety.h"
#include "../../core/thermal/temperature.h"

namespace heater {

constexpr uint16_t kPeriodMs = am::HeaterPid::kDefaultPeriodMs;

void init();
// The loop's turn; in a machine alarm (firmware/engine/limits.h) it also
// turns the heater off, once (`heater off: alarm`).
void poll();

// False (nothing changes) once a fault has latched, or while the machine is
// in an alarm.
bool set_target(int16_t centi);
int16_t target();  // what the heater holds now (an autotune's while it runs)
am::TempReading reading();
am::HeaterFault fault();
const char* fault_text();  // in flash: write_P()

// The PID's gains (Marlin's units, thousandths), while no autotune is on
// (the two share their RAM); set_gains() is HeaterPid::set_gains (false and
// nothing changes outside its ranges).
const am::PidGains& gains();
bool set_gains(const am::PidGains& g);
// M500: the gains into the EEPROM (a tag and a checksum with them); init()
// takes them back on every reset when the tag and the checksum hold and
// set_gains() accepts them, Marlin's defaults otherwise. On a board with
// settings (board::kSettings) the gains are its $300..302 instead: init()
// takes Marlin's defaults, settings::boot() puts the stored ones in force,
// the settings' M500 stores those in force (store_gains() is not used).
void store_gains();
// Starts an autotune (target, cycles; the rest Marlin's defaults); false
// once a fault has latched or in an alarm. While it is on, the PID rests with its gains
// kept; it ends with autotune_end(): `apply` and a finished tune whose gains
// set_gains() takes put them in force (true), anything else keeps the old
// gains (false). The target is 0 (off) afterwards.
bool autotune(int16_t centi, uint8_t cycles);
bool autotune_end(bool apply);
const am::RelayAutotune* tuning();  // nullptr while no autotune is on

void auto_report(uint8_t seconds);  // 0: off
// The status `T:<cur> /<target> @:<duty>` as a line of its own, in the
// board's style (docs/heater.md): as it is in Marlin's, `[MSG:...]` in
// grbl's (a grbl host takes any other line for an answer or ignores it).
void write_status_line();
void write_centi(int32_t hundredths);  // "-12.34"

}  // namespace heater
