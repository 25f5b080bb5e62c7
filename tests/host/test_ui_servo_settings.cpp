// The DC-servo leadscrew's settings block (core/ui/settings.h,
// Settings<Drive::servo>): its fields and ranges, its layout against the
// stepper's, the gains it hands the PID (core/lathe/servo_pid.h) checked
// against the coefficients' definitions in real numbers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/lathe/servo_pid.h"
#include "core/ui/settings.h"

namespace {

using am::ui::Drive;
using Servo = am::ui::Settings<Drive::servo>;
using Stepper = am::ui::Settings<Drive::stepper>;

// The seed's servo machine: a 40-slot disc, the 3.175 mm leadscrew, 30
// pulses behind 1:26, reversed, 1800 counts/s, the seed's gains.
const Servo kSeedServo = {{40, 0, 3175, 0, 30, 26, 1, 1800, 72037, 82608, 672}, 0};

TEST(UiServoSettings, FieldsAndRanges) {
  ASSERT_EQ(am::ui::field_count(Drive::servo), 11);
  ASSERT_EQ(am::ui::field_count(Drive::stepper), 8);
  EXPECT_STREQ(am::ui::field<Drive::servo>(am::ui::kFieldMotorSteps).label, "Pulses/motor rev");
  EXPECT_STREQ(am::ui::field<Drive::servo>(am::ui::kFieldMicrosteps).label, "Gearbox 1:N");
  EXPECT_STREQ(am::ui::field<Drive::stepper>(am::ui::kFieldMotorSteps).label, "Steps/rev");
  for (uint8_t f = 0; f < am::ui::field_count(Drive::servo); ++f)
    EXPECT_LE(std::strlen(am::ui::field<Drive::servo>(f).label), 16u) << int(f);
  // One channel on the servo's spindle; the rapid rate is the servo's.
  EXPECT_EQ(am::ui::field<Drive::servo>(am::ui::kFieldQuadrature).max, 0);
  EXPECT_EQ(am::ui::field<Drive::servo>(am::ui::kFieldRapid).max, 1800);
  EXPECT_EQ(am::ui::field<Drive::stepper>(am::ui::kFieldRapid).max, 20000);
  // The shared fields keep the stepper's ranges.
  for (uint8_t f : {am::ui::kFieldEncoderLines, am::ui::kFieldLeadUm, am::ui::kFieldLeadTpi, am::ui::kFieldReversed}) {
    EXPECT_EQ(am::ui::field<Drive::servo>(f).min, am::ui::field<Drive::stepper>(f).min) << int(f);
    EXPECT_EQ(am::ui::field<Drive::servo>(f).max, am::ui::field<Drive::stepper>(f).max) << int(f);
  }
}

TEST(UiServoSettings, DefaultsMachineAndGains) {
  Servo s{};
  EXPECT_FALSE(am::ui::load_settings(s, kSeedServo));  // a zero block: the defaults
  ASSERT_TRUE(am::ui::settings_valid(s));
  const am::Machine m = am::ui::machine(s);
  EXPECT_EQ(m.leadscrew_counts.num, 780u);  // 30 x 26
  EXPECT_EQ(m.leadscrew_counts.den, 1u);
  EXPECT_EQ(m.spindle_counts, 40);
  EXPECT_TRUE(m.leadscrew_reversed);
  const am::ServoGains g = am::ui::servo_gains(s);
  EXPECT_EQ(g.kp_milli, 72037u);
  EXPECT_EQ(g.ki_milli, 82608u);
  EXPECT_EQ(g.kd_milli, 672u);
}

TEST(UiServoSettings, EachFieldAtAndBeyondItsBounds) {
  for (uint8_t f = 0; f < am::ui::field_count(Drive::servo); ++f) {
    const am::ui::FieldSpec spec = am::ui::field<Drive::servo>(f);
    for (int64_t v : {int64_t(spec.min) - 1, int64_t(spec.min), int64_t(spec.max), int64_t(spec.max) + 1}) {
      if (v < 0) continue;
      Servo s = kSeedServo;
      s.value[f] = uint32_t(v);
      am::ui::seal(s);
      EXPECT_EQ(am::ui::settings_valid(s), v >= spec.min && v <= spec.max) << int(f) << " " << v;
    }
  }
}

// A stepper's block where a servo's is expected (and the other way round),
// with the rest of the cells erased or zero, never passes: the layouts
// start their sums from different versions.
TEST(UiServoSettings, TheOtherDrivesBlockIsRefused) {
  Stepper st = {{40, 0, 3175, 0, 200, 1, 0, 4000}, 0};
  am::ui::seal(st);
  ASSERT_TRUE(am::ui::settings_valid(st));
  for (uint8_t fill : {uint8_t(0x00), uint8_t(0xFF)}) {
    Servo sv;
    std::memset(&sv, fill, sizeof sv);
    std::memcpy(&sv, &st, sizeof st);
    EXPECT_FALSE(am::ui::settings_valid(sv)) << int(fill);
  }
  Servo sv = kSeedServo;
  am::ui::seal(sv);
  Stepper as_stepper;
  std::memcpy(&as_stepper, &sv, sizeof as_stepper);
  EXPECT_FALSE(am::ui::settings_valid(as_stepper));
  // The same values under the stepper's version do not pass as a servo's.
  std::memcpy(sv.value, st.value, sizeof st.value);
  sv.check = st.check;
  EXPECT_FALSE(am::ui::settings_valid(sv));
}

// Every gain the fields accept is one the PID takes, for every sample period
// from kServoMinSampleUs; and the coefficients are the definitions rounded:
// Kp x 256 (duty/2^8 per count/2^8), Ki Ts x 2^16, Kd / Ts x 256.
TEST(UiServoSettings, AcceptedGainsGiveTheDefinedCoefficients) {
  std::mt19937 rng(11);
  const am::ui::FieldSpec kp = am::ui::field<Drive::servo>(am::ui::kFieldKp);
  const am::ui::FieldSpec ki = am::ui::field<Drive::servo>(am::ui::kFieldKi);
  const am::ui::FieldSpec kd = am::ui::field<Drive::servo>(am::ui::kFieldKd);
  int checked = 0;
  for (uint32_t period : {am::kServoMinSampleUs, 1024u, 2048u, 5000u, 65535u}) {
    for (int i = 0; i < 4000; ++i) {
      am::ServoGains g;
      // The corners first, then values across the ranges.
      g.kp_milli = i < 8 ? (i & 1 ? uint32_t(kp.max) : 0) : std::uniform_int_distribution<uint32_t>(0, kp.max)(rng);
      g.ki_milli = i < 8 ? (i & 2 ? uint32_t(ki.max) : 0) : std::uniform_int_distribution<uint32_t>(0, ki.max)(rng);
      g.kd_milli = i < 8 ? (i & 4 ? uint32_t(kd.max) : 0) : std::uniform_int_distribution<uint32_t>(0, kd.max)(rng);
      const am::ServoCoefficients c = am::servo_coefficients(g, period);
      ASSERT_TRUE(c.ok) << g.kp_milli << " " << g.ki_milli << " " << g.kd_milli << " " << period;
      const double ts = period * 1e-6;
      EXPECT_LE(std::fabs(c.kp - g.kp_milli / 1000.0 * 256), 0.5) << g.kp_milli;
      EXPECT_LE(std::fabs(c.ki - g.ki_milli / 1000.0 * ts * 65536), 0.5 + 1e-9) << g.ki_milli << " " << period;
      // Kd / Ts is rounded to 0.001 duty per count first: 0.128 more.
      EXPECT_LE(std::fabs(c.kd - g.kd_milli / 1000.0 / ts * 256), 0.5 + 0.128 + 1e-9) << g.kd_milli << " " << period;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 20000);
  // Beyond the PID's own ranges: refused, whatever the overflow would give.
  EXPECT_FALSE(am::servo_coefficients({0, 0, 0xFFFFFFFFu}, 1024).ok);
  EXPECT_FALSE(am::servo_coefficients({0xFFFFFFFFu, 0, 0}, 1024).ok);
  EXPECT_FALSE(am::servo_coefficients({0, 0xFFFFFFFFu, 0}, 1024).ok);
  EXPECT_FALSE(am::servo_coefficients({0, 0, 4097}, 1024).ok);  // Kd / Ts = 4001 duty per count
  EXPECT_TRUE(am::servo_coefficients({0, 0, 4096}, 1024).ok);
}

}  // namespace
