// NTC thermistor: ADC reading -> temperature, by interpolation in a table the
// compiler computes from the thermistor's parameters and the divider.
//
// Contract
//   Circuit: the NTC from the ADC input to ground, a pull-up resistor from the
//   input to the ADC reference (ratiometric: the reference cancels). An N-bit
//   reading r says the input lies in [r, r + 1) / 2^N of the reference and is
//   taken at the bin's centre x = (r + 1/2) / 2^N, so R = R_pullup x / (1 - x)
//   (for the opposite divider pass 2^N - 1 - r).
//   Model, T in kelvin, R in ohm: 1/T = a + b ln R + c (ln R)^3 (Steinhart-
//   Hart); the Beta model is the case a = 1/T0 - ln(R0)/beta, b = 1/beta, c = 0.
//
//   ThermistorTable<N>(spec) holds N points at temperatures evenly spaced from
//   spec.t_hi_c down to spec.t_lo_c, in increasing x: each point is x rounded
//   to 1/65536 of full scale (uint16) and the model's temperature at exactly
//   that x, rounded to 0.01 C (int16). It is built by constexpr code with
//   const_ln/const_exp in the compiler's double (32-bit on avr-gcc; the
//   default table dumped from an ATmega32 image is byte for byte the host's),
//   4 bytes a point, no code in the image.
//
//   thermistor_temperature<Bits>(table, r, fetch) interpolates linearly in x
//   between the two points around r and returns the temperature in 0.01 C
//   (integer only: a binary search, one 32-bit multiply and one division;
//   about 1900 cycles on the ATmega32 with the table in flash).
//   A reading beyond the cold end (x above the t_lo point) is SensorState::open
//   (open circuit, or colder than the table), beyond the hot end shorted; the
//   end points themselves are inside. `fetch` loads a point: the default reads
//   memory, the firmware passes one that reads a PROGMEM table with LPM.
//
// Default (kHotendThermistor, 34 points, 136 bytes): 100 kOhm at 25 C, beta
// 3950, 4.7 kOhm pull-up, -10 .. 320 C every 10 C. Measured against a double
// model (tests/host/test_thermal_thermistor.cpp), 20 .. 300 C:
//   resolution, C per 10-bit count: 0.61 at 20 C, 0.14 at 100 C, 0.47 at
//     200 C, 1.09 at 250 C, 2.37 at 300 C (four times finer at 12 bits);
//   interpolation error (12-bit readings) at most 0.43 C, worst near 20-30 C;
//     at most 0.22 C over 150 .. 300 C.
#pragma once
#include <stdint.h>

#include "const_math.h"
#include "temperature.h"

namespace am {

struct ThermistorSpec {
  double a, b, c;         // 1/T = a + b ln R + c ln^3 R (kelvin, ohm)
  double pullup_ohm;      // from the ADC input to the reference
  double t_lo_c, t_hi_c;  // table range, Celsius
};

constexpr double kKelvinOffset = 273.15;

constexpr ThermistorSpec beta_thermistor(double r0_ohm, double t0_c, double beta, double pullup_ohm,
                                         double t_lo_c, double t_hi_c) {
  return ThermistorSpec{1.0 / (t0_c + kKelvinOffset) - const_ln(r0_ohm) / beta, 1.0 / beta, 0.0,
                        pullup_ohm, t_lo_c, t_hi_c};
}

constexpr ThermistorSpec steinhart_hart_thermistor(double a, double b, double c, double pullup_ohm,
                                                   double t_lo_c, double t_hi_c) {
  return ThermistorSpec{a, b, c, pullup_ohm, t_lo_c, t_hi_c};
}

constexpr ThermistorSpec kHotendThermistor = beta_thermistor(100000.0, 25.0, 3950.0, 4700.0, -10.0, 320.0);
constexpr uint8_t kHotendThermistorPoints = 34;

struct ThermistorPoint {
  uint16_t x;     // input / reference, 1/65536
  int16_t centi;  // temperature, 0.01 C
};

namespace thermistor_detail {

// Model temperature (Celsius) at input fraction x (0 < x < 1).
constexpr double celsius_at(const ThermistorSpec& s, double x) {
  const double l = const_ln(s.pullup_ohm * x / (1 - x));
  return 1.0 / (s.a + s.b * l + s.c * l * l * l) - kKelvinOffset;
}

// Input fraction at a temperature: ln R from the model by Newton's method
// (monotonic cubic; the Beta case is exact at the first step), then the divider.
constexpr double fraction_at(const ThermistorSpec& s, double celsius) {
  const double y = 1.0 / (celsius + kKelvinOffset);
  double l = (y - s.a) / s.b;
  for (int i = 0; i < 8; ++i) l -= (s.a + s.b * l + s.c * l * l * l - y) / (s.b + 3 * s.c * l * l);
  const double r = const_exp(l);
  return r / (r + s.pullup_ohm);
}

}  // namespace thermistor_detail

template <uint8_t N>
struct ThermistorTable {
  static_assert(N >= 2, "two points at least");
  static constexpr uint8_t size = N;
  ThermistorPoint point[N];

  constexpr explicit ThermistorTable(const ThermistorSpec& s) : point() {
    for (uint8_t i = 0; i < N; ++i) {
      const double celsius = s.t_hi_c - (s.t_hi_c - s.t_lo_c) * i / (N - 1);
      const double xq = thermistor_detail::fraction_at(s, celsius) * 65536.0;
      const uint16_t x = uint16_t(xq + 0.5);
      const double t = thermistor_detail::celsius_at(s, x / 65536.0) * 100.0;
      point[i] = ThermistorPoint{x, int16_t(t < 0 ? t - 0.5 : t + 0.5)};
    }
  }

  // Strictly increasing x, decreasing temperature, no point at 0 or full scale:
  // what the lookup relies on (static_assert it on a custom table).
  constexpr bool valid() const {
    if (point[0].x == 0) return false;
    for (uint8_t i = 1; i < N; ++i)
      if (point[i].x <= point[i - 1].x || point[i].centi >= point[i - 1].centi) return false;
    return true;
  }
};

struct DirectFetch {
  ThermistorPoint operator()(const ThermistorPoint* p) const { return *p; }
};

template <uint8_t Bits, uint8_t N, typename Fetch = DirectFetch>
TempReading thermistor_temperature(const ThermistorTable<N>& table, uint16_t reading,
                                   Fetch fetch = Fetch()) {
  static_assert(Bits >= 8 && Bits <= 15, "8 to 15-bit readings");
  if (reading >= (1u << Bits)) return TempReading::fault(SensorState::open);
  const uint16_t x = uint16_t(((uint32_t(reading) << 1) | 1u) << (15 - Bits));
  const ThermistorPoint* p = table.point;
  if (x < fetch(p).x) return TempReading::fault(SensorState::shorted);
  if (x > fetch(p + N - 1).x) return TempReading::fault(SensorState::open);
  // Largest i with point[i].x <= x (i <= N - 2: the segment i, i + 1).
  uint8_t lo = 0, hi = N - 1;
  while (hi - lo > 1) {
    const uint8_t mid = uint8_t((lo + hi) >> 1);
    if (fetch(p + mid).x <= x) lo = mid; else hi = mid;
  }
  const ThermistorPoint a = fetch(p + lo), b = fetch(p + lo + 1);
  const int32_t dx = int32_t(b.x) - a.x;
  const int32_t num = int32_t(b.centi - a.centi) * int32_t(x - a.x);  // <= 0
  return TempReading::celsius_centi(int16_t(a.centi + (num - dx / 2) / dx));
}

}  // namespace am
