// core/thermal/pid.h: the fixed-point controller against the same control law
// written here in double precision and engineering units, and closed loops on
// a simulated hotend.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <random>

#include "core/thermal/pid.h"
#include "core/thermal/thermistor.h"

namespace {

constexpr double kTs = 0.125;  // s, the controller's period
constexpr uint16_t kTsMs = 125;

am::TempReading reading_of(double celsius) {
  return am::TempReading::celsius_centi(int16_t(std::lround(celsius * 100)));
}

// The law of pid.h restated in C, seconds and duty (0..255), in double.
struct ReferencePid {
  double kp, ki, kd;
  int shift = 4;
  bool anti_windup = true;
  double integral = 0, d = 0, last = 0, u = 0;  // u: the unrounded output of the last update
  bool primed = false;

  int update(double measured, double target) {
    if (target <= 0) {
      integral = d = 0;
      primed = false;
      return 0;
    }
    const double e = target - measured;
    const double dm = primed ? measured - last : 0;
    last = measured;
    primed = true;
    const double p = kp * e;
    d += (kd / kTs * dm - d) / double(1 << shift);
    const double before = p + integral - d;
    const bool frozen = anti_windup && ((before >= 255 && e > 0) || (before <= 0 && e < 0));
    if (!frozen) integral += ki * kTs * e;
    if (anti_windup) integral = std::clamp(integral, 0.0, 255.0);
    u = p + integral - d;
    return int(std::clamp(std::floor(u + 0.5), 0.0, 255.0));
  }
};

// Hotend model: a heater block (first order to ambient) seen through a
// first-order sensor lag, heat arriving after a transport delay.
struct Hotend {
  double ambient = 25, heater_w = 40, capacity_j_per_k = 12, loss_w_per_k = 1.0 / 7;
  double sensor_tau_s = 3, delay_s = 1;
  double block = 25, sensor = 25;
  std::deque<int> pipe;

