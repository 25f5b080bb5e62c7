// Relay (bang-bang) PID autotune in the manner of Marlin's M303: the heater
// is switched between two duties around the target, the oscillation that
// follows is measured, and Ziegler-Nichols gains come out in M301 units.
//
// Contract
//   start(config), then update(reading) once per config.period_ms; each call
//   returns the duty for the next period. The relay heats (duty `high`) until
//   T > target, then cools (duty `low`) until T < target; a switch needs the
//   current half to have lasted min_half_ms (5 s), so sensor noise near the
//   target cannot chatter it. Each full cycle (a switch to heating) measures
//   t_high, t_low, the peak of the cooling half and the trough of the heating
//   half (temperature lags the relay, so they fall after the switches), then:
//   - the relay is re-centred on the power the target needs, as Marlin does:
//     bias += d (t_high - t_low) / (t_high + t_low), bias within 20 ..
//     max - 20, d = min(bias, max - bias), so one end stays at 0 or max;
//   - from the third cycle on, with a = (peak - trough) / 2 and d the half
//     swing that was applied in the cycle, Tu = t_high + t_low and
//       Ku = 4 d / (pi a),  Kp = 0.6 Ku,  Ki = 2 Kp / Tu,  Kd = Kp Tu / 8
//     (Marlin's classic PID rule), in duty per C, per C s, and duty s per C.
//   After `cycles` cycles (at least 3, Marlin's C parameter, default 5)
//   state() is done and gains() holds the last cycle's gains in thousandths
//   (PidGains: feed them to HeaterPid::set_gains). Failures end with output
//   0: a sensor fault (failed_sensor), T above target + max_overshoot (30 C,
//   Marlin's MAX_OVERSHOOT_PID_AUTOTUNE: failed_overshoot), or a half cycle
//   longer than timeout_ms (20 min: failed_timeout). The safety rules
//   (safety.h) still run beside it.
//
// Arithmetic: integer only; per sample compares and adds (about 120 cycles
// on the ATmega32), at each cycle end a few 32-bit divisions and
// mul_div_round (pi as 355/113). The relay levels are kept in half duties,
// so both ends are exact integers. 68 bytes of RAM, about 2.2 kB of flash
// (1.6 kB more than the PID alone: they share mul_div_round).
#pragma once
#include <stdint.h>

#include "fixed_point.h"
#include "pid.h"
#include "temperature.h"

namespace am {

struct AutotuneConfig {
  int16_t target = centi_c(200);
  uint8_t cycles = 5;
  uint16_t period_ms = 125;
  uint8_t max_output = 255;
  uint16_t min_half_ms = 5000;
  uint32_t timeout_ms = 20ul * 60ul * 1000ul;
  int16_t max_overshoot = centi_c(30);
};

enum class AutotuneState : uint8_t { idle, running, done, failed_sensor, failed_overshoot, failed_timeout };

class RelayAutotune {
 public:
  void start(const AutotuneConfig& config) {
    cfg_ = config;
    if (cfg_.cycles < 3) cfg_.cycles = 3;
    state_ = AutotuneState::running;
    bias2_ = cfg_.max_output;  // bias = d = max / 2: full power, then off
    set_levels();
    heating_ = true;
    now_ = 0;
    t_on_ = t_off_ = 0;
    t_high_ = t_low_ = 0;
    cycles_ = 0;
    have_gains_ = false;
    peak_ = trough_ = 0;
  }

