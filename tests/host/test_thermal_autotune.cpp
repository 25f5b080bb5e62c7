// core/thermal/autotune.h on a simulated hotend: the measured ultimate gain
// and period against the describing-function prediction computed here from
// the plant's frequency response, and a closed loop with the tuned gains.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <vector>

#include "core/thermal/autotune.h"
#include "core/thermal/pid.h"
#include "core/thermal/safety.h"
#include "core/thermal/thermistor.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTs = 0.125;

// Heater block (first order to ambient) through a first-order sensor lag,
// heat arriving after a transport delay (as in test_thermal_pid.cpp).
struct Hotend {
  double ambient = 25, heater_w = 40, capacity_j_per_k = 12, loss_w_per_k = 1.0 / 7;
  double sensor_tau_s = 3, delay_s = 1;
  double block = 25, sensor = 25;
  std::deque<int> pipe;

  void run(int duty) {
    if (pipe.empty()) pipe.assign(size_t(delay_s / kTs + 0.5), 0);
    pipe.push_back(duty);
    const int applied = pipe.front();
    pipe.pop_front();
    const int sub = 25;
    const double dt = kTs / sub;
    for (int i = 0; i < sub; ++i) {
      block += dt * (heater_w * applied / 255.0 - loss_w_per_k * (block - ambient)) / capacity_j_per_k;
      sensor += dt * (block - sensor) / sensor_tau_s;
    }
  }

  // Frequency response, C per duty: K / ((1 + j w tau)(1 + j w tau_s)) e^{-j w L}.
  double gain_at(double w) const {
    const double k = heater_w / loss_w_per_k / 255, tau = capacity_j_per_k / loss_w_per_k;
    return k / std::hypot(1, w * tau) / std::hypot(1, w * sensor_tau_s);
  }
  double phase_at(double w, double extra_delay_s) const {
    const double tau = capacity_j_per_k / loss_w_per_k;
    return -std::atan(w * tau) - std::atan(w * sensor_tau_s) - w * (delay_s + extra_delay_s);
  }
};

constexpr am::ThermistorTable<am::kHotendThermistorPoints> kTable(am::kHotendThermistor);
am::TempReading measure(double celsius) {
  const double r = 100000 * std::exp(3950 * (1 / (celsius + 273.15) - 1 / 298.15));
  const double code = std::floor(4096 * r / (r + 4700));
  return am::thermistor_temperature<12>(kTable, uint16_t(std::clamp(code, 0.0, 4095.0)));
}

struct Tuned {
  am::RelayAutotune tune;
  double seconds = 0;
};

Tuned run_autotune(Hotend& plant, int16_t target, uint8_t cycles = 5) {
  Tuned t;
  am::AutotuneConfig cfg;
  cfg.target = target;
  cfg.cycles = cycles;
  t.tune.start(cfg);
  while (t.tune.running() && t.seconds < 3600) {
    plant.run(t.tune.update(measure(plant.sensor)));
    t.seconds += kTs;
  }
  return t;
}