  // Applies `duty` for one controller period.
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
};

// The measurement path: 12-bit oversampled ADC on the default divider, then the table.
constexpr am::ThermistorTable<am::kHotendThermistorPoints> kTable(am::kHotendThermistor);
am::TempReading measure(double celsius) {
  const double r = 100000 * std::exp(3950 * (1 / (celsius + 273.15) - 1 / 298.15));
  const double code = std::floor(4096 * r / (r + 4700));
  return am::thermistor_temperature<12>(kTable, uint16_t(std::clamp(code, 0.0, 4095.0)));
}

// Marlin's default hotend gains (M301 P22.2 I1.08 D114).
constexpr am::PidGains kMarlinHotend{22200, 1080, 114000};

am::HeaterPid make_pid(const am::PidGains& g, uint8_t shift = 4) {
  am::HeaterPid pid;
  EXPECT_TRUE(pid.set_gains(g, kTsMs, shift));
  return pid;
}

TEST(ThermalPid, EachTermInEngineeringUnits) {
  // P: 10 C below target at Kp 10 duty/C -> 100.
  am::HeaterPid p = make_pid({10000, 0, 0});
  EXPECT_EQ(p.update(reading_of(190), 20000), 100);
  // I: 1 C below target at Ki 2 duty/(C s): 2 duty a second, 16 samples = 2 s -> 4.
  am::HeaterPid i = make_pid({0, 2000, 0});
  int out = 0;
  for (int n = 0; n < 16; ++n) out = i.update(reading_of(199), 20000);
  EXPECT_EQ(out, 4);
  // D, unfiltered: rising 4 C/s at Kd 10 duty s/C -> 40 duty taken off 200.
  am::HeaterPid d = make_pid({20000, 0, 10000}, 0);
  d.update(reading_of(150), 16000);                    // 10 C low: 200
  EXPECT_EQ(d.update(reading_of(150.5), 16000), 190 - 40);  // 9.5 C low, rising 0.5 C in 0.125 s
}

// Random measurement histories and targets: the fixed-point controller gives
// the double-precision law's output, but where the law's unrounded output lies
// within 0.05 of a rounding boundary (gain quantisation: Kp is held to 1/655
// duty per C, Ki Ts to 2^-24 duty per 0.01 C), and then it is one step off.
TEST(ThermalPid, MatchesTheDoubleLawButAtRoundingTies) {
  std::mt19937 rng(7);
  const am::PidGains gains[] = {kMarlinHotend, {10000, 23, 305000}, {5000, 200, 0}, {60000, 5000, 400000}};
  for (const am::PidGains& g : gains) {
    for (int shift : {0, 4}) {
      am::HeaterPid pid = make_pid(g, uint8_t(shift));
      ReferencePid ref{g.kp_milli / 1000.0, g.ki_milli / 1000.0, g.kd_milli / 1000.0, shift};
      std::uniform_real_distribution<double> jitter(-0.3, 0.3);
      double t = 150, target = 200;
      int mismatches = 0;
      for (int n = 0; n < 20000; ++n) {
        if (n % 2000 == 0) target = 150 + (rng() % 100);
        t += 0.1 * (target - t) * kTs + jitter(rng);
        const double measured = std::lround(t * 100) / 100.0;  // what the controller sees
        const int want = ref.update(measured, target);
        const int got = pid.update(reading_of(measured), int16_t(target * 100));
        ASSERT_NEAR(got, want, 1) << "gains " << g.kp_milli << " n " << n;
        if (got != want) {
          ++mismatches;
          const double frac = ref.u - std::floor(ref.u);
          EXPECT_NEAR(frac, 0.5, 0.05) << "gains " << g.kp_milli << " n " << n << " u " << ref.u;
        }
      }
      EXPECT_LT(mismatches, 2000) << g.kp_milli;
    }
  }
}

struct LoopRun {
  double peak = -1e9, settle_s = -1, final_c = 0, mean_err_last_min = 0;
};

// Closed loop from ambient: heats at `target_c`, returns the peak sensor
// temperature and when it last left target +-0.5 C.
template <typename Controller>
LoopRun heat(Controller&& step, double target_c, double seconds, Hotend& plant) {
  LoopRun r;
  const int n_total = int(seconds / kTs);
  double err_sum = 0;
  int err_n = 0;
  for (int n = 0; n < n_total; ++n) {
    const int duty = step(plant.sensor, target_c);
    plant.run(duty);
    r.peak = std::max(r.peak, plant.sensor);
    if (std::fabs(plant.sensor - target_c) > 0.5) r.settle_s = (n + 1) * kTs;
    if (n >= n_total - int(60 / kTs)) err_sum += plant.sensor - target_c, ++err_n;
  }
  r.final_c = plant.sensor;
  r.mean_err_last_min = err_sum / err_n;
  return r;
}

// A long heat-up at full power (25 -> 240 C takes about two minutes on this
// 40 W hotend): the output sits at 255 throughout, and the anti-windup keeps
// the integral from growing there. Bounds: the overshoot with conditional
// integration (measured 0.5 C at 240 C, 1.9 C at 150 C) against the same
// controller with only the 0..255 clamp on the integral (1.6 C, 4.0 C) and
// with no anti-windup at all (over 60 C).
TEST(ThermalPid, NoWindupAfterALongSaturatedHeatUp) {
  struct Case { double target, max_overshoot, min_saturated_s; };
  for (const Case& c : {Case{240, 1.0, 100}, Case{150, 2.5, 40}}) {
    Hotend plant;
    am::HeaterPid pid = make_pid(kMarlinHotend);
    int saturated = 0;
    const LoopRun ours = heat(
        [&](double m, double target) {
          const int u = pid.update(measure(m), int16_t(target * 100));
          saturated += u == 255;
          return u;
        },
        c.target, 600, plant);
    Hotend plant2;
    ReferencePid naive{22.2, 1.08, 114, 4, false};
    const LoopRun wound =
        heat([&](double m, double target) { return naive.update(m, target); }, c.target, 600, plant2);
    std::printf("  heat-up to %.0f C: %.1f s at full power; peak %.2f C (without anti-windup %.2f C), "
                "within 0.5 C after %.1f s\n",
                c.target, saturated * kTs, ours.peak, wound.peak, ours.settle_s);
    EXPECT_GT(saturated * kTs, c.min_saturated_s);  // it really was a long saturated phase
    EXPECT_LT(ours.peak - c.target, c.max_overshoot);
    EXPECT_GT(wound.peak - c.target, 20.0);  // what windup does on the same plant
    EXPECT_LT(ours.settle_s, 200.0);
    EXPECT_NEAR(ours.mean_err_last_min, 0.0, 0.1);
  }
}

TEST(ThermalPid, TracksSetpointChanges) {
  Hotend plant;
  am::HeaterPid pid = make_pid(kMarlinHotend);
  auto step = [&](double c, double target) { return pid.update(measure(c), int16_t(target * 100)); };
  heat(step, 200, 400, plant);
  ASSERT_NEAR(plant.sensor, 200, 0.3);
  const LoopRun up = heat(step, 220, 300, plant);
  std::printf("  200 -> 220 C: peak %.2f C, within 0.5 C after %.1f s\n", up.peak, up.settle_s);
  EXPECT_LT(up.peak, 223.0);
  EXPECT_LT(up.settle_s, 150.0);
  EXPECT_NEAR(up.mean_err_last_min, 0.0, 0.1);
  const LoopRun down = heat(step, 180, 400, plant);
  std::printf("  220 -> 180 C: within 0.5 C after %.1f s\n", down.settle_s);
  EXPECT_LT(down.settle_s, 300.0);
  EXPECT_NEAR(down.mean_err_last_min, 0.0, 0.1);
}

// Identical measurement histories, one target stepped by 10 C: the outputs
// differ by (Kp + Ki Ts) * 10 C at the step, nothing from Kd (a derivative
// of the error would add Kd / Ts * 10 C = 4000 duty here).
TEST(ThermalPid, NoDerivativeKickOnSetpointChange) {
  const am::PidGains g{2000, 100, 50000};
  am::HeaterPid a = make_pid(g), b = make_pid(g);
  double t = 180;
  for (int n = 0; n < 400; ++n) {
    t += 0.01 * std::sin(n * 0.05);
    const int ua = a.update(reading_of(t), 20000);
    const int ub = b.update(reading_of(t), n < 200 ? 20000 : 21000);
    if (n < 200) {
      ASSERT_EQ(ua, ub);
    } else {
      // step: 2 * 10 + 0.1 * 0.125 * 10 * (n - 199) duty
      const double want = 20 + 0.125 * (n - 199);
      EXPECT_NEAR(ub - ua, want, 1.0) << n;
    }
  }
}

TEST(ThermalPid, OffIsOffAndStartsClean) {
  am::HeaterPid pid = make_pid(kMarlinHotend);
  for (int n = 0; n < 100; ++n) pid.update(reading_of(205), 21000);
  EXPECT_GT(pid.integral_term(), 0);
  EXPECT_EQ(pid.update(reading_of(205), 0), 0);
  EXPECT_EQ(pid.integral_term(), 0);
  EXPECT_EQ(pid.derivative_term(), 0);
  EXPECT_EQ(pid.update(reading_of(205), -500), 0);
  EXPECT_EQ(pid.update(am::TempReading::fault(am::SensorState::open), 21000), 0);
  EXPECT_EQ(pid.update(am::TempReading::fault(am::SensorState::shorted), 21000), 0);
  // Just above target: P is negative, output exactly 0 (not a 1/255 trickle).
  EXPECT_EQ(pid.update(reading_of(210.01), 21000), 0);
  // Less than half a step of demand rounds to 0; from half a step it is 1.
  am::HeaterPid tiny = make_pid({25000, 0, 0});  // 25 duty per C: 0.02 C is half a step
  EXPECT_EQ(tiny.update(reading_of(209.99), 21000), 0);
  tiny.reset();
  EXPECT_EQ(tiny.update(reading_of(209.98), 21000), 1);
}

TEST(ThermalPid, ExtremesSaturateWithoutOverflow) {
  am::HeaterPid hot = make_pid({1000000, 1000000, 10000000}, 0);
  EXPECT_EQ(hot.update(reading_of(-300), 32000), 255);
  EXPECT_EQ(hot.update(reading_of(320), 100), 0);    // huge negative error and a fast rise
  EXPECT_EQ(hot.update(reading_of(-300), 32000), 255);  // and the opposite
  am::HeaterPid weak = make_pid({10, 1, 0});  // 0.01 duty/C: 600 C of error is 6 duty
  EXPECT_EQ(weak.update(reading_of(-300), 30000), 6);
}

TEST(ThermalPid, RejectsGainsOutOfRange) {
  am::HeaterPid pid = make_pid(kMarlinHotend);
  EXPECT_FALSE(pid.set_gains({1000001, 0, 0}, kTsMs));
  EXPECT_FALSE(pid.set_gains({0, 1000001, 0}, kTsMs));
  EXPECT_FALSE(pid.set_gains({0, 0, 10000001}, kTsMs));
  EXPECT_FALSE(pid.set_gains(kMarlinHotend, 49));
  EXPECT_FALSE(pid.set_gains(kMarlinHotend, 1001));
  EXPECT_FALSE(pid.set_gains(kMarlinHotend, kTsMs, 9));
  EXPECT_EQ(pid.gains().kp_milli, 22200u);
  EXPECT_EQ(pid.period_ms(), kTsMs);
}

}  // namespace
