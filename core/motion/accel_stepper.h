// AccelStepper-like motion for one axis: absolute/relative targets, stop and
// retarget while moving, constant-speed mode, producing the timer interval of
// every step for the step queue.
//
// Contract
//   Positions are signed steps. run() returns the next step of the move toward
//   targetPosition(): its interval (timer ticks since the previous step) and
//   direction (+1 / -1), and counts it in currentPosition(); {0, 0} when the
//   axis is at rest on its target. runSpeed() does the same at the constant
//   speed of setSpeed(), ignoring the target (AccelStepper's runSpeed()).
//   moveTo(), move(), stop(), setMaxSpeed(), setAcceleration() and
//   setDeceleration() may be called at any time; the next run() continues from
//   the current speed, so the speed never jumps:
//     - a target ahead within reach: accelerate (a), cruise, decelerate (d) so
//       the speed reaches zero exactly on the target;
//     - a target behind, or ahead but closer than the stopping distance: brake
//       at d, stop past it, then move back from rest (reversal only at rest);
//     - stop(): the target becomes the nearest point the axis can stop at
//       with decel d (ceil(v^2 / 2d) steps ahead).
//   Setters reject 0 and out-of-range values with a MotionError and keep the
//   previous setting, so nothing downstream divides by zero.
//
// Kinematics (integer only; main loop, not the ISR)
//   The state is the squared speed E = v^2 (steps^2/s^2, exact integer) at the
//   last step. Under constant acceleration v^2 grows linearly with distance,
//   so each step sets E' = min(E + 2a, vmax^2, 2d (D - 1)) with D the steps
//   left (the last term is the braking parabola that ends at rest on the
//   target), or E' = E - 2d when braking. The step then takes exactly
//   2 / (v + v') seconds (distance over mean speed under constant
//   acceleration). Speeds come from isqrt64 in Q12 and intervals are kept in
//   Q8 ticks with the fraction carried, so rounding never accumulates.
//   The profile accelerates and brakes at whole-step boundaries: it is the
//   exact motion of piecewise-constant acceleration per step, |accel| <= a, d.
//
// Limits: tick rate 1 .. 2^24 Hz; max speed 1 .. min(2^19, tick rate / 2)
// steps/s; accel, decel 1 .. 2^24 steps/s^2; setSpeed() |v| within the same
// bounds as max speed. Intervals longer than the step queue's 16.7 M ticks
// (a < 2 (f / 16.7e6)^2 on the first step) are the caller's to split.
#pragma once
#include <stdint.h>
#include "../math/isqrt.h"

namespace am {

enum class MotionError : uint8_t { none, zero_speed, zero_accel, out_of_range };

struct StepOut {
  uint32_t interval;  // ticks since the previous step; 0 = no step
  int8_t dir;         // +1 forward, -1 backward, 0 = no step
};

class AccelStepper {
 public:
  explicit AccelStepper(uint32_t tick_hz) : tick_hz_(tick_hz) {}

  MotionError setMaxSpeed(uint32_t steps_per_s) {
    const MotionError err = check_speed(steps_per_s);
    if (err == MotionError::none) max_speed_ = steps_per_s;
    return err;
  }
  // Sets the acceleration, and the deceleration too until setDeceleration().
  MotionError setAcceleration(uint32_t steps_per_s2) {
    const MotionError err = check_accel(steps_per_s2);
    if (err != MotionError::none) return err;
    accel_ = steps_per_s2;
    if (!separate_decel_) decel_ = steps_per_s2;
    return err;
  }
  MotionError setDeceleration(uint32_t steps_per_s2) {
    const MotionError err = check_accel(steps_per_s2);
    if (err != MotionError::none) return err;
    decel_ = steps_per_s2;
    separate_decel_ = true;
    return err;
  }
  // Constant speed for runSpeed(), signed steps/s.
  MotionError setSpeed(int32_t steps_per_s) {
    const uint32_t magnitude = steps_per_s < 0 ? 0u - uint32_t(steps_per_s) : uint32_t(steps_per_s);
    const MotionError err = check_speed(magnitude);
    if (err == MotionError::none) {
      const_speed_ = steps_per_s;
      const_rest_ = 0;
    }
    return err;
  }

  void moveTo(int32_t absolute) { target_ = absolute; }
  void move(int32_t relative) { target_ = pos_ + relative; }
  void stop() {
    if (e_ == 0) {
      target_ = pos_;
      return;
    }
    const uint64_t two_d = 2 * uint64_t(decel_);
    target_ = pos_ + dir_ * int32_t((e_ + two_d - 1) / two_d);
  }
  // Redefines where the axis is, at rest (as AccelStepper does).
  void setCurrentPosition(int32_t position) {
    pos_ = target_ = position;
    e_ = 0;
    v_q12_ = 0;
    frac_q8_ = 0;
  }

  int32_t currentPosition() const { return pos_; }
  int32_t targetPosition() const { return target_; }
  int32_t distanceToGo() const { return target_ - pos_; }
  bool isRunning() const { return e_ != 0 || target_ != pos_; }
  // Speed reached at the last step, signed, whole steps/s.
  int32_t speed() const { return dir_ * int32_t(isqrt64(e_)); }

