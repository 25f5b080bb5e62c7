// core/lathe/bn_list.h against the seed's published B(n) vectors (digest
// section 1 and the pitch table of section 2) and against the definition
// B(n) = floor(n a / b) - floor((n - 1) a / b), evaluated here directly.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "core/lathe/bn_list.h"
#include "core/lathe/ratio.h"

namespace {

std::vector<uint32_t> list(const am::Ratio& r, uint32_t count, uint32_t* period = nullptr) {
  std::vector<uint32_t> v(count);
  const uint32_t p = am::bn_list(r, v.data(), count);
  if (period) *period = p;
  return v;
}

std::vector<uint32_t> by_definition(uint64_t a, uint64_t b, uint32_t count) {
  std::vector<uint32_t> v;
  for (uint64_t n = 1; n <= count; ++n) v.push_back(uint32_t(n * a / b - (n - 1) * a / b));
  return v;
}

std::vector<uint32_t> head(const std::vector<uint32_t>& v, size_t n) { return {v.begin(), v.begin() + n}; }

const am::Machine kSeed = {am::pitch_um(3175), am::servo_counts(30, 26), 40, false};

am::Ratio seed_ratio(am::Pitch p, uint32_t max_den = am::kMaxDen) {
  return am::gear_ratio(kSeed, {p, 1, am::Hand::right}, max_den).ratio;
}

TEST(LatheBnList, ThirteenEighths) {
  uint32_t period = 0;
  EXPECT_EQ(list({13, 8}, 16, &period),
            (std::vector<uint32_t>{1, 2, 1, 2, 2, 1, 2, 2, 1, 2, 1, 2, 2, 1, 2, 2}));
  EXPECT_EQ(period, 8u);
}

TEST(LatheBnList, OneMillimetreOnTheSeed) {
  const am::Ratio r = seed_ratio(am::pitch_um(1000));
  ASSERT_EQ(r.num, 780u);
  ASSERT_EQ(r.den, 127u);
  uint32_t period = 0;
  const std::vector<uint32_t> v = list(r, 2 * 127, &period);
  EXPECT_EQ(period, 127u);
  EXPECT_EQ(head(v, 15), (std::vector<uint32_t>{6, 6, 6, 6, 6, 6, 6, 7, 6, 6, 6, 6, 6, 6, 7}));
  uint32_t sum = 0;
  for (uint32_t i = 0; i < 127; ++i) sum += v[i];
  EXPECT_EQ(sum, 780u);  // 127 nodes, sum 780
  for (uint32_t i = 0; i < 127; ++i) EXPECT_EQ(v[i], v[i + 127]);
  EXPECT_EQ(v, by_definition(780, 127, 254));
}

TEST(LatheBnList, SeedPitchTableRows) {
  // 2.50 mm: 1950/127 exact, 15,15,16,15,15,16,...
  EXPECT_EQ(head(list(seed_ratio(am::pitch_um(2500)), 6), 6),
            (std::vector<uint32_t>{15, 15, 16, 15, 15, 16}));
  // 20 TPI (1.27 mm): 39/5, 7,8,8,8,8.
  uint32_t period = 0;
  EXPECT_EQ(list(seed_ratio(am::pitch_tpi(20)), 5, &period), (std::vector<uint32_t>{7, 8, 8, 8, 8}));
  EXPECT_EQ(period, 5u);
  // 4 TPI (6.35 mm): 39/1, the one-node list [39].
  EXPECT_EQ(list(seed_ratio(am::pitch_tpi(4)), 3, &period), (std::vector<uint32_t>{39, 39, 39}));
  EXPECT_EQ(period, 1u);
  // The feeds, approximated with denominators <= 150 as the seed did:
  // 0.04 mm -> 14/57 (57 nodes), 0.08 mm -> 57/116 (116 nodes).
  const am::Ratio fine = seed_ratio(am::pitch_um(40), 150), coarse = seed_ratio(am::pitch_um(80), 150);
  EXPECT_EQ(head(list(fine, 57, &period), 9), (std::vector<uint32_t>{0, 0, 0, 0, 1, 0, 0, 0, 1}));
  EXPECT_EQ(period, 57u);
  EXPECT_EQ(head(list(coarse, 116, &period), 7), (std::vector<uint32_t>{0, 0, 1, 0, 1, 0, 1}));
  EXPECT_EQ(period, 116u);
  // Exact, as avrmotion runs them: 156/635 and 312/635.
  EXPECT_EQ(list(seed_ratio(am::pitch_um(40)), 635, &period), by_definition(156, 635, 635));
  EXPECT_EQ(period, 635u);
  EXPECT_EQ(list(seed_ratio(am::pitch_um(80)), 635), by_definition(312, 635, 635));
}

// 131/80 by truncation (the list's I(n) = sum of the first n terms): I(11) =
// 18 (error 131/80 - 18/11 = 0.001136), I(50) = 81 (error 0.0175).
TEST(LatheBnList, ThesisTruncationExamples131Over80) {
  const std::vector<uint32_t> v = list({131, 80}, 80);
  uint32_t sum = 0;
  for (int n = 1; n <= 50; ++n) {
    sum += v[n - 1];
    if (n == 11) {
      EXPECT_EQ(sum, 18u);
      EXPECT_NEAR(131.0 / 80 - sum / 11.0, 0.001136, 0.0000005);
    }
  }
  EXPECT_EQ(sum, 81u);
  EXPECT_NEAR(131.0 / 80 - sum / 50.0, 0.0175, 1e-12);
  EXPECT_EQ(v, by_definition(131, 80, 80));
}

TEST(LatheBnList, EveryTermIsWholeOrWholePlusOne) {
  for (uint32_t den = 1; den <= 60; ++den)
    for (uint32_t num = 0; num <= 200; num += 7) {
      const std::vector<uint32_t> v = list({num, den}, 2 * den);
      EXPECT_EQ(v, by_definition(num, den, 2 * den)) << num << "/" << den;
      for (uint32_t b : v) EXPECT_TRUE(b == num / den || b == num / den + 1);
    }
}

}  // namespace
