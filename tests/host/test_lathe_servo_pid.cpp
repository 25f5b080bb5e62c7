// core/lathe/servo_pid.h against the seed's AVR221-style test vectors
// (digest section 3: P 2 with error 10 -> 20, error 600 -> 1023, error <= 0
// -> 0; I with Ki Ts = 1 and error 5 over three samples -> 5, 10, 15) and
// against a reference written in doubles.
#include "core/lathe/servo_pid.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace {

constexpr int32_t kQ = 256;  // one count in Q8

am::ServoPid make(uint32_t kp_milli, uint32_t ki_milli, uint32_t kd_milli, uint32_t period_us = 1000) {
  am::ServoPid pid;
  EXPECT_TRUE(pid.set(am::servo_coefficients({kp_milli, ki_milli, kd_milli}, period_us)));
  return pid;
}

TEST(ServoPid, SeedProportionalVectors) {
  am::ServoPid pid = make(2000, 0, 0);
  EXPECT_EQ(pid.update(10 * kQ, 0), 20);
  EXPECT_EQ(pid.update(600 * kQ, 0), 1023);
  EXPECT_EQ(pid.update(0, 0), 0);
  EXPECT_EQ(pid.update(-5 * kQ, 0), 0);
  EXPECT_EQ(pid.update(-600 * kQ, 0), 0);
}

TEST(ServoPid, SeedIntegralVectors) {
  // Ki Ts = 1 duty per count per sample: Ki = 1000 /s at Ts = 1 ms.
  am::ServoPid pid = make(0, 1000000, 0);
  EXPECT_EQ(pid.update(5 * kQ, 0), 5);
  EXPECT_EQ(pid.update(5 * kQ, 0), 10);
  EXPECT_EQ(pid.update(5 * kQ, 0), 15);
}

TEST(ServoPid, DerivativeOnTheErrorsChange) {
  // Kd / Ts = 10 duty per count: Kd = 0.01 duty s per count at 1 ms.
  am::ServoPid pid = make(0, 0, 10);
  EXPECT_EQ(pid.update(0, 0), 0);
  EXPECT_EQ(pid.update(3 * kQ, 0), 30);
  EXPECT_EQ(pid.update(3 * kQ, 0), 0);
  EXPECT_EQ(pid.update(1 * kQ, 500), 480);  // -20 on the feedforward
}

TEST(ServoPid, FeedforwardAndOffIsOff) {
  am::ServoPid pid = make(1000, 0, 0);
  EXPECT_EQ(pid.update(0, 700), 700);
  EXPECT_EQ(pid.update(-700 * kQ / 1000, 0), 0);  // -0.7 duty: off, exactly
  EXPECT_EQ(pid.update(kQ / 2, 0), 1);              // 0.5 duty rounds up
  EXPECT_EQ(pid.update(kQ / 2 - 1, 0), 0);          // just below half a count
  EXPECT_EQ(pid.update(0, 1023), 1023);
  EXPECT_EQ(pid.update(10 * kQ, 1023), 1023);
  EXPECT_EQ(am::ServoPid::duty(-1), 0);
  EXPECT_EQ(am::ServoPid::duty(int32_t(1022) << 16), 1022);
}

TEST(ServoPid, AntiWindupHoldsTheIntegralAtTheRails) {
  am::ServoPid pid = make(2000, 100000, 0);  // Kp 2, Ki Ts 0.1 duty per count per sample
  // Saturated high for 5000 samples with an error of 200 counts (P = 400
  // duty): the integral grows only while the output is below the rail, so
  // it stops at 1023 - 400 duty plus at most one step (20 duty).
  int at_rail = 0;
  for (int i = 0; i < 5000; ++i) at_rail += pid.update(200 * kQ, 0) == 1023;
  EXPECT_GE(at_rail, 4960);
  const int32_t held = pid.integral();
  EXPECT_GE(held, int32_t(1023 - 400) << 16);
  EXPECT_LE(held, int32_t(1023 - 400 + 20) << 16);
  // The error reverses: the output leaves the rail at once (no minutes of
  // wound-up integral): the integral it held, less P and one step.
  const uint16_t u = pid.update(-20 * kQ, 0);
  EXPECT_LE(u, (held >> 16) - 40 + 1);
  EXPECT_GE(u, (held >> 16) - 40 - 3);
  // Saturated low (output 0, error negative): the integral does not sink.
  am::ServoPid low = make(10000, 100000, 0);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(low.update(-50 * kQ, 0), 0);
  EXPECT_EQ(low.integral(), 0);
}