  // The next step toward the target.
  StepOut run() {
    if (max_speed_ == 0 || accel_ == 0) return StepOut{0, 0};
    if (e_ == 0) {
      if (target_ == pos_) return StepOut{0, 0};
      dir_ = target_ > pos_ ? 1 : -1;
    }
    const int64_t ahead = (int64_t(target_) - pos_) * dir_;  // steps left along the motion
    const uint64_t two_a = 2 * uint64_t(accel_), two_d = 2 * uint64_t(decel_);
    const uint64_t vmax2 = uint64_t(max_speed_) * max_speed_;
    uint64_t e_next;
    if (ahead >= 1 && e_ <= two_d * uint64_t(ahead)) {
      // Speed up toward vmax (or brake down to a lowered vmax), but never
      // above the braking parabola that ends at rest on the target.
      uint64_t wanted;
      if (e_ > vmax2) wanted = e_ > vmax2 + two_d ? e_ - two_d : vmax2;
      else wanted = e_ + two_a < vmax2 ? e_ + two_a : vmax2;
      const uint64_t parabola = two_d * uint64_t(ahead - 1);
      e_next = wanted < parabola ? wanted : parabola;
    } else {
      e_next = e_ > two_d ? e_ - two_d : 0;  // cannot stop in time: brake
    }
    const uint64_t v_next = e_next == e_ ? v_q12_ : speed_q12(e_next);
    const uint32_t interval = take_q8(step_time_q8(v_q12_ + v_next));
    e_ = e_next;
    v_q12_ = v_next;
    pos_ += dir_;
    return StepOut{interval, dir_};
  }

  // The next step at the setSpeed() speed; {0, 0} if none was set.
  StepOut runSpeed() {
    if (const_speed_ == 0) return StepOut{0, 0};
    const int8_t dir = const_speed_ > 0 ? 1 : -1;
    const uint32_t magnitude = uint32_t(const_speed_ * dir);
    // f / v with the remainder carried: n steps take exactly n f / v ticks.
    uint32_t interval = tick_hz_ / magnitude;
    const_rest_ += tick_hz_ % magnitude;
    if (const_rest_ >= magnitude) {
      const_rest_ -= magnitude;
      ++interval;
    }
    pos_ += dir;
    return StepOut{interval, dir};
  }

 private:
  static constexpr uint32_t max_rate = uint32_t(1) << 19;
  static constexpr uint32_t max_accel = uint32_t(1) << 24;
  static constexpr uint32_t max_tick_hz = uint32_t(1) << 24;

  MotionError check_speed(uint32_t v) const {
    if (v == 0) return MotionError::zero_speed;
    if (tick_hz_ == 0 || tick_hz_ > max_tick_hz) return MotionError::out_of_range;
    if (v > max_rate || v > tick_hz_ / 2) return MotionError::out_of_range;
    return MotionError::none;
  }
  static MotionError check_accel(uint32_t a) {
    if (a == 0) return MotionError::zero_accel;
    if (a > max_accel) return MotionError::out_of_range;
    return MotionError::none;
  }

  // Speed in Q12 steps/s from a squared speed (< 2^40).
  static uint64_t speed_q12(uint64_t e) { return isqrt64(e << 24); }

  // Duration of one step whose end speeds (Q12) add up to `sum`, Q8 ticks.
  // The last result is kept: a cruise then costs no division.
  uint64_t step_time_q8(uint64_t sum) {
    if (sum == 0) {
      // A one-step move from rest: accelerate at a, brake at d, within the
      // step: f sqrt(2/a + 2/d), computed in Q4 and returned in Q8.
      const uint64_t f2 = uint64_t(tick_hz_) * tick_hz_;
      return uint64_t(isqrt64(((2 * f2 / accel_) + (2 * f2 / decel_)) << 8)) << 4;
    }
    if (sum != last_sum_) {
      last_sum_ = sum;
      last_q8_ = (uint64_t(tick_hz_) << 21) / sum;  // 2 f / (v0 + v1)
    }
    return last_q8_;
  }

  // Whole ticks of a Q8 duration, carrying the fraction to the next step.
  uint32_t take_q8(uint64_t q8) {
    const uint64_t total = q8 + frac_q8_;
    frac_q8_ = uint8_t(total & 0xFF);
    return uint32_t(total >> 8);
  }

  uint32_t tick_hz_;
  uint32_t max_speed_ = 0;
  uint32_t accel_ = 0;
  uint32_t decel_ = 0;
  bool separate_decel_ = false;
  int32_t const_speed_ = 0;
  uint32_t const_rest_ = 0;  // remainder of f / v carried by runSpeed()
  int32_t pos_ = 0;
  int32_t target_ = 0;
  uint64_t e_ = 0;      // squared speed after the last step, steps^2/s^2
  uint64_t v_q12_ = 0;  // sqrt(e_), Q12
  uint64_t last_sum_ = 0, last_q8_ = 0;  // step_time_q8() cache
  int8_t dir_ = 1;      // direction of the current motion
  uint8_t frac_q8_ = 0; // tick fraction carried between steps
};

}  // namespace am
