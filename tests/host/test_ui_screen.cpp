// core/ui's screen buffer and settings block: numbers against printf, the
// dirty mask, the progress bar, the table rows against core/lathe's arrays,
// and the settings block's validation (checksum, ranges, erased cells).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "../../core/ui/settings.h"
#include "../../core/ui/tables.h"

namespace {

using am::ui::Screen;

std::string row_text(const Screen& s, int r) { return std::string(s.cell + r * 16, 16); }

// printf's rendering of v / 10^dec, right-aligned in `width`, "*" padded
// when it does not fit.
std::string reference(int32_t v, int width, int dec) {
  char body[32];
  const long long mag = v < 0 ? -(long long)v : v;
  long long p = 1;
  for (int i = 0; i < dec; ++i) p *= 10;
  if (dec)
    std::snprintf(body, sizeof body, "%s%lld.%0*lld", v < 0 ? "-" : "", mag / p, dec, mag % p);
  else
    std::snprintf(body, sizeof body, "%s%lld", v < 0 ? "-" : "", mag);
  std::string b = body;
  if (width == 0) return b;
  if (int(b.size()) > width) return "*" + std::string(width - 1, ' ');
  return std::string(width - b.size(), ' ') + b;
}

TEST(UiScreen, NumbersMatchPrintfOverASweep) {
  std::mt19937 rng(3);
  for (int n = 0; n < 20000; ++n) {
    Screen s;
    s.clear_sent();
    int32_t v = int32_t(rng());
    if (n % 3 == 0) v %= 100000;
    if (n % 7 == 0) v = int32_t(rng() % 21) - 10;
    if (n == 1) v = INT32_MIN;
    const int dec = int(rng() % 5), width = int(rng() % 13);
    const uint8_t end = s.number(0, 1, v, uint8_t(width), uint8_t(dec));
    const std::string want = reference(v, width, dec);
    const std::string got = row_text(s, 0).substr(1, want.size());
    ASSERT_EQ(got, want.substr(0, 15)) << v << " w" << width << " d" << dec;
    EXPECT_EQ(end, 1 + want.size());
  }
}

TEST(UiScreen, DirtyBitsOnlyForChangedCells) {
  Screen s;
  s.clear_sent();
  s.line(0, "ab");
  EXPECT_EQ(s.dirty, 0x3u);  // the spaces were already there
  s.dirty = 0;
  s.line(0, "ab");
  EXPECT_EQ(s.dirty, 0u);
  s.put(1, 15, 'x');
  EXPECT_EQ(s.dirty, 1u << 31);
  s.put(1, 16, 'y');  // past the row: dropped
  EXPECT_EQ(s.dirty, 1u << 31);
  EXPECT_EQ(row_text(s, 1), "               x");
}

TEST(UiScreen, BarFillsGlyphByGlyph) {
  for (int filled = 0; filled <= am::ui::kBarSteps; ++filled) {
    Screen s;
    s.clear_sent();
    s.bar(1, uint8_t(filled));
    int lit = 0;
    for (int c = 0; c < 16; ++c) {
      const char g = s.cell[16 + c];
      const int k = g == ' ' ? 0 : g;
      ASSERT_GE(k, 0);
      ASSERT_LE(k, 5);
      if (c < filled / 5) {
        EXPECT_EQ(k, 5);
      }
      lit += k;
    }
    EXPECT_EQ(lit, filled);
  }
}

TEST(UiTables, RowsAreCoreLathesEntries) {
  using namespace am;
  using namespace am::ui;
  ASSERT_EQ(list_size(kMetricList), kIsoCoarseCount);
  for (uint8_t i = 0; i < list_size(kMetricList); ++i) EXPECT_EQ(table_value(kMetricList, i), kIsoCoarse[i].pitch_um);
  ASSERT_EQ(list_size(kInchList), kCommonTpiCount);
  for (uint8_t i = 0; i < list_size(kInchList); ++i) EXPECT_EQ(table_value(kInchList, i), kCommonTpi[i] * 5);
  ASSERT_EQ(list_size(kFeedList), kTurningFeedsCount);
  for (uint8_t i = 0; i < list_size(kFeedList); ++i) EXPECT_EQ(table_value(kFeedList, i), kTurningFeeds[i]);
  // The common TPI hold every UNC and UNF pitch (so those tables are left out).
  for (const InchThread* t : {kUnc, kUnf}) {
    const size_t n = t == kUnc ? kUncCount : kUnfCount;
    for (size_t i = 0; i < n; ++i) {
      bool found = false;
      for (uint8_t k : kCommonTpi) found = found || k == t[i].tpi_x2;
      EXPECT_TRUE(found) << int(t[i].tpi_x2);
    }
  }
  // And the ISO coarse pitches every ISO fine one.
  for (const MetricThread& f : kIsoFine) {
    bool found = false;
    for (const MetricThread& c : kIsoCoarse) found = found || c.pitch_um == f.pitch_um;
    EXPECT_TRUE(found) << f.pitch_um;
  }
}

// The seed's machine: a 40-slot disc, a 3.175 mm leadscrew, 200 full steps.
const am::ui::Settings<am::ui::Drive::stepper> kSeed = {{40, 0, 3175, 0, 200, 1, 0, 4000}, 0};

TEST(UiSettings, DefaultsReplaceAnInvalidBlock) {
  am::ui::Settings<am::ui::Drive::stepper> s{};
  EXPECT_FALSE(am::ui::load_settings(s, kSeed));
  const am::Machine m = am::ui::machine(s);
  EXPECT_EQ(m.spindle_counts, 40);
  EXPECT_EQ(m.leadscrew.num, 3175u);
  EXPECT_EQ(m.leadscrew.den, 1u);
  EXPECT_EQ(m.leadscrew_counts.num, 200u);
  EXPECT_EQ(m.leadscrew_counts.den, 1u);
  EXPECT_FALSE(m.leadscrew_reversed);
  EXPECT_TRUE(am::ui::settings_valid(s));
  s.value[am::ui::kFieldQuadrature] = 1;  // both edges of both channels
  s.value[am::ui::kFieldEncoderLines] = am::ui::kMaxLines;
  EXPECT_EQ(am::ui::machine(s).spindle_counts, 4 * am::ui::kMaxLines);
}

TEST(UiSettings, EveryCorruptionIsCaught) {
  am::ui::Settings<am::ui::Drive::stepper> good{};
  am::ui::load_settings(good, kSeed);
  good.value[am::ui::kFieldMicrosteps] = 16;
  good.value[am::ui::kFieldLeadTpi] = 80;  // an 8 TPI leadscrew
  am::ui::seal(good);
  ASSERT_TRUE(am::ui::settings_valid(good));
  const am::Machine m = am::ui::machine(good);
  EXPECT_EQ(m.leadscrew.num, 254000u);  // 25.4 mm / 8 = 3175 um
  EXPECT_EQ(m.leadscrew.den, 80u);
  // Every single-bit flip of the block is refused (Fletcher-16 catches all
  // of them), so the defaults come back.
  for (size_t bit = 0; bit < sizeof good * 8; ++bit) {
    am::ui::Settings<am::ui::Drive::stepper> s = good;
    reinterpret_cast<uint8_t*>(&s)[bit / 8] ^= uint8_t(1u << (bit % 8));
    if (bit / 8 >= offsetof(am::ui::Settings<am::ui::Drive::stepper>, check) + sizeof s.check) continue;  // padding
    EXPECT_FALSE(am::ui::settings_valid(s)) << bit;
  }
  // A value out of its range with a matching check is refused too.
  for (uint8_t f = 0; f < am::ui::field_count(am::ui::Drive::stepper); ++f) {
    am::ui::Settings<am::ui::Drive::stepper> s = good;
    const am::ui::FieldSpec spec = am::ui::field<am::ui::Drive::stepper>(f);
    s.value[f] = uint32_t(spec.max) + 1;
    am::ui::seal(s);
    EXPECT_FALSE(am::ui::settings_valid(s)) << int(f);
    if (spec.min > 0) {
      s.value[f] = uint32_t(spec.min) - 1;
      am::ui::seal(s);
      EXPECT_FALSE(am::ui::settings_valid(s)) << int(f);
    }
  }
  // Erased cells.
  am::ui::Settings<am::ui::Drive::stepper> erased;
  std::memset(&erased, 0xFF, sizeof erased);
  EXPECT_FALSE(am::ui::load_settings(erased, kSeed));
  EXPECT_TRUE(am::ui::settings_valid(erased));  // now the defaults
}

}  // namespace