TEST(ServoPid, RangesRefused) {
  EXPECT_FALSE(am::servo_coefficients({256000, 0, 0}, 1000).ok);
  EXPECT_FALSE(am::servo_coefficients({0, 2000001, 0}, 1000).ok);
  EXPECT_FALSE(am::servo_coefficients({0, 0, 4001}, 1000).ok);  // Kd/Ts 4001 duty per count
  EXPECT_FALSE(am::servo_coefficients({1000, 0, 0}, 99).ok);
  EXPECT_FALSE(am::servo_coefficients({1000, 0, 0}, 65536).ok);
  EXPECT_TRUE(am::servo_coefficients({255000, 2000000, 4000}, 1000).ok);
  am::ServoPid pid = make(2000, 0, 0);
  EXPECT_FALSE(pid.set(am::servo_coefficients({256000, 0, 0}, 1000)));
  EXPECT_EQ(pid.update(10 * kQ, 0), 20);  // the old gains kept
}

// The law in doubles, with the same clamps and the same conditional
// integration; the fixed point stays within a duty count of it.
TEST(ServoPid, MatchesADoubleReference) {
  std::mt19937 rng(11);
  const uint32_t periods[] = {1024, 500, 2048};
  for (uint32_t period : periods) {
    const am::ServoGains g{72037, 82608, 672};  // the seed's tuning
    am::ServoPid pid;
    ASSERT_TRUE(pid.set(am::servo_coefficients(g, period)));
    const double ts = period * 1e-6;
    const double kp = g.kp_milli / 1000.0, ki = g.ki_milli / 1000.0, kd = g.kd_milli / 1000.0;
    double integral = 0, last = 0;
    bool primed = false;
    std::uniform_int_distribution<int32_t> err(-40 * kQ, 40 * kQ);
    std::uniform_int_distribution<int> ffd(0, 1023);
    int worst = 0;
    for (int i = 0; i < 200000; ++i) {
      int32_t eq = err(rng);
      if (i % 7) eq = eq / 16;  // mostly small errors, some large
      const uint16_t ff = uint16_t(i % 3 ? ffd(rng) : 0);
      // The clamps: |P|, |D| <= 2048 duty, an integral step <= 64 duty.
      const double e = double(eq) / kQ;
      const double dlim = 2048 / (kd / ts), plim = 2048 / kp, ilim = 64 / (ki * ts);
      const double de = primed ? std::clamp(e - last, -dlim, dlim) : 0;
      last = e;
      primed = true;
      const double base = ff + kp * std::clamp(e, -plim, plim) + kd / ts * de;
      const double before = base + integral;
      if (!((before >= 1023 && e > 0) || (before <= 0 && e < 0)))
        integral = std::clamp(integral + ki * ts * std::clamp(e, -ilim, ilim), -1023.0, 1023.0);
      const double u = base + integral;
      const int want = u >= 1022.5 ? 1023 : u < 0.5 ? 0 : int(std::floor(u + 0.5));
      const int got = pid.update(eq, ff);
      worst = std::max(worst, std::abs(got - want));
      // Re-align the reference's integral on the fixed point's (the two
      // drift apart by rounding only; the comparison is per update).
      integral = pid.integral() / 65536.0;
    }
    EXPECT_LE(worst, 1) << "Ts " << period << " us";
  }
}

}  // namespace
