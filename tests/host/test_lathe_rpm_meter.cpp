// core/lathe/rpm_meter.h against rpm computed here in double: a spindle
// turning at a steady rate, forwards and backwards, on encoders of several
// resolutions, sampled every 64 ms; a reset forgets the history.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "core/lathe/rpm_meter.h"

namespace {

TEST(RpmMeter, ASteadySpindleReadsItsRpmOnceTheWindowIsFull) {
  for (const uint16_t per_turn : {uint16_t(40), uint16_t(600), uint16_t(2400), uint16_t(60000)}) {
    for (const double rpm : {0.0, 1.0, 59.9, 300.0, -450.0, 3000.0, -3000.0}) {
      // Within the meter's limit: 2.2 million counts/s (60000 counts a turn
      // at 3000 rpm is 3 million).
      if (std::fabs(rpm) / 60 * per_turn > 2.2e6) continue;
      am::RpmMeter m;
      const int32_t start = 123456;
      m.reset(start);
      const double counts_per_sample = rpm / 60.0 * per_turn * 0.064;
      for (int k = 1; k <= 40; ++k) {
        const int32_t count = start + int32_t(std::trunc(counts_per_sample * k));
        m.sample(count, per_turn);
        // Over the last 8 samples (or back to the reset while fewer).
        const int32_t back = start + int32_t(std::trunc(counts_per_sample * (k < 8 ? 0 : k - 8)));
        const double expected = std::trunc(double(count - back) * 60000.0 / (512.0 * per_turn));
        ASSERT_EQ(m.rpm(), int16_t(expected)) << per_turn << " counts/turn, " << rpm << " rpm, sample " << k;
      }
      // A full window of a steady spindle: within one count's worth of the rpm.
      EXPECT_NEAR(m.rpm(), rpm, 60000.0 / (512.0 * per_turn) + 1) << per_turn << " " << rpm;
    }
  }
}

TEST(RpmMeter, TheLimitsEdgeStillReadsRight) {
  // 1145324 counts in the window, both ways: 1145324 x 1875 < 2^31.
  for (const int32_t sign : {1, -1}) {
    am::RpmMeter m;
    m.reset(0);
    for (int k = 1; k <= 8; ++k) m.sample(sign * 1145324 / 8 * k + (k == 8 ? sign * (1145324 % 8) : 0), 65535);
    EXPECT_EQ(m.rpm(), int16_t(sign * int32_t(1145324.0 * 60000.0 / (512.0 * 65535))));
  }
}

TEST(RpmMeter, AResetForgetsTheHistory) {
  am::RpmMeter m;
  for (int k = 1; k <= 8; ++k) m.sample(k * 100, 600);
  EXPECT_NE(m.rpm(), 0);
  m.reset(5000);
  m.sample(5000, 600);
  EXPECT_EQ(m.rpm(), 0);
  m.sample(5024, 600);  // 24 counts since the reset: 24 x 60000 / (512 x 600)
  EXPECT_EQ(m.rpm(), 4);
}

}  // namespace
