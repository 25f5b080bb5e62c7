// avrmotion-profile's computations: seed-000 section 3.3's torque-speed worked
// example, the stall check, argument handling.
#include <gtest/gtest.h>

#include <cmath>

#include "tools/profile/profile.h"

namespace {

using namespace am::profile;

// seed-000 3.3: 15 degree motor (24 steps/rev), J = 2e-4 kg m^2, T_L = 0.1 N m,
// T = 0.35 below 100 steps/s, 0.426 - 0.00075 f from 100 to 435.
Motor seed_motor() {
  return Motor({{0, 0.35}, {100, 0.35}, {100, 0.426 - 0.00075 * 100}, {435, 0.426 - 0.00075 * 435}},
               0.1, 2e-4, 24);
}

constexpr double k = 24 / (2 * M_PI * 2e-4);  // n p / (2 pi J)

TEST(ProfileTool, SeedWorkedExampleReaches100StepsPerSecondIn21ms) {
  const Motor m = seed_motor();
  EXPECT_NEAR(m.max_accel(50), 0.25 * k, 1e-9);  // 4774.6 steps/s^2
  // "100 steps/s reached after 21 ms (t = 0.2094 f ms)".
  EXPECT_NEAR(m.time_to_reach(100) * 1e3, 20.94, 0.01);
  EXPECT_NEAR(m.time_to_reach(50) * 1e3, 0.2094 * 50, 0.01);
}

TEST(ProfileTool, SeedWorkedExampleAboveTheCorner) {
  const Motor m = seed_motor();
  // On 0.426 - 0.00075 f the equation integrates to a logarithm:
  // t(100 -> f) = ln((0.326 - 0.075) / (0.326 - 0.00075 f)) / (0.00075 k).
  const double above = std::log(0.251 / (0.326 - 0.00075 * 300)) / (0.00075 * k);
  EXPECT_NEAR(m.time_to_reach(300), 100 / (0.25 * k) + above, 2e-5);
  // Pull-out 435 steps/s; never reached with the load beyond it.
  EXPECT_NEAR(m.pull_out_rate(), 435, 0.5);
  EXPECT_TRUE(std::isinf(m.time_to_reach(440)));
  // The load helps braking: (T + T_L) k.
  EXPECT_NEAR(m.max_decel(50), 0.45 * k, 1e-9);
}

TEST(ProfileTool, StallFoundWhereTheMotorRunsOutOfTorque) {
  // 4000 steps/s^2 exceeds (0.326 - 0.00075 f) k above f = 155.4 steps/s.
  const double limit = (0.326 - 4000 / k) / 0.00075;
  ASSERT_NEAR(limit, 155.4, 0.1);
  Options o;
  ASSERT_EQ(parse_args({"--steps", "300", "--speed", "300", "--accel", "4000", "--spr", "24"}, o), "");
  std::string error;
  const std::vector<uint32_t> intervals = plan_intervals(o, error);
  ASSERT_EQ(error, "");
  const StallReport r = check_ramp(intervals, o.tick_hz, seed_motor());
  ASSERT_FALSE(r.follows);
  // Reported at the first speed past the limit; steps here change the speed
  // by 4000 * ~5.5 ms = 22 steps/s.
  EXPECT_GT(r.rate, limit);
  EXPECT_LT(r.rate, limit + 25);
  EXPECT_NEAR(r.required, 4000, 0.05 * 4000);
  EXPECT_LT(r.available, r.required);
}

TEST(ProfileTool, GentleRampIsFollowed) {
  // At 300 steps/s the motor still gives (0.326 - 0.225) k = 1929 steps/s^2.
  Options o;
  ASSERT_EQ(parse_args({"--steps", "300", "--speed", "300", "--accel", "1500", "--spr", "24"}, o), "");
  std::string error;
  const StallReport r = check_ramp(plan_intervals(o, error), o.tick_hz, seed_motor());
  EXPECT_TRUE(r.follows) << r.step << " " << r.rate;
}

TEST(ProfileTool, CruiseAbovePullOutStalls) {
  Options o;
  ASSERT_EQ(parse_args({"--steps", "2000", "--speed", "450", "--accel", "100", "--spr", "24"}, o), "");
  std::string error;
  const StallReport r = check_ramp(plan_intervals(o, error), o.tick_hz, seed_motor());
  ASSERT_FALSE(r.follows);
  // 100 steps/s^2 runs out where (0.326 - 0.00075 f) k = 100: f = 427.7.
  EXPECT_NEAR(r.rate, (0.326 - 100 / k) / 0.00075, 1.0);
}

TEST(ProfileTool, MethodsUseTheFirmwareRamps) {
  Options o;
  ASSERT_EQ(parse_args({"--steps", "400", "--speed", "670", "--accel", "3185", "--method", "seed"}, o), "");
  EXPECT_EQ(o.decel, 3185u);  // defaults to accel
  std::string error;
  std::vector<uint32_t> seed = plan_intervals(o, error);
  ASSERT_EQ(seed.size(), 400u);
  EXPECT_NEAR(seed[0], 0.676 * 1e6 * std::sqrt(2.0 / 3185), 1.0);
  ASSERT_EQ(parse_args({"--method", "exact"}, o), "");
  std::vector<uint32_t> exact = plan_intervals(o, error);
  ASSERT_EQ(exact.size(), 400u);
  EXPECT_NEAR(exact[0], 1e6 * std::sqrt(2.0 / 3185), 1.0);
}

TEST(ProfileTool, BadArgumentsGiveClearErrors) {
  Options o;
  EXPECT_EQ(parse_args({"--steps", "10", "--speed", "0", "--accel", "5"}, o),
            "bad value for --speed: '0' (expected a whole number >= 1)");
  o = Options{};
  EXPECT_EQ(parse_args({"--steps", "10", "--speed", "100"}, o), "--accel is required (>= 1 steps/s^2)");
  o = Options{};
  EXPECT_EQ(parse_args({"--steps", "10", "--speed", "100", "--accel", "-3"}, o),
            "bad value for --accel: '-3' (expected a whole number >= 1)");
  EXPECT_EQ(parse_args({"--method", "fast"}, o), "bad value for --method: 'fast' (expected seed or exact)");
  EXPECT_EQ(parse_args({"--frobnicate", "1"}, o), "unknown option --frobnicate");
  EXPECT_EQ(parse_args({"--steps"}, o), "--steps needs a value");
  EXPECT_EQ(parse_args({"--torque", "100:0.3,50:0.4"}, o),
            "bad value for --torque: '100:0.3,50:0.4' (expected RATE:NM pairs, rates ascending)");
  o = Options{};
  EXPECT_EQ(parse_args({"--steps", "10", "--speed", "100", "--accel", "5", "--torque", "0:0.3"}, o),
            "--torque needs --inertia (kg m^2, > 0)");
  // Limits of the exact method come back as text, not a crash.
  o = Options{};
  ASSERT_EQ(parse_args({"--steps", "10", "--speed", "10000", "--accel", "1", "--tick-hz", "16000000"}, o), "");
  std::string error;
  EXPECT_TRUE(plan_intervals(o, error).empty());
  EXPECT_EQ(error, "outside the exact method's limits (see docs/ramps.md)");
}

}  // namespace