  // Not inlined, for flash: as HeaterPid::update (core/thermal/pid.h).
  [[gnu::noinline]] uint8_t update(TempReading t) {
    if (state_ != AutotuneState::running) return 0;
    const uint32_t now = now_;
    now_ += cfg_.period_ms;
    if (!t.ok()) return finish(AutotuneState::failed_sensor);
    const int16_t c = t.centi;
    if (int32_t(c) > int32_t(cfg_.target) + cfg_.max_overshoot)
      return finish(AutotuneState::failed_overshoot);
    if (c > peak_) peak_ = c;
    if (c < trough_) trough_ = c;

    if (heating_ && c > cfg_.target && now - t_on_ >= cfg_.min_half_ms) {
      heating_ = false;
      t_off_ = now;
      t_high_ = t_off_ - t_on_;
      peak_ = c;
    } else if (!heating_ && c < cfg_.target && now - t_off_ >= cfg_.min_half_ms) {
      heating_ = true;
      t_on_ = now;
      t_low_ = t_on_ - t_off_;
      end_cycle();
      trough_ = c;
      if (cycles_ > cfg_.cycles && have_gains_) return finish(AutotuneState::done);
    }
    if (now - (heating_ ? t_on_ : t_off_) > cfg_.timeout_ms)
      return finish(AutotuneState::failed_timeout);
    return heating_ ? high_ : low_;
  }

  AutotuneState state() const { return state_; }
  bool running() const { return state_ == AutotuneState::running; }
  uint8_t cycles_done() const { return cycles_; }
  // The last cycle's results (valid once a third cycle has ended).
  const PidGains& gains() const { return gains_; }
  uint32_t ku_milli() const { return ku_milli_; }  // duty per C, thousandths
  uint32_t tu_ms() const { return tu_ms_; }
  int16_t amplitude_centi() const { return amplitude_; }  // a = (peak - trough) / 2
  uint8_t relay_high() const { return high_; }
  uint8_t relay_low() const { return low_; }

 private:
  uint8_t finish(AutotuneState s) {
    state_ = s;
    return 0;
  }

  // high = (bias + d), low = (bias - d) with d = min(bias, max - bias), in
  // half duties: bias2 = 2 bias.
  void set_levels() {
    const uint16_t max = cfg_.max_output;
    high_ = uint8_t(bias2_ <= max ? bias2_ : max);
    low_ = uint8_t(bias2_ <= max ? 0 : bias2_ - max);
  }

  void end_cycle() {
    const uint32_t tu = t_high_ + t_low_;
    if (cycles_ > 2) {
      const int32_t swing = int32_t(peak_) - trough_;  // 2a, 0.01 C
      const uint32_t relay = uint32_t(high_ - low_);   // 2d, duty
      if (swing > 0 && relay > 0 && tu > 0) {
        // Ku = 4 d / (pi a) = 400 (2d) / (pi (2a)) duty per C (2a in 0.01 C)
        ku_milli_ = mul_div_round(400000ul * relay, 113, 355ul * uint32_t(swing));
        const uint32_t kp = mul_div_round(240000ul * relay, 113, 355ul * uint32_t(swing));
        gains_ = PidGains{kp, mul_div_round(kp, 2000, tu), mul_div_round(kp, tu, 8000)};
        tu_ms_ = tu;
        amplitude_ = int16_t(swing / 2);
        have_gains_ = true;
      }
    }
    if (cycles_ > 0 && tu > 0) {
      // 2 bias += 2 d (t_high - t_low) / Tu, with 2 d = high - low
      const int32_t swing2 = int32_t(high_) - low_;
      const int32_t bias2 = int32_t(bias2_) + swing2 * (int32_t(t_high_) - int32_t(t_low_)) / int32_t(tu);
      const int32_t lo = 40, hi = 2 * int32_t(cfg_.max_output) - 40;
      bias2_ = uint16_t(clamp32(bias2, lo, hi));
      set_levels();
    }
    ++cycles_;
  }

  AutotuneConfig cfg_;
  AutotuneState state_ = AutotuneState::idle;
  bool heating_ = true;
  bool have_gains_ = false;
  uint8_t cycles_ = 0;
  uint8_t high_ = 0, low_ = 0;
  uint16_t bias2_ = 0;
  int16_t peak_ = 0, trough_ = 0, amplitude_ = 0;
  uint32_t now_ = 0, t_on_ = 0, t_off_ = 0, t_high_ = 0, t_low_ = 0;
  uint32_t ku_milli_ = 0, tu_ms_ = 0;
  PidGains gains_{0, 0, 0};
};

}  // namespace am
