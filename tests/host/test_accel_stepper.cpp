// AccelStepper: targets, stop, retarget, constant speed, errors, and the
// physical limits every produced step must respect.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/motion/accel_stepper.h"

namespace {

constexpr uint32_t f = 1000000;  // 1 MHz timer

struct Log {
  std::vector<am::StepOut> steps;
  int forward = 0, backward = 0;
};

// Runs until the axis rests on its target (or `limit` steps).
Log run_to_rest(am::AccelStepper& s, size_t limit = 1000000) {
  Log log;
  while (s.isRunning() && log.steps.size() < limit) {
    const am::StepOut out = s.run();
    if (out.dir == 0) break;
    log.steps.push_back(out);
    (out.dir > 0 ? log.forward : log.backward)++;
  }
  return log;
}

Log run_steps(am::AccelStepper& s, int n) {
  Log log;
  for (int i = 0; i < n; ++i) {
    const am::StepOut out = s.run();
    log.steps.push_back(out);
    (out.dir > 0 ? log.forward : log.backward)++;
  }
  return log;
}

// Signed mean speed over a step: direction * f / interval.
double mean_speed(const am::StepOut& s) { return s.dir * double(f) / s.interval; }

// Between consecutive steps the mean speed can change by at most
// a_max * (t_k + t_{k+1}) / 2 (constant acceleration within each step). Slack:
// one tick of rounding per interval moves a mean speed by f / I^2. Checked
// across a reversal as well, with signed speeds.
void expect_speed_continuity(const std::vector<am::StepOut>& steps, double a_max) {
  for (size_t i = 1; i < steps.size(); ++i) {
    const double dv = std::fabs(mean_speed(steps[i]) - mean_speed(steps[i - 1]));
    const double allowed = a_max * (steps[i].interval + steps[i - 1].interval) / (2.0 * f);
    const double rounding = double(f) / (double(steps[i].interval) * steps[i].interval) +
                            double(f) / (double(steps[i - 1].interval) * steps[i - 1].interval);
    ASSERT_LE(dv, allowed * 1.0001 + rounding) << "step " << i;
  }
}

void expect_speed_at_most(const std::vector<am::StepOut>& steps, double v_max) {
  for (size_t i = 0; i < steps.size(); ++i)
    ASSERT_LE(std::fabs(mean_speed(steps[i])), v_max * 1.001) << "step " << i;
}

am::AccelStepper make(uint32_t v, uint32_t a, uint32_t d = 0) {
  am::AccelStepper s(f);
  EXPECT_EQ(s.setMaxSpeed(v), am::MotionError::none);
  EXPECT_EQ(s.setAcceleration(a), am::MotionError::none);
  if (d) {
    EXPECT_EQ(s.setDeceleration(d), am::MotionError::none);
  }
  return s;
}

double seconds(const Log& log) {
  double t = 0;
  for (const am::StepOut& s : log.steps) t += s.interval / double(f);
  return t;
}

TEST(AccelStepper, TrapezoidMoveReachesTargetAtRestWithinLimits) {
  am::AccelStepper s = make(1000, 2000, 500);
  s.moveTo(3000);
  EXPECT_EQ(s.distanceToGo(), 3000);
  EXPECT_TRUE(s.isRunning());
  const Log log = run_to_rest(s);
  EXPECT_EQ(s.currentPosition(), 3000);
  EXPECT_EQ(log.forward, 3000);
  EXPECT_FALSE(s.isRunning());
  EXPECT_EQ(s.run().dir, 0);
  expect_speed_continuity(log.steps, 2000);
  expect_speed_at_most(log.steps, 1000);
  // Ideal trapezoid: v/2a + v/2d + N/v = 0.25 + 1 + 3 = 4.25 s. The discrete
  // profile switches phase on step boundaries; it stays within a few ms.
  EXPECT_NEAR(seconds(log), 4.25, 0.005);
  // First step: f sqrt(2/a) = 31623 ticks; the cruise: f / v = 1000 ticks.
  EXPECT_NEAR(log.steps.front().interval, 31623.0, 1.0);
  EXPECT_EQ(log.steps[1500].interval, 1000u);
  // Last step brakes from sqrt(2d) to 0: 2 / sqrt(2d) = f sqrt(2/d) = 63246.
  EXPECT_NEAR(log.steps.back().interval, 63246.0, 1.0);
}

TEST(AccelStepper, TriangleMove) {
  am::AccelStepper s = make(5000, 1000);
  s.moveTo(-400);
  const Log log = run_to_rest(s);
  EXPECT_EQ(s.currentPosition(), -400);
  EXPECT_EQ(log.backward, 400);
  expect_speed_continuity(log.steps, 1000);
  // Peak sqrt(a N) = 632.5 steps/s, total 2 sqrt(N / a) = 1.2649 s.
  EXPECT_NEAR(seconds(log), 1.2649, 0.003);
  double peak = 0;
  for (const am::StepOut& st : log.steps) peak = std::max(peak, std::fabs(mean_speed(st)));
  EXPECT_NEAR(peak, 632.5, 3.0);
}

TEST(AccelStepper, MoveToIsAbsoluteMoveIsRelative) {
  am::AccelStepper s = make(800, 4000);
  s.moveTo(500);
  run_to_rest(s);
  EXPECT_EQ(s.currentPosition(), 500);
  // seed-000 section 5: moveTo(500) then moveTo(200) -> 300 steps back.
  s.moveTo(200);
  EXPECT_EQ(s.distanceToGo(), -300);
  Log log = run_to_rest(s);
  EXPECT_EQ(log.backward, 300);
  EXPECT_EQ(log.forward, 0);
  s.move(-50);
  EXPECT_EQ(s.targetPosition(), 150);
  log = run_to_rest(s);
  EXPECT_EQ(log.backward, 50);
  EXPECT_EQ(s.currentPosition(), 150);
}

TEST(AccelStepper, OneStepMove) {
  am::AccelStepper s = make(1000, 100, 400);
  s.move(1);
  const Log log = run_to_rest(s);
  ASSERT_EQ(log.steps.size(), 1u);
  // Accelerate at a, brake at d inside the one step: f sqrt(2/a + 2/d).
  EXPECT_NEAR(log.steps[0].interval, 1e6 * std::sqrt(2.0 / 100 + 2.0 / 400), 1.0);
}

TEST(AccelStepper, StopMidRampDeceleratesWithinStoppingDistance) {
  am::AccelStepper s = make(2000, 1000, 250);
  s.moveTo(100000);
  Log before = run_steps(s, 200);  // still accelerating: 2000^2 / 2000 = 2000 ramp steps
  const double v = std::sqrt(2.0 * 1000 * 200);  // v^2 = 2 a x
  EXPECT_NEAR(s.speed(), v, 1.0);
  s.stop();
  const int32_t stopped_at = s.currentPosition();
  const double stopping = v * v / (2.0 * 250);  // 800 steps
  EXPECT_NEAR(s.targetPosition() - stopped_at, stopping, 0.5);
  const Log after = run_to_rest(s);
  EXPECT_EQ(after.backward, 0);
  EXPECT_LE(after.forward, int(std::ceil(stopping)));
  EXPECT_FALSE(s.isRunning());
  EXPECT_EQ(s.speed(), 0);
  before.steps.insert(before.steps.end(), after.steps.begin(), after.steps.end());
  expect_speed_continuity(before.steps, 1000);
  // Braking at d from v takes v / d seconds.
  EXPECT_NEAR(seconds(after), v / 250, 0.01);
}

TEST(AccelStepper, RetargetBehindReversesOnlyAfterStopping) {
  am::AccelStepper s = make(1500, 3000);
  s.moveTo(5000);
  Log log = run_steps(s, 300);
  const double v = s.speed();
  s.moveTo(0);
  const Log rest = run_to_rest(s);
  log.steps.insert(log.steps.end(), rest.steps.begin(), rest.steps.end());
  // Every forward step comes before every backward step.
  size_t first_back = 0;
  while (log.steps[first_back].dir > 0) ++first_back;
  for (size_t i = first_back; i < log.steps.size(); ++i) ASSERT_EQ(log.steps[i].dir, -1) << i;
  // Forward steps after the retarget: the stopping distance v^2 / 2d.
  EXPECT_LE(rest.forward, int(std::ceil(v * v / (2.0 * 3000))));
  EXPECT_GE(rest.forward, int(std::floor(v * v / (2.0 * 3000))) - 1);
  // At the turn the motor is at rest: the last forward step and the first
  // backward one are the slowest of their neighbourhood (speed ~ sqrt(2a)).
  EXPECT_LT(std::fabs(mean_speed(log.steps[first_back - 1])), 60.0);
  EXPECT_LT(std::fabs(mean_speed(log.steps[first_back])), 60.0);
  EXPECT_EQ(s.currentPosition(), 0);
  expect_speed_continuity(log.steps, 3000);
}

TEST(AccelStepper, RetargetAheadWithinStoppingDistanceOvershootsAndReturns) {
  am::AccelStepper s = make(1000, 1000);
  s.moveTo(10000);
  Log log = run_steps(s, 600);  // cruising at 1000 (ramp = 500 steps)
  EXPECT_EQ(s.speed(), 1000);
  s.moveTo(s.currentPosition() + 100);  // needs 500 steps to stop
  const Log rest = run_to_rest(s);
  log.steps.insert(log.steps.end(), rest.steps.begin(), rest.steps.end());
  EXPECT_EQ(s.currentPosition(), 700);
  EXPECT_EQ(rest.forward, 500);
  EXPECT_EQ(rest.backward, 400);
  expect_speed_continuity(log.steps, 1000);
}

TEST(AccelStepper, RetargetFurtherWhileBrakingAcceleratesAgain) {
  am::AccelStepper s = make(1000, 1000);
  s.moveTo(2000);
  Log log = run_steps(s, 1800);  // braking since step 1500
  const int32_t v_braking = s.speed();
  EXPECT_LT(v_braking, 1000);
  s.moveTo(4000);
  const Log rest = run_to_rest(s);
  log.steps.insert(log.steps.end(), rest.steps.begin(), rest.steps.end());
  EXPECT_EQ(rest.backward, 0);
  EXPECT_EQ(s.currentPosition(), 4000);
  expect_speed_continuity(log.steps, 1000);
  expect_speed_at_most(log.steps, 1000);
}

TEST(AccelStepper, LoweringMaxSpeedWhileCruisingBrakesAtDecel) {
  am::AccelStepper s = make(2000, 4000, 1000);
  s.moveTo(20000);
  Log log = run_steps(s, 1000);
  EXPECT_EQ(s.speed(), 2000);
  ASSERT_EQ(s.setMaxSpeed(500), am::MotionError::none);
  const Log rest = run_to_rest(s);
  log.steps.insert(log.steps.end(), rest.steps.begin(), rest.steps.end());
  expect_speed_continuity(log.steps, 4000);
  // (2000^2 - 500^2) / 2d = 1875 steps later it cruises at 500.
  EXPECT_EQ(log.steps[1000 + 1875 + 10].interval, 2000u);
  EXPECT_EQ(s.currentPosition(), 20000);
}

TEST(AccelStepper, ConstantSpeedMode) {
  am::AccelStepper s(f);
  EXPECT_EQ(s.runSpeed().dir, 0);  // no speed set yet
  ASSERT_EQ(s.setSpeed(-250), am::MotionError::none);
  for (int i = 0; i < 10; ++i) {
    const am::StepOut out = s.runSpeed();
    EXPECT_EQ(out.interval, 4000u);
    EXPECT_EQ(out.dir, -1);
  }
  EXPECT_EQ(s.currentPosition(), -10);
  // 3 steps/s: 333333.33 ticks; the fraction is carried, so three steps take
  // one second to the tick.
  ASSERT_EQ(s.setSpeed(3), am::MotionError::none);
  uint32_t total = 0;
  for (int i = 0; i < 3; ++i) total += s.runSpeed().interval;
  EXPECT_EQ(total, 1000000u);
  EXPECT_EQ(s.currentPosition(), -7);
}

TEST(AccelStepper, ZeroAndOutOfRangeAreRejected) {
  am::AccelStepper s(f);
  EXPECT_EQ(s.setMaxSpeed(0), am::MotionError::zero_speed);
  EXPECT_EQ(s.setAcceleration(0), am::MotionError::zero_accel);
  EXPECT_EQ(s.setDeceleration(0), am::MotionError::zero_accel);
  EXPECT_EQ(s.setSpeed(0), am::MotionError::zero_speed);
  EXPECT_EQ(s.setMaxSpeed(f), am::MotionError::out_of_range);
  EXPECT_EQ(s.setAcceleration(uint32_t(1) << 25), am::MotionError::out_of_range);
  EXPECT_EQ(s.setSpeed(-int32_t(f)), am::MotionError::out_of_range);
  // Unconfigured: no step, no division.
  s.moveTo(10);
  EXPECT_EQ(s.run().dir, 0);
  EXPECT_EQ(s.currentPosition(), 0);
  // A rejected value keeps the previous one.
  ASSERT_EQ(s.setMaxSpeed(100), am::MotionError::none);
  ASSERT_EQ(s.setAcceleration(100), am::MotionError::none);
  EXPECT_EQ(s.setMaxSpeed(0), am::MotionError::zero_speed);
  run_to_rest(s);
  EXPECT_EQ(s.currentPosition(), 10);
  am::AccelStepper bad_clock(0);
  EXPECT_EQ(bad_clock.setMaxSpeed(10), am::MotionError::out_of_range);
}

TEST(AccelStepper, SetCurrentPositionRedefinesAtRest) {
  am::AccelStepper s = make(1000, 1000);
  s.moveTo(1000);
  run_steps(s, 100);
  s.setCurrentPosition(0);
  EXPECT_FALSE(s.isRunning());
  EXPECT_EQ(s.speed(), 0);
  EXPECT_EQ(s.targetPosition(), 0);
  EXPECT_EQ(s.run().dir, 0);
  s.moveTo(10);
  const Log log = run_to_rest(s);
  // Starts from rest again: the first interval is f sqrt(2/a).
  EXPECT_NEAR(log.steps.front().interval, 1e6 * std::sqrt(2.0 / 1000), 1.0);
}

}  // namespace
