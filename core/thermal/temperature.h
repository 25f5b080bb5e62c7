// Temperatures as the heater core passes them around: an integer in 1/100 C
// with the sensor's state beside it, so a broken sensor can never be read as
// a temperature.
//
// Contract
//   TempReading::centi is the temperature in hundredths of a degree Celsius
//   (int16_t: -327.68 .. 327.67 C) and means something only when state is
//   SensorState::ok. open: the reading lies beyond the cold end of the
//   thermistor table (open circuit, unplugged, or colder than the table);
//   shorted: beyond the hot end (short circuit, or hotter than the table).
//   Targets use the same unit; a target <= 0 means "heater off".
#pragma once
#include <stdint.h>

namespace am {

enum class SensorState : uint8_t { ok, open, shorted };

struct TempReading {
  int16_t centi;  // 0.01 C, valid when state == ok
  SensorState state;

  constexpr bool ok() const { return state == SensorState::ok; }
  static constexpr TempReading celsius_centi(int16_t c) { return TempReading{c, SensorState::ok}; }
  static constexpr TempReading fault(SensorState s) { return TempReading{0, s}; }
};

// Whole degrees to the unit (compile-time constants: limits, defaults).
constexpr int16_t centi_c(int16_t degrees) { return int16_t(degrees * 100); }

}  // namespace am