// Where the loop's phase reaches -180 degrees (bisection). The relay acts on
// a sample that is on average half a period late, and holds for a period.
double phase_crossover(const Hotend& p) {
  double lo = 1e-3, hi = 10;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (p.phase_at(mid, kTs) > -kPi ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(ThermalAutotune, UltimateGainAndPeriodMatchTheDescribingFunction) {
  Hotend plant;
  const Tuned t = run_autotune(plant, 20000);
  ASSERT_EQ(t.tune.state(), am::AutotuneState::done);
  const double w180 = phase_crossover(plant);
  const double ku_pred = 1 / plant.gain_at(w180), tu_pred = 2 * kPi / w180;
  const double ku = t.tune.ku_milli() / 1000.0, tu = t.tune.tu_ms() / 1000.0;
  const am::PidGains g = t.tune.gains();
  std::printf("  autotune at 200 C: %.0f s, relay %d/%d, amplitude %.2f C; Ku %.2f (predicted "
              "%.2f), Tu %.2f s (predicted %.2f s); Kp %.2f Ki %.3f Kd %.1f\n",
              t.seconds, t.tune.relay_low(), t.tune.relay_high(), t.tune.amplitude_centi() / 100.0,
              ku, ku_pred, tu, tu_pred, g.kp_milli / 1000.0, g.ki_milli / 1000.0,
              g.kd_milli / 1000.0);
  // The describing function is an approximation (the sensor signal is not a
  // pure sine): agreement to 15 % is what it supports.
  EXPECT_NEAR(ku / ku_pred, 1.0, 0.15);
  EXPECT_NEAR(tu / tu_pred, 1.0, 0.15);
  // Marlin's classic rule applied to what was measured.
  EXPECT_NEAR(g.kp_milli / 1000.0, 0.6 * ku, 0.01);
  EXPECT_NEAR(g.ki_milli / 1000.0, 2 * 0.6 * ku / tu, 0.01);
  EXPECT_NEAR(g.kd_milli / 1000.0, 0.6 * ku * tu / 8, 0.05);
  // Sane for a 40 W hotend (Marlin's own defaults are P22.2 I1.08 D114).
  EXPECT_GT(g.kp_milli, 5000u);
  EXPECT_LT(g.kp_milli, 100000u);
  EXPECT_GT(g.ki_milli, 100u);
  EXPECT_LT(g.ki_milli, 10000u);
  EXPECT_GT(g.kd_milli, 10000u);
  EXPECT_LT(g.kd_milli, 1000000u);
  // The relay re-centred on the power 200 C needs: (200 - 25) C / 7 K/W = 25 W = 159 duty.
  EXPECT_EQ(t.tune.relay_high(), 255);
  EXPECT_NEAR((t.tune.relay_high() + t.tune.relay_low()) / 2.0, 159.4, 12);
  // The amplitude: 4 d / pi * |G| at the crossover, d the half swing.
  const double d = (t.tune.relay_high() - t.tune.relay_low()) / 2.0;
  EXPECT_NEAR(t.tune.amplitude_centi() / 100.0, 4 * d / kPi * plant.gain_at(w180),
              0.15 * 4 * d / kPi * plant.gain_at(w180));
}

// The last cycle measured here from what the autotune saw and did (its
// readings and its relay output), and Ku from those observables in double.
TEST(ThermalAutotune, MeasuresTheLastCycleExactly) {
  Hotend plant;
  am::RelayAutotune tune;
  am::AutotuneConfig cfg;
  cfg.target = 20000;
  tune.start(cfg);
  std::vector<int> seen, out;
  while (tune.running()) {
    const am::TempReading r = measure(plant.sensor);
    const int u = tune.update(r);
    seen.push_back(r.centi);
    out.push_back(u);
    plant.run(u);
  }
  ASSERT_EQ(tune.state(), am::AutotuneState::done);
  // Switches to heating: the output rises; the run ends on one (output 0, done).
  std::vector<size_t> on;
  for (size_t i = 1; i + 1 < out.size(); ++i)
    if (out[i] > out[i - 1]) on.push_back(i);
  on.push_back(out.size() - 1);
  ASSERT_GE(on.size(), 4u);
  const size_t a = on[on.size() - 2], b = on.back();
  const int hi = *std::max_element(seen.begin() + long(a), seen.begin() + long(b) + 1);
  const int lo = *std::min_element(seen.begin() + long(a), seen.begin() + long(b) + 1);
  const int relay_hi = *std::max_element(out.begin() + long(a), out.begin() + long(b));
  const int relay_lo = *std::min_element(out.begin() + long(a), out.begin() + long(b));
  EXPECT_EQ(tune.tu_ms(), (b - a) * 125);
  EXPECT_NEAR(tune.amplitude_centi(), (hi - lo) / 2.0, 0.5);
  const double ku = 4 * ((relay_hi - relay_lo) / 2.0) / (kPi * (hi - lo) / 200.0);
  EXPECT_NEAR(tune.ku_milli() / 1000.0, ku, 0.001 * ku);
  EXPECT_NEAR(tune.gains().kp_milli / 1000.0, 0.6 * ku, 0.001 * ku);
}

TEST(ThermalAutotune, ClosedLoopWithTheTunedGainsSettles) {
  Hotend tune_plant;
  const Tuned t = run_autotune(tune_plant, 21000);
  ASSERT_EQ(t.tune.state(), am::AutotuneState::done);
  am::HeaterPid pid;
  ASSERT_TRUE(pid.set_gains(t.tune.gains(), 125));
  Hotend plant;  // cold start
  double peak = 0, last_out = 0, worst_late = 0;
  for (int n = 0; n < int(600 / kTs); ++n) {
    plant.run(pid.update(measure(plant.sensor), 21000));
    peak = std::max(peak, plant.sensor);
    if (std::fabs(plant.sensor - 210) > 0.5) last_out = (n + 1) * kTs;
    if (n * kTs > 400) worst_late = std::max(worst_late, std::fabs(plant.sensor - 210));
  }
  std::printf("  tuned loop 25 -> 210 C: peak %.2f C, within 0.5 C after %.1f s, worst after 400 s "
              "%.3f C\n",
              peak, last_out, worst_late);
  EXPECT_LT(peak, 215.0);
  EXPECT_LT(last_out, 300.0);
  EXPECT_LT(worst_late, 0.2);
}

// The safety rules run beside the autotune and the tuned loop without a
// false alarm: the relay's full-power halves are short, its swing is well
// inside the runaway band.
TEST(ThermalAutotune, SafetyStaysQuietDuringTheTuneAndTheTunedLoop) {
  Hotend plant;
  am::HeaterSafety safety;
  am::RelayAutotune tune;
  am::AutotuneConfig cfg;
  cfg.target = 23000;
  tune.start(cfg);
  uint32_t now = 0;
  while (tune.running()) {
    const am::TempReading r = measure(plant.sensor);
    plant.run(safety.check(now, r, cfg.target, tune.update(r)));
    now += 125;
  }
  ASSERT_EQ(tune.state(), am::AutotuneState::done);
  am::HeaterPid pid;
  ASSERT_TRUE(pid.set_gains(tune.gains()));
  for (int n = 0; n < 4000; ++n, now += 125) {
    const am::TempReading r = measure(plant.sensor);
    plant.run(safety.check(now, r, 23000, pid.update(r, 23000)));
  }
  EXPECT_EQ(safety.fault(), am::HeaterFault::none);
  EXPECT_TRUE(safety.temp_ok(measure(plant.sensor), 23000));
}

TEST(ThermalAutotune, RelayStartsAtFullPowerAndNeedsThreeCycles) {
  am::RelayAutotune tune;
  am::AutotuneConfig cfg;
  cfg.target = 20000;
  cfg.cycles = 1;  // raised to 3
  tune.start(cfg);
  EXPECT_EQ(tune.update(am::TempReading::celsius_centi(2500)), 255);
  Hotend plant;
  tune.start(cfg);
  while (tune.running()) plant.run(tune.update(measure(plant.sensor)));
  EXPECT_EQ(tune.state(), am::AutotuneState::done);
  EXPECT_EQ(tune.cycles_done(), 4);
  EXPECT_GT(tune.gains().kp_milli, 0u);
}

TEST(ThermalAutotune, NoSwitchBeforeFiveSeconds) {
  am::RelayAutotune tune;
  am::AutotuneConfig cfg;
  cfg.target = 20000;
  tune.start(cfg);
  // Above target from the first sample: the relay heats 5 s (40 samples) before it may switch.
  for (int n = 0; n < 40; ++n) EXPECT_EQ(tune.update(am::TempReading::celsius_centi(20010)), 255) << n;
  EXPECT_EQ(tune.update(am::TempReading::celsius_centi(20010)), 0);
  // And below target again: 5 s of cooling first.
  for (int n = 0; n < 39; ++n) EXPECT_EQ(tune.update(am::TempReading::celsius_centi(19990)), 0) << n;
  EXPECT_EQ(tune.update(am::TempReading::celsius_centi(19990)), 255);
}

TEST(ThermalAutotune, FailuresEndWithTheHeaterOff) {
  am::AutotuneConfig cfg;
  cfg.target = 20000;
  am::RelayAutotune sensor;
  sensor.start(cfg);
  sensor.update(am::TempReading::celsius_centi(2500));
  EXPECT_EQ(sensor.update(am::TempReading::fault(am::SensorState::open)), 0);
  EXPECT_EQ(sensor.state(), am::AutotuneState::failed_sensor);
  EXPECT_EQ(sensor.update(am::TempReading::celsius_centi(2500)), 0);  // stays ended

  am::RelayAutotune over;
  over.start(cfg);
  EXPECT_EQ(over.update(am::TempReading::celsius_centi(23000)), 255);  // target + 30 C: still fine
  EXPECT_EQ(over.update(am::TempReading::celsius_centi(23001)), 0);
  EXPECT_EQ(over.state(), am::AutotuneState::failed_overshoot);

  am::RelayAutotune slow;  // a heater that never gets there
  slow.start(cfg);
  int n = 0;
  while (slow.running() && n < 20000) slow.update(am::TempReading::celsius_centi(5000)), ++n;
  EXPECT_EQ(slow.state(), am::AutotuneState::failed_timeout);
  EXPECT_EQ(n, 20 * 60 * 8 + 2);  // the first sample past 20 minutes
}

}  // namespace
