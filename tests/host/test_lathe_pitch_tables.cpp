// core/lathe/pitch_tables.h: spot values from the standards, ordering, and
// that every entry converts to the pitch it names.
#include <gtest/gtest.h>

#include <cstdint>
#include <type_traits>

#include "core/lathe/pitch_tables.h"
#include "core/lathe/ratio.h"

namespace {

uint16_t coarse_pitch(uint16_t d_x10) {
  for (const auto& t : am::kIsoCoarse)
    if (t.diameter_x10 == d_x10) return t.pitch_um;
  return 0;
}

uint8_t tpi_x2(const am::InchThread* table, size_t n, uint16_t d) {
  for (size_t i = 0; i < n; ++i)
    if (table[i].diameter_x10000 == d) return table[i].tpi_x2;
  return 0;
}

TEST(LathePitchTables, PlainData) {
  static_assert(std::is_trivial<am::MetricThread>::value && std::is_standard_layout<am::MetricThread>::value,
                "flash-friendly rows");
  static_assert(std::is_trivial<am::InchThread>::value && std::is_standard_layout<am::InchThread>::value,
                "flash-friendly rows");
  EXPECT_EQ(am::kIsoCoarseCount, 34u);  // M1 .. M64
  EXPECT_EQ(am::kIsoFineCount, 26u);
  EXPECT_EQ(am::kUncCount, 33u);        // #1 .. 4 in
  EXPECT_EQ(am::kUnfCount, 24u);        // #0 .. 1 1/2 in
  EXPECT_EQ(am::kCommonTpiCount, 31u);  // 4 .. 80
  EXPECT_EQ(am::kTurningFeedsCount, 16u);
}

TEST(LathePitchTables, IsoSpotValues) {
  EXPECT_EQ(coarse_pitch(30), 500);    // M3 x 0.5
  EXPECT_EQ(coarse_pitch(60), 1000);   // M6 x 1
  EXPECT_EQ(coarse_pitch(80), 1250);   // M8 x 1.25
  EXPECT_EQ(coarse_pitch(100), 1500);  // M10 x 1.5
  EXPECT_EQ(coarse_pitch(120), 1750);  // M12 x 1.75
  EXPECT_EQ(coarse_pitch(240), 3000);  // M24 x 3
  EXPECT_EQ(coarse_pitch(640), 6000);  // M64 x 6
  // Coarse diameters ascend, pitches never fall; fine pitches are below the
  // coarse pitch of the same diameter.
  for (size_t i = 1; i < am::kIsoCoarseCount; ++i) {
    EXPECT_GT(am::kIsoCoarse[i].diameter_x10, am::kIsoCoarse[i - 1].diameter_x10);
    EXPECT_GE(am::kIsoCoarse[i].pitch_um, am::kIsoCoarse[i - 1].pitch_um);
  }
  for (const auto& f : am::kIsoFine) {
    ASSERT_NE(coarse_pitch(f.diameter_x10), 0) << f.diameter_x10;
    EXPECT_LT(f.pitch_um, coarse_pitch(f.diameter_x10)) << f.diameter_x10;
  }
}

TEST(LathePitchTables, UnifiedSpotValues) {
  EXPECT_EQ(tpi_x2(am::kUnc, am::kUncCount, 2500), 40);   // 1/4-20 UNC
  EXPECT_EQ(tpi_x2(am::kUnf, am::kUnfCount, 2500), 56);   // 1/4-28 UNF
  EXPECT_EQ(tpi_x2(am::kUnc, am::kUncCount, 5000), 26);   // 1/2-13 UNC
  EXPECT_EQ(tpi_x2(am::kUnc, am::kUncCount, 20000), 9);   // 2-4 1/2 UNC
  EXPECT_EQ(tpi_x2(am::kUnf, am::kUnfCount, 600), 160);   // #0-80 UNF
  EXPECT_EQ(tpi_x2(am::kUnc, am::kUncCount, 1900), 48);   // #10-24 UNC
  EXPECT_EQ(tpi_x2(am::kUnf, am::kUnfCount, 1900), 64);   // #10-32 UNF
  // Numbered sizes: 0.060 in + 0.013 in per number.
  const int numbers[] = {1, 2, 3, 4, 5, 6, 8, 10, 12};
  for (size_t i = 0; i < 9; ++i) EXPECT_EQ(am::kUnc[i].diameter_x10000, 600 + 130 * numbers[i]);
  // Finer for the same diameter.
  for (const auto& f : am::kUnf) {
    const uint8_t c = tpi_x2(am::kUnc, am::kUncCount, f.diameter_x10000);
    if (c != 0) {
      EXPECT_GT(f.tpi_x2, c) << f.diameter_x10000;
    }
  }
}

TEST(LathePitchTables, EntriesConvertToTheirPitch) {
  // 11.5 TPI (NPT) = 25.4 / 11.5 mm = 50800/23 um exactly; 4.5 TPI = 50800/9.
  bool has_11_5 = false, has_4_5 = false;
  for (uint8_t t : am::kCommonTpi) {
    const am::Pitch p = am::pitch_tpi_x2(t);
    // pitch (um) x TPI = 25400: num / den x t / 2 = 25400.
    EXPECT_EQ(uint64_t(p.num) * t, uint64_t(50800) * p.den);
    EXPECT_GE(t, 8);    // 4 TPI
    EXPECT_LE(t, 160);  // 80 TPI
    has_11_5 |= t == 23;
    has_4_5 |= t == 9;
  }
  EXPECT_TRUE(has_11_5);
  EXPECT_TRUE(has_4_5);
  // The seed's feeds.
  bool fine = false, coarse = false;
  for (uint16_t f : am::kTurningFeeds) fine |= f == 40, coarse |= f == 80;
  EXPECT_TRUE(fine && coarse);
}

}  // namespace
