// core/thermal/thermistor.h, const_math.h and adc_filter.h against
// independent double-precision models written here with <cmath>.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/thermal/adc_filter.h"
#include "core/thermal/const_math.h"
#include "core/thermal/thermistor.h"

namespace {

// The default circuit, restated: 100 kOhm at 25 C, beta 3950, 4.7 kOhm pull-up.
constexpr double kR0 = 100000, kT0 = 298.15, kBeta = 3950, kPullup = 4700;

double ntc_ohm(double fraction) { return kPullup * fraction / (1 - fraction); }
// Beta model in its usual form (not the a/b/c form the header uses).
double beta_celsius(double r_ohm) { return 1 / (1 / kT0 + std::log(r_ohm / kR0) / kBeta) - 273.15; }
double beta_fraction(double celsius) {
  const double r = kR0 * std::exp(kBeta * (1 / (celsius + 273.15) - 1 / kT0));
  return r / (r + kPullup);
}
// Centre of a reading's bin, as a fraction of the reference.
double centre(uint32_t reading, int bits) { return (reading + 0.5) / double(1u << bits); }

constexpr am::ThermistorTable<am::kHotendThermistorPoints> kTable(am::kHotendThermistor);
static_assert(kTable.valid(), "default table is monotonic");
static_assert(sizeof(kTable) == 136, "flash budget: 34 points of 4 bytes");

struct ErrorScan {
  double worst = 0, at_celsius = 0;
};

// Every reading whose centre lies in [lo, hi] C, converted, against the model.
template <uint8_t Bits, uint8_t N>
ErrorScan scan(const am::ThermistorTable<N>& table, double (*model)(uint32_t, int), double lo,
               double hi) {
  ErrorScan s;
  for (uint32_t r = 0; r < (1u << Bits); ++r) {
    const double t = model(r, Bits);
    if (t < lo || t > hi) continue;
    const am::TempReading got = am::thermistor_temperature<Bits>(table, uint16_t(r));
    EXPECT_TRUE(got.ok()) << r;
    const double err = std::fabs(got.centi / 100.0 - t);
    if (err > s.worst) s.worst = err, s.at_celsius = t;
  }
  return s;
}

double beta_model(uint32_t r, int bits) { return beta_celsius(ntc_ohm(centre(r, bits))); }

TEST(ThermalConstMath, LnAndExpMatchCmath) {
  for (double x = 1e-6; x < 1e9; x *= 1.37)
    EXPECT_NEAR(am::const_ln(x), std::log(x), 4e-16 * std::fabs(std::log(x)) + 1e-15) << x;
  for (double x = -30; x < 30; x += 0.173)
    EXPECT_NEAR(am::const_exp(x), std::exp(x), 6e-16 * std::exp(x)) << x;
  static_assert(am::const_ln(1.0) == 0.0, "ln 1");
  static_assert(am::const_exp(0.0) == 1.0, "exp 0");
}

TEST(ThermalThermistor, TablePointsLieOnTheModel) {
  for (uint8_t i = 0; i < kTable.size; ++i) {
    const double want_c = 320.0 - 10.0 * i;  // every 10 C from the hot end
    const double x = kTable.point[i].x / 65536.0;
    EXPECT_NEAR(x, beta_fraction(want_c), 0.5 / 65536) << int(i);
    EXPECT_NEAR(kTable.point[i].centi / 100.0, beta_celsius(ntc_ohm(x)), 0.005 + 1e-9) << int(i);
  }
}

// The figures quoted in thermistor.h's header comment.
TEST(ThermalThermistor, InterpolationErrorOver20To300C) {
  const ErrorScan s12 = scan<12>(kTable, beta_model, 20, 300);
  const ErrorScan s10 = scan<10>(kTable, beta_model, 20, 300);
  const ErrorScan hot = scan<12>(kTable, beta_model, 150, 300);
  std::printf("  worst |error| 20..300 C: 12-bit %.3f C at %.1f C, 10-bit %.3f C at %.1f C; "
              "150..300 C: %.3f C\n",
              s12.worst, s12.at_celsius, s10.worst, s10.at_celsius, hot.worst);
  EXPECT_LE(s12.worst, 0.43);
  EXPECT_LE(s10.worst, 0.43);
  EXPECT_LE(hot.worst, 0.22);
  EXPECT_GT(s12.worst, 0.3);  // the figure is a measurement, not a loose bound
}

// C per count of the circuit, from the model, and the same step seen through
// the table between neighbouring 10-bit readings.
TEST(ThermalThermistor, ResolutionPerCount) {
  struct Row { double celsius, c_per_count; };
  const Row rows[] = {{20, 0.61}, {100, 0.14}, {200, 0.47}, {250, 1.09}, {300, 2.37}};
  for (const Row& row : rows) {
    const double counts_per_c =
        (beta_fraction(row.celsius - 0.5) - beta_fraction(row.celsius + 0.5)) * 1024;
    EXPECT_NEAR(1 / counts_per_c, row.c_per_count, 0.006) << row.celsius;
    const uint16_t r = uint16_t(beta_fraction(row.celsius) * 1024);
    const am::TempReading a = am::thermistor_temperature<10>(kTable, r);
    const am::TempReading b = am::thermistor_temperature<10>(kTable, uint16_t(r + 1));
    EXPECT_NEAR((a.centi - b.centi) / 100.0, row.c_per_count, 0.12 * row.c_per_count)
        << row.celsius;
  }
}

TEST(ThermalThermistor, MonotonicAndFaultsBeyondTheTable) {
  int16_t last = INT16_MAX;
  bool seen_ok = false;
  for (uint32_t r = 0; r < 4096; ++r) {
    const am::TempReading t = am::thermistor_temperature<12>(kTable, uint16_t(r));
    const double model = beta_model(r, 12);
    if (model >= 320.05) {
      EXPECT_EQ(t.state, am::SensorState::shorted) << r;
    } else if (model <= -10.05) {
      EXPECT_EQ(t.state, am::SensorState::open) << r;
    } else if (model > -9.95 && model < 319.95) {
      ASSERT_TRUE(t.ok()) << r;
    }
    if (!t.ok()) {
      // faults only at the two ends: shorted before any temperature, open after
      EXPECT_EQ(t.state, seen_ok ? am::SensorState::open : am::SensorState::shorted) << r;
      continue;
    }
    seen_ok = true;
    EXPECT_LE(t.centi, last) << r;
    last = t.centi;
  }
  // A 10-bit converter at full scale (open thermistor) and at 0 (short), and
  // readings that do not fit the width.
  EXPECT_EQ(am::thermistor_temperature<10>(kTable, 1023).state, am::SensorState::open);
  EXPECT_EQ(am::thermistor_temperature<10>(kTable, 0).state, am::SensorState::shorted);
  EXPECT_EQ(am::thermistor_temperature<10>(kTable, 1024).state, am::SensorState::open);
  EXPECT_EQ(am::thermistor_temperature<12>(kTable, 4096).state, am::SensorState::open);
}

TEST(ThermalThermistor, EndPointsAreInside) {
  // A reading exactly on an end point's x (14-bit codes hit it when the
  // point's x is odd multiples of 2: pick the reading whose centre is nearest).
  const am::ThermistorPoint hot = kTable.point[0], cold = kTable.point[kTable.size - 1];
  const uint16_t r_hot = uint16_t((hot.x + 1) >> 2), r_cold = uint16_t(cold.x >> 2);
  const am::TempReading h = am::thermistor_temperature<14>(kTable, r_hot);
  const am::TempReading c = am::thermistor_temperature<14>(kTable, r_cold);
  ASSERT_TRUE(h.ok());
  ASSERT_TRUE(c.ok());
  EXPECT_NEAR(h.centi / 100.0, beta_model(r_hot, 14), 0.05);
  EXPECT_NEAR(c.centi / 100.0, beta_model(r_cold, 14), 0.05);
  EXPECT_NEAR(h.centi, 32000, 20);
  EXPECT_NEAR(c.centi, -1000, 20);
  EXPECT_EQ(am::thermistor_temperature<14>(kTable, uint16_t(r_hot - 1)).state,
            am::SensorState::shorted);
  EXPECT_EQ(am::thermistor_temperature<14>(kTable, uint16_t(r_cold + 1)).state,
            am::SensorState::open);
}

// Steinhart-Hart coefficients fitted to three points of a 100 kOhm part that
// is not a Beta curve (100 kOhm at 25 C, 1.9 kOhm at 150 C, 300 Ohm at 250 C),
// evaluated here independently.
constexpr double kShA = 5.364681e-4, kShB = 2.398841e-4, kShC = 3.655338e-8;
double sh_celsius(double r_ohm) {
  const double l = std::log(r_ohm);
  return 1 / (kShA + kShB * l + kShC * l * l * l) - 273.15;
}
double sh_model(uint32_t r, int bits) { return sh_celsius(ntc_ohm(centre(r, bits))); }

TEST(ThermalThermistor, SteinhartHartTable) {
  constexpr am::ThermistorSpec spec =
      am::steinhart_hart_thermistor(kShA, kShB, kShC, 4700.0, 0.0, 320.0);
  constexpr am::ThermistorTable<40> table(spec);
  static_assert(table.valid(), "monotonic");
  EXPECT_NEAR(sh_celsius(100000), 25.0, 0.01);
  EXPECT_NEAR(sh_celsius(1900), 150.0, 0.01);
  EXPECT_NEAR(sh_celsius(300), 250.0, 0.01);
  for (uint8_t i = 0; i < table.size; ++i)
    EXPECT_NEAR(table.point[i].centi / 100.0, sh_celsius(ntc_ohm(table.point[i].x / 65536.0)),
                0.0051)
        << int(i);
  const ErrorScan s = scan<12>(table, sh_model, 20, 300);
  std::printf("  Steinhart-Hart, 40 points: worst |error| 20..300 C %.3f C at %.1f C\n", s.worst,
              s.at_celsius);
  EXPECT_LE(s.worst, 0.35);
}

// --- ADC conditioning ---

TEST(ThermalAdcFilter, OversamplerGivesTheFinerFloorCodeUnderDither) {
  // 16 samples with uniform dither at 1/16 step: floor(v + n_k), n_k in (-1/2, 1/2).
  am::AdcOversampler<2> os;
  double sum_err = 0;
  int sets = 0;
  for (double v = 100.0; v < 1000.0; v += 0.0371) {
    for (int k = 0; k < 16; ++k) {
      const bool done = os.add(uint16_t(std::floor(v - 0.5 + (k + 0.5) / 16)));
      EXPECT_EQ(done, k == 15);
    }
    const int ideal = int(std::floor(4 * v));
    EXPECT_NEAR(os.value(), ideal, 1) << v;
    sum_err += os.value() + 0.5 - 4 * v;  // read at the bin centre, as the lookup does
    ++sets;
  }
  // Unbiased but for the sum's own quantisation: +1/8 of a 12-bit step.
  EXPECT_NEAR(sum_err / sets, 0.125, 0.01);
}

TEST(ThermalAdcFilter, OversamplerQuietInputAndRange) {
  am::AdcOversampler<2> os;
  for (int k = 0; k < 16; ++k) os.add(700);
  EXPECT_EQ(os.value(), 4 * 700 + 2);
  for (int k = 0; k < 16; ++k) os.add(1023);
  EXPECT_EQ(os.value(), 4 * 1023 + 2);  // still a 12-bit code
  am::AdcOversampler<5> big;
  for (int k = 0; k < 1024; ++k) big.add(1023);
  EXPECT_EQ(big.value(), 32 * 1023 + 16);
  am::AdcOversampler<0> none;
  EXPECT_TRUE(none.add(512));
  EXPECT_EQ(none.value(), 512);
}

TEST(ThermalAdcFilter, SmootherIsAFirstOrderLagThatSettlesExactly) {
  am::AdcSmoother<3> f;
  EXPECT_EQ(f.add(1000), 1000);  // primed by the first sample
  // Step to 2000: y_n = 2000 - 1000 (7/8)^n, to within rounding.
  for (int n = 1; n <= 60; ++n) {
    const uint16_t y = f.add(2000);
    EXPECT_NEAR(y, 2000 - 1000 * std::pow(7.0 / 8, n), 4.0) << n;
  }
  EXPECT_EQ(f.value(), 2000);
  for (int n = 0; n < 200; ++n) f.add(1999);
  EXPECT_EQ(f.value(), 1999);  // from above
  for (int n = 0; n < 200; ++n) f.add(2003);
  EXPECT_EQ(f.value(), 2003);  // from below
  f.reset();
  EXPECT_EQ(f.add(5), 5);
}

}  // namespace
