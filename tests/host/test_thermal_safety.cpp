// core/thermal/safety.h: every rule just inside and just outside its limit
// and its time, the latch, the messages and TEMP_OK.
#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "core/thermal/safety.h"

namespace {

using am::HeaterFault;
using am::HeaterSafety;
using am::SensorState;
using am::TempReading;

TempReading c(double celsius) { return TempReading::celsius_centi(int16_t(celsius * 100 + (celsius < 0 ? -0.5 : 0.5))); }
const TempReading kOpen = TempReading::fault(SensorState::open);
const TempReading kShort = TempReading::fault(SensorState::shorted);
constexpr int16_t k200 = 20000;

// --- sensor faults ---

TEST(ThermalSafety, OpenSensorLatchesAfter500ms) {
  HeaterSafety s;
  EXPECT_EQ(s.check(1000, c(200), k200, 120), 120);
  EXPECT_EQ(s.check(1125, kOpen, k200, 255), 0);  // no temperature: no heat, not yet a fault
  EXPECT_FALSE(s.faulted());
  EXPECT_EQ(s.check(1624, kOpen, k200, 255), 0);
  EXPECT_FALSE(s.faulted());  // 499 ms
  EXPECT_EQ(s.check(1625, kOpen, k200, 255), 0);
  EXPECT_EQ(s.fault(), HeaterFault::sensor_open);  // 500 ms
}

TEST(ThermalSafety, ShortedSensorLatchesAndHeaterOffDoesNotMatter) {
  HeaterSafety s;
  s.check(0, kShort, 0, 0);
  s.check(499, kShort, 0, 0);
  EXPECT_FALSE(s.faulted());
  s.check(500, kShort, 0, 0);
  EXPECT_EQ(s.fault(), HeaterFault::sensor_shorted);
}

TEST(ThermalSafety, ABadReadingShorterThan500msIsForgiven) {
  HeaterSafety s;
  s.check(0, kOpen, k200, 255);
  s.check(400, kOpen, k200, 255);
  EXPECT_EQ(s.check(450, c(200), k200, 90), 90);  // good again: the timer restarts
  s.check(500, kOpen, k200, 255);
  s.check(999, kOpen, k200, 255);
  EXPECT_FALSE(s.faulted());
  s.check(1000, kOpen, k200, 255);
  EXPECT_EQ(s.fault(), HeaterFault::sensor_open);
}

TEST(ThermalSafety, SensorBreakLatchedWithinOneSecondAtAnyPhase) {
  // The wire breaks at t_break; samples every 125 ms (the PID period) at any phase.
  for (uint32_t phase = 0; phase < 125; phase += 5) {
    HeaterSafety s;
    const uint32_t t_break = 10000 + phase;
    uint32_t latched = 0;
    for (uint32_t t = 0; t < 15000 && !latched; t += 125) {
      s.check(t, t < t_break ? c(210) : kOpen, 21000, 100);
      if (s.faulted()) latched = t;
    }
    ASSERT_NE(latched, 0u);
    EXPECT_LT(latched - t_break, 1000u) << phase;
  }
}

// --- MAXTEMP / MINTEMP ---

TEST(ThermalSafety, MaxtempBoundaryAlwaysChecked) {
  HeaterSafety a;
  EXPECT_EQ(a.check(0, c(275.00), 0, 0), 0);
  EXPECT_FALSE(a.faulted());
  EXPECT_EQ(a.check(125, c(275.00), 26000, 200), 200);
  EXPECT_FALSE(a.faulted());
  EXPECT_EQ(a.check(250, c(275.01), 0, 0), 0);
  EXPECT_EQ(a.fault(), HeaterFault::maxtemp);
}

TEST(ThermalSafety, MintempOnlyWhileAskedToHeat) {
  HeaterSafety s;
  EXPECT_EQ(s.check(0, c(-5), 0, 0), 0);  // off in a cold room: fine
  EXPECT_FALSE(s.faulted());
  EXPECT_EQ(s.check(125, c(5.00), k200, 255), 255);
  EXPECT_FALSE(s.faulted());
  s.check(250, c(4.99), k200, 255);
  EXPECT_EQ(s.fault(), HeaterFault::mintemp);
}

// --- thermal runaway while holding ---

TEST(ThermalSafety, RunawayAfter40sBelowTargetMinus4C) {
  HeaterSafety s;
  // Heat up (not at full power, so the watch stays out of it), reach 200.00.
  s.check(0, c(150), k200, 200);
  s.check(1000, c(199.99), k200, 200);
  s.check(2000, c(200.00), k200, 150);
  // Exactly target - 4 C for a long time is still holding.
  for (uint32_t t = 2125; t <= 100000; t += 125) s.check(t, c(196.00), k200, 150);
  EXPECT_FALSE(s.faulted());
  // 195.99 C from just after the last reading on the line (t = 100000).
  for (uint32_t t = 100125; t < 140000; t += 125) s.check(t, c(195.99), k200, 150);
  s.check(139999, c(195.99), k200, 150);
  EXPECT_FALSE(s.faulted());  // 39.999 s
  s.check(140000, c(195.99), k200, 150);
  EXPECT_EQ(s.fault(), HeaterFault::runaway);  // 40 s
}

TEST(ThermalSafety, NoRunawayBeforeTheTargetIsReached) {
  HeaterSafety s;
  for (uint32_t t = 0; t <= 200000; t += 125) s.check(t, c(180), k200, 200);
  EXPECT_FALSE(s.faulted());
}

TEST(ThermalSafety, ATargetChangeRestartsTheFirstHeating) {
  HeaterSafety s;
  s.check(0, c(200), k200, 100);  // reached: holding
  // Raised to 230 C: 200 C is 30 C low, but the new target was never reached.
  for (uint32_t t = 125; t <= 100000; t += 125) s.check(t, c(200), 23000, 200);
  EXPECT_FALSE(s.faulted());
  // Same target again after a pause at 0 (off): first heating again too.
  s.check(100125, c(200), 0, 0);
  for (uint32_t t = 100250; t <= 200000; t += 125) s.check(t, c(190), k200, 200);
  EXPECT_FALSE(s.faulted());
}

// --- heating watch ---

TEST(ThermalSafety, WatchNeeds2CIn20sAtFullPower) {
  HeaterSafety fail;
  fail.check(5000, c(25.00), k200, 255);  // the window starts here
  fail.check(24999, c(25.00), k200, 255);
  EXPECT_FALSE(fail.faulted());
  fail.check(25000, c(26.99), k200, 255);
  EXPECT_EQ(fail.fault(), HeaterFault::heating_failed);

  HeaterSafety pass;
  pass.check(5000, c(25.00), k200, 255);
  pass.check(25000, c(27.00), k200, 255);  // exactly 2 C: passes, next window from 27.00
  EXPECT_FALSE(pass.faulted());
  pass.check(44999, c(27.00), k200, 255);
  pass.check(45000, c(28.99), k200, 255);
  EXPECT_EQ(pass.fault(), HeaterFault::heating_failed);
}

TEST(ThermalSafety, WatchOnlyAtFullPowerAndWithATarget) {
  HeaterSafety s;
  s.check(0, c(25), k200, 255);
  s.check(10000, c(25), k200, 254);  // left full power: watch ends
  s.check(15000, c(25), k200, 255);  // a new window from here
  s.check(34999, c(25), k200, 255);
  EXPECT_FALSE(s.faulted());
  s.check(35000, c(25), k200, 255);
  EXPECT_EQ(s.fault(), HeaterFault::heating_failed);

  HeaterSafety off;
  for (uint32_t t = 0; t < 100000; t += 125) off.check(t, c(25), 0, 255);
  EXPECT_FALSE(off.faulted());
}

// --- latch, reset, order ---

TEST(ThermalSafety, LatchedFaultForcesZeroUntilReset) {
  HeaterSafety s;
  s.check(0, c(280), k200, 0);
  ASSERT_EQ(s.fault(), HeaterFault::maxtemp);
  for (uint32_t t = 125; t < 10000; t += 125) EXPECT_EQ(s.check(t, c(200), k200, 255), 0);
  EXPECT_EQ(s.fault(), HeaterFault::maxtemp);  // the first fault stays named
  s.check(10000, kOpen, k200, 255);
  s.check(20000, kOpen, k200, 255);
  EXPECT_EQ(s.fault(), HeaterFault::maxtemp);
  s.reset();
  EXPECT_FALSE(s.faulted());
  EXPECT_EQ(s.check(20125, c(200), k200, 255), 255);
  s.check(20250, c(276), k200, 255);  // and the rules still hold after a reset
  EXPECT_EQ(s.fault(), HeaterFault::maxtemp);
}

TEST(ThermalSafety, CustomLimits) {
  am::SafetyLimits bed;
  bed.maxtemp = am::centi_c(120);
  bed.runaway_period_ms = 20000;
  bed.runaway_hysteresis = am::centi_c(2);
  bed.watch_period_ms = 60000;
  HeaterSafety s(bed);
  s.check(0, c(120.00), 11000, 0);
  EXPECT_FALSE(s.faulted());
  s.check(125, c(120.01), 11000, 0);
  EXPECT_EQ(s.fault(), HeaterFault::maxtemp);
}

TEST(ThermalSafety, TimesSurviveTheMillisecondWrap) {
  HeaterSafety s;
  const uint32_t t0 = 0xFFFFFF00u;
  s.check(t0, c(25), k200, 255);
  s.check(t0 + 19999u, c(25), k200, 255);  // wraps through 0
  EXPECT_FALSE(s.faulted());
  s.check(t0 + 20000u, c(25), k200, 255);
  EXPECT_EQ(s.fault(), HeaterFault::heating_failed);
}

// --- messages and TEMP_OK ---

TEST(ThermalSafety, EveryFaultHasAnIdAndAShortDistinctMessage) {
  EXPECT_STREQ(am::heater_fault_message(HeaterFault::none), "");
  EXPECT_STREQ(am::heater_fault_message(HeaterFault::maxtemp), "MAXTEMP triggered");
  EXPECT_STREQ(am::heater_fault_message(HeaterFault::mintemp), "MINTEMP triggered");
  EXPECT_STREQ(am::heater_fault_message(HeaterFault::runaway), "Thermal Runaway");
  EXPECT_STREQ(am::heater_fault_message(HeaterFault::heating_failed), "Heating failed");
  for (uint8_t i = 1; i < am::kHeaterFaultCount; ++i) {
    const char* m = am::heater_fault_message(HeaterFault(i));
    EXPECT_GT(std::strlen(m), 0u) << int(i);
    EXPECT_LT(std::strlen(m), size_t(am::kHeaterFaultTextSize)) << int(i);
    for (uint8_t j = 1; j < i; ++j) EXPECT_STRNE(m, am::heater_fault_message(HeaterFault(j)));
  }
  EXPECT_STREQ(am::heater_fault_message(HeaterFault(99)), "");
  EXPECT_EQ(std::string("Error:") + am::heater_fault_message(HeaterFault::sensor_open),
            "Error:Thermistor open");
}

TEST(ThermalSafety, TempOkHoldsThroughTheHysteresis) {
  // Rising into the band: on at 197.00, not at 196.99.
  EXPECT_FALSE(am::temp_ok(c(196.99), k200, am::kTempOkBand, false));
  EXPECT_TRUE(am::temp_ok(c(197.00), k200, am::kTempOkBand, false));
  // Once on: still on out to 4 C off, off beyond, both sides.
  for (double t : {196.0, 196.5, 203.5, 204.0}) EXPECT_TRUE(am::temp_ok(c(t), k200, am::kTempOkBand, true)) << t;
  for (double t : {195.99, 204.01}) EXPECT_FALSE(am::temp_ok(c(t), k200, am::kTempOkBand, true)) << t;
  HeaterSafety s;
  EXPECT_TRUE(s.temp_ok(c(196.5), k200, true));
  EXPECT_FALSE(s.temp_ok(c(196.5), k200, false));
}

TEST(ThermalSafety, TempOkBandIsInclusive) {
  EXPECT_TRUE(am::temp_ok(c(203.00), k200));
  EXPECT_TRUE(am::temp_ok(c(197.00), k200));
  EXPECT_FALSE(am::temp_ok(c(203.01), k200));
  EXPECT_FALSE(am::temp_ok(c(196.99), k200));
  EXPECT_TRUE(am::temp_ok(c(200.50), k200, 50));
  EXPECT_FALSE(am::temp_ok(c(200.51), k200, 50));
  EXPECT_FALSE(am::temp_ok(kOpen, k200));
  EXPECT_FALSE(am::temp_ok(c(0), 0));  // off is never "at temperature"
  HeaterSafety s;
  EXPECT_TRUE(s.temp_ok(c(200), k200));
  s.check(0, c(300), k200, 0);
  EXPECT_FALSE(s.temp_ok(c(200), k200));  // not while faulted
}

}  // namespace
