// The seed's heater controller (seed-002 §8), restated here as a small
// reference model from the digest's facts, against the vectors derived there,
// and contrasted with core/thermal: what changes when the loop works in
// temperature, with anti-windup and fault handling.
//
// The seed's controller, as the digest gives it: the raw 8-bit ADC reading
// compared with REFERENCE_TEMP = 190 counts (no table), u = Kp e + Ki Ts sum e
// + (Kd / Ts)(e - e_prev) with KP 200, KI 1, KD 500 in raw counts (the
// vectors show Ts folded into the constants: e = 1 from rest gives
// 200 + 1 + 500 = 701), an int16 sum with no anti-windup, output clamped to
// 0..255, TEMP_OK when |REF - ADC| < 5, the reading stored as int8_t (values
// >= 128 become negative), no sensor-fault handling.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "core/thermal/pid.h"
#include "core/thermal/safety.h"
#include "core/thermal/thermistor.h"

namespace {

struct SeedPid {
  static constexpr int32_t kp = 200, ki = 1, kd = 500;
  int16_t sum = 0, prev = 0;
  int32_t last_unclamped = 0;

  uint8_t update(int16_t e) {
    sum = int16_t(uint16_t(sum) + uint16_t(e));  // int16, wraps as the AVR does
    last_unclamped = kp * e + ki * sum + kd * (e - prev);
    prev = e;
    return uint8_t(last_unclamped < 0 ? 0 : last_unclamped > 255 ? 255 : last_unclamped);
  }
};

constexpr int16_t kSeedReference = 190;  // REFERENCE_TEMP, counts
// Error from a raw 8-bit reading, as stored by the seed (int8_t).
int16_t seed_error(uint8_t adc) { return int16_t(kSeedReference - int8_t(adc)); }
bool seed_temp_ok(uint8_t adc) { return std::abs(kSeedReference - int(adc)) < 5; }

TEST(ThermalSeedPid, DigestVectorsFromRest) {
  SeedPid s;
  EXPECT_EQ(s.update(0), 0);
  EXPECT_EQ(s.last_unclamped, 0);
  EXPECT_EQ(s.update(1), 255);
  EXPECT_EQ(s.last_unclamped, 701);
  EXPECT_EQ(s.update(1), 202);
  EXPECT_EQ(s.last_unclamped, 202);
  EXPECT_EQ(s.update(0), 0);
  EXPECT_LT(s.last_unclamped, 0);  // 0 + 2 - 500
  EXPECT_EQ(s.last_unclamped, -498);
}

// "Any |e| >= 2 at steady state saturates": the seed is nearly on/off.
TEST(ThermalSeedPid, AnErrorOfTwoCountsSaturates) {
  for (int e : {2, 3, 5, 50}) {
    SeedPid s;
    s.update(int16_t(e));
    for (int n = 0; n < 20; ++n) EXPECT_EQ(s.update(int16_t(e)), 255) << e;
  }
  for (int e : {-1, -2, -5}) {
    SeedPid s;
    for (int n = 0; n < 20; ++n) EXPECT_EQ(s.update(int16_t(e)), 0) << e;
  }
  // Ours, Marlin's hotend gains: 2 C of error is 44 duty, proportionate.
  am::HeaterPid ours;
  ASSERT_TRUE(ours.set_gains({22200, 1080, 114000}));
  EXPECT_NEAR(ours.update(am::TempReading::celsius_centi(19800), 20000), 44.4 + 0.27, 1);
}

// No anti-windup: the int16 sum of a cold start (e = 50 counts) wraps after
// 656 conversions, about 0.4 s at the seed's ~1.6 kHz, and the heater goes
// off while the hotend is still cold. Ours keeps the integral within 0..255
// duty and stops integrating while saturated.
TEST(ThermalSeedPid, IntegralWrapsDuringAColdStart) {
  SeedPid s;
  int first_off = -1;
  for (int n = 0; n < 2000 && first_off < 0; ++n)
    if (s.update(50) == 0) first_off = n;
  EXPECT_EQ(first_off, 655);  // sum reaches 32800 > 32767 at the 656th sample
  am::HeaterPid ours;
  ASSERT_TRUE(ours.set_gains({22200, 1080, 114000}));
  for (int n = 0; n < 100000; ++n) ASSERT_EQ(ours.update(am::TempReading::celsius_centi(2500), 20000), 255);
  EXPECT_EQ(ours.integral_term(), 0);  // saturated from the start: nothing wound up
}

// The int8_t reading: 128..255 become -128..-1. The reference itself (190)
// lies in that range, so at the setpoint the error is 190 - (-66) = 256, not
// 0: full power at the setpoint. Below 128 the error is right.
TEST(ThermalSeedPid, ReadingsFrom128AreNegative) {
  EXPECT_EQ(seed_error(190), 256);
  EXPECT_EQ(seed_error(200), 246);  // 10 counts past the reference: should be -10
  EXPECT_EQ(seed_error(127), 63);
  EXPECT_EQ(seed_error(128), 318);
  SeedPid s;
  for (int n = 0; n < 10; ++n) EXPECT_EQ(s.update(seed_error(kSeedReference)), 255);
  SeedPid right;  // the same reading as unsigned: no demand at the setpoint
  EXPECT_EQ(right.update(int16_t(kSeedReference - 190)), 0);
}

// No fault handling: an open thermistor on the NTC-to-ground divider reads
// full scale (255), a short 0; the seed answers a number either way. Ours
// reports the faults, gives 0 duty and latches the fault within 1 s.
TEST(ThermalSeedPid, BrokenSensorIsJustANumber) {
  SeedPid open, shorted;
  EXPECT_EQ(open.update(seed_error(255)), 255);    // int8 -1: error 191
  EXPECT_EQ(shorted.update(seed_error(0)), 255);   // error 190
  constexpr am::ThermistorTable<am::kHotendThermistorPoints> table(am::kHotendThermistor);
  const am::TempReading r_open = am::thermistor_temperature<10>(table, 1023);
  const am::TempReading r_short = am::thermistor_temperature<10>(table, 0);
  am::HeaterPid pid;
  ASSERT_TRUE(pid.set_gains({22200, 1080, 114000}));
  EXPECT_EQ(pid.update(r_open, 20000), 0);
  EXPECT_EQ(pid.update(r_short, 20000), 0);
  am::HeaterSafety safety;
  for (uint32_t t = 0; t <= 1000; t += 125) safety.check(t, r_open, 20000, 255);
  EXPECT_EQ(safety.fault(), am::HeaterFault::sensor_open);
}

// Raw counts are not degrees: the seed's +-5-count TEMP_OK band, mapped
// through the default divider (8-bit reading), is a fraction of a degree
// near 100 C and several degrees near 250 C. Ours is 3 C everywhere.
TEST(ThermalSeedPid, TempOkBandInCountsIsNotABandInDegrees) {
  constexpr am::ThermistorTable<am::kHotendThermistorPoints> table(am::kHotendThermistor);
  auto count_at = [](double celsius) {
    const double r = 100000 * std::exp(3950 * (1 / (celsius + 273.15) - 1 / 298.15));
    return int(std::floor(256 * r / (r + 4700)));
  };
  auto band_c = [&](double celsius) {  // width of the |REF - ADC| < 5 window, in C
    const int ref = count_at(celsius);
    const am::TempReading hi = am::thermistor_temperature<8>(table, uint16_t(ref - 4));
    const am::TempReading lo = am::thermistor_temperature<8>(table, uint16_t(ref + 4));
    return (hi.centi - lo.centi) / 100.0;
  };
  const double at100 = band_c(100), at250 = band_c(250);
  std::printf("  seed TEMP_OK window (9 counts, 8-bit): %.1f C wide at 100 C, %.1f C at 250 C\n",
              at100, at250);
  EXPECT_LT(at100, 6.0);
  EXPECT_GT(at250, 30.0);
  EXPECT_TRUE(seed_temp_ok(uint8_t(kSeedReference + 4)));
  EXPECT_FALSE(seed_temp_ok(uint8_t(kSeedReference + 5)));
  EXPECT_TRUE(am::temp_ok(am::TempReading::celsius_centi(25300), 25000));
  EXPECT_FALSE(am::temp_ok(am::TempReading::celsius_centi(25301), 25000));
}

}  // namespace
