// The operator workflow (core/ui/workflow.h) against a simulated lathe:
// every screen of a threading session read back as text, the ratio and
// length it engages checked against hand-reduced fractions and a 128-bit
// reference, entry errors, the table pick, moves, the emergency stop and the
// settings round trip.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>

#include "ui_fake_lathe.h"

FakeLathe::Motion FakeLathe::motion;
bool FakeLathe::synced_now, FakeLathe::refuse;
int32_t FakeLathe::pos, FakeLathe::target, FakeLathe::cut_start, FakeLathe::error;
uint16_t FakeLathe::rpm_now, FakeLathe::now_ms;
std::vector<FakeLathe::Engage> FakeLathe::engages;
std::vector<std::pair<int32_t, uint32_t>> FakeLathe::moves;
std::vector<am::ui::Settings<am::ui::Drive::stepper>> FakeLathe::saved;

namespace {

using am::ui::State;

struct UiTest : ::testing::Test {
  Ui ui{};
  void SetUp() override {
    FakeLathe::reset();
    ui.start(default_settings(), true);
    ui.poll(0);
  }
  std::string r0() { return row(ui, 0); }
  std::string r1() { return row(ui, 1); }
};

// Reduced p / q as a pair, by std::gcd (the reference, not core/lathe).
std::pair<uint64_t, uint64_t> reduced(unsigned __int128 p, unsigned __int128 q) {
  unsigned __int128 a = p, b = q;
  while (b) {
    const unsigned __int128 t = a % b;
    a = b;
    b = t;
  }
  return {uint64_t(p / a), uint64_t(q / a)};
}

TEST_F(UiTest, ThreadingSessionScreenByScreen) {
  FakeLathe::rpm_now = 250;
  wait_ms(ui, 100);  // the live line refreshes every 100 ms
  EXPECT_EQ(r0(), "1Thr 2Feed 3Move");
  EXPECT_EQ(r1(), " 250rpm Z   0.00");
  press(ui, "1");
  EXPECT_EQ(r0(), "Pitch mm A:TPI  ");
  EXPECT_EQ(r1(), "_               ");
  press(ui, "1#0");
  EXPECT_EQ(r1(), "1.0_            ");
  press(ui, "D");
  EXPECT_EQ(r0(), "Hand            ");
  EXPECT_EQ(r1(), "1Right 2Left    ");
  press(ui, "1");
  EXPECT_EQ(r0(), "Starts 1..8     ");
  EXPECT_EQ(r1(), "1 = one start   ");
  press(ui, "1");
  EXPECT_EQ(r0(), "Length mm 0=run ");
  press(ui, "20D");
  EXPECT_EQ(r0(), "OK to cut pass 1");
  EXPECT_EQ(r1(), " 250rpm Z   0.00");
  press(ui, "D");
  // 1.00 mm on 200 steps per 3.175 mm, 40 counts per turn:
  // 1000 x 200 / (3175 x 40) = 200/127; 20 mm = floor(20000 x 200 / 3175) = 1259 steps.
  ASSERT_EQ(FakeLathe::engages.size(), 1u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.num, 200u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.den, 127u);
  EXPECT_FALSE(FakeLathe::engages[0].reversed);
  EXPECT_EQ(FakeLathe::engages[0].length, 1259);
  ui.poll(0);
  EXPECT_EQ(r0(), "Wait index      ");
  FakeLathe::index();
  FakeLathe::run(630);
  wait_ms(ui, 100);
  EXPECT_EQ(r0(), "Cut  err       0");
  // 630 steps x 3175 / 200 = 10001.25 um
  EXPECT_EQ(r1(), " 250rpm Z  10.00");
  FakeLathe::run(10000);
  EXPECT_EQ(FakeLathe::pos, 1259);
  wait_ms(ui, 10);
  EXPECT_EQ(r0(), "Done slip      0");
  EXPECT_EQ(r1(), "OK=retract C=end");
  press(ui, "D");
  ASSERT_EQ(FakeLathe::moves.size(), 1u);
  EXPECT_EQ(FakeLathe::moves[0].first, 0);
  EXPECT_EQ(FakeLathe::moves[0].second, 4000u);  // the rapid rate
  EXPECT_EQ(r0(), "Retract Z  19.98");            // 1259 x 3175 / 200 = 19986.6 um
  EXPECT_EQ(r1(), "                ");
  FakeLathe::run(1259 / 2);
  wait_ms(ui, 100);
  // 629 of 1259 steps back: floor(629 x 80 / 1259) = 39 columns of 80 lit
  EXPECT_EQ(r1(), "55555554        ");
  FakeLathe::run(1259);
  wait_ms(ui, 10);
  EXPECT_EQ(r0(), "OK to cut pass 2");
  press(ui, "D");
  ASSERT_EQ(FakeLathe::engages.size(), 2u);
  EXPECT_EQ(FakeLathe::engages[1].ratio.num, 200u);
  EXPECT_EQ(FakeLathe::engages[1].ratio.den, 127u);
  EXPECT_EQ(FakeLathe::engages[1].length, 1259);
}

TEST_F(UiTest, LeftHandThirteenTpiFromTheKeys) {
  press(ui, "1A");
  EXPECT_EQ(r0(), "Pitch TPI A:mm  ");
  press(ui, "13D21");
  press(ui, "0D");  // length 0: until stopped
  EXPECT_EQ(r0(), "OK to cut pass 1");
  press(ui, "D");
  // (25400 / 13) x 200 / (3175 x 40) = 40/13
  ASSERT_EQ(FakeLathe::engages.size(), 1u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.num, 40u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.den, 13u);
  EXPECT_TRUE(FakeLathe::engages[0].reversed);
  EXPECT_EQ(FakeLathe::engages[0].length, 0);
  FakeLathe::index();
  FakeLathe::run(5000);
  wait_ms(ui, 10);
  EXPECT_EQ(ui.state(), State::cutting);  // runs until stopped
  press(ui, "D");                          // the emergency stop
  wait_ms(ui, 10);
  EXPECT_EQ(r0(), "Done slip      0");
  EXPECT_EQ(FakeLathe::pos, -5000);
}

// A multi-start thread: its starts on their own screen (one key, 1..8),
// the ratio for the lead (pitch x starts), and each pass offering the next
// start, the first again with the next pass number; A skips to the next
// start, C goes back through the screens.
TEST_F(UiTest, MultiStartThreadOffersEachStartInTurn) {
  press(ui, "11D2");
  EXPECT_EQ(r0(), "Starts 1..8     ");
  press(ui, "09C");  // 0 and 9 are not a number of starts; C goes back
  EXPECT_EQ(r0(), "Hand            ");
  press(ui, "13");
  EXPECT_EQ(r0(), "Length mm 0=run ");
  press(ui, "C");
  EXPECT_EQ(r0(), "Starts 1..8     ");
  press(ui, "3");
  press(ui, "10D");
  // 1.00 mm x 3 starts: a 3 mm lead, 3000 x 200 / (3175 x 40) = 600/127;
  // 10 mm = floor(10000 x 200 / 3175) = 629 steps.
  const char* offers[] = {"OK pass 1 st 1/3", "OK pass 1 st 2/3", "OK pass 1 st 3/3", "OK pass 2 st 1/3"};
  for (int n = 0; n < 4; ++n) {
    EXPECT_EQ(r0(), offers[n]) << n;
    press(ui, "D");
    ASSERT_EQ(FakeLathe::engages.size(), size_t(n + 1));
    const FakeLathe::Engage& e = FakeLathe::engages[n];
    EXPECT_EQ(e.ratio.num, 600u);
    EXPECT_EQ(e.ratio.den, 127u);
    EXPECT_FALSE(e.reversed);
    EXPECT_EQ(e.length, 629);
    EXPECT_EQ(e.start, n % 3) << n;
    EXPECT_EQ(e.starts, 3u);
    FakeLathe::index();
    FakeLathe::run(1000);
    wait_ms(ui, 10);
    EXPECT_EQ(r0(), "Done slip      0");
    press(ui, "D");  // retract to where the pass began
    FakeLathe::run(1000);
    wait_ms(ui, 10);
    EXPECT_EQ(FakeLathe::pos, 0);
  }
  EXPECT_EQ(r0(), "OK pass 2 st 2/3");
  press(ui, "A");  // skip to the next start, the same pass
  EXPECT_EQ(r0(), "OK pass 2 st 3/3");
  press(ui, "A");
  EXPECT_EQ(r0(), "OK pass 2 st 1/3");
  press(ui, "D");
  ASSERT_EQ(FakeLathe::engages.size(), 5u);
  EXPECT_EQ(FakeLathe::engages[4].start, 0u);
  // A new thread starts again from start 1, pass 1; one start says so.
  FakeLathe::stop_now();
  wait_ms(ui, 10);
  press(ui, "C");
  press(ui, "11D11");
  press(ui, "5D");
  EXPECT_EQ(r0(), "OK to cut pass 1");
  press(ui, "AD");  // A: nothing else to offer
  ASSERT_EQ(FakeLathe::engages.size(), 6u);
  EXPECT_EQ(FakeLathe::engages[5].start, 0u);
  EXPECT_EQ(FakeLathe::engages[5].starts, 1u);
}

// B types the table's next distinct value into the entry; D takes it.
TEST_F(UiTest, TablePickTypesTheRowsPitch) {
  press(ui, "1B");
  EXPECT_EQ(r1(), "0.250_          ");  // M1
  press(ui, "B");
  EXPECT_EQ(r1(), "0.300_          ");  // M1.4 (M1.2 repeats 0.25)
  for (int k = 0; k < 8; ++k) press(ui, "B");  // 0.35 0.4 0.45 0.5 0.6 0.7 0.8 1
  EXPECT_EQ(r1(), "1.000_          ");
  press(ui, "B");
  EXPECT_EQ(r1(), "1.250_          ");  // M8
  press(ui, "B");
  EXPECT_EQ(r1(), "1.500_          ");  // M10
  press(ui, "D11");
  press(ui, "0D");
  press(ui, "D");
  ASSERT_EQ(FakeLathe::engages.size(), 1u);  // 1500 x 200 / 127000 = 300/127
  EXPECT_EQ(FakeLathe::engages[0].ratio.num, 300u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.den, 127u);
}

TEST_F(UiTest, InchAndFeedTables) {
  press(ui, "1AB");
  EXPECT_EQ(r1(), "4.0_            ");
  for (int k = 0; k < 11; ++k) press(ui, "B");  // 4.5 5 6 7 8 9 10 11 11.5 12 13
  EXPECT_EQ(r1(), "13.0_           ");
  press(ui, "D21");
  press(ui, "0D");
  press(ui, "D");
  ASSERT_EQ(FakeLathe::engages.size(), 1u);  // 13 TPI, as typed: 40/13
  EXPECT_EQ(FakeLathe::engages[0].ratio.num, 40u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.den, 13u);
  press(ui, "C");
  wait_ms(ui, 10);
  press(ui, "C");
  EXPECT_EQ(r0(), "1Thr 2Feed 3Move");
  press(ui, "2");
  EXPECT_EQ(r0(), "Feed mm/rev B:tb");
  press(ui, "BBB");  // 0.02 0.03 0.04: the seed's fine feed
  EXPECT_EQ(r1(), "0.040_          ");
  press(ui, "D");
  EXPECT_EQ(r0(), "Hand            ");
  press(ui, "1");  // a feed has one start: no starts screen
  EXPECT_EQ(r0(), "Length mm 0=run ");
  press(ui, "10D");
  press(ui, "D");
  // 40 um x 200 / (3175 x 40) = 8000 / 127000 = 8/127
  ASSERT_EQ(FakeLathe::engages.size(), 2u);
  EXPECT_EQ(FakeLathe::engages[1].ratio.num, 8u);
  EXPECT_EQ(FakeLathe::engages[1].ratio.den, 127u);
  EXPECT_EQ(FakeLathe::engages[1].length, 629);  // floor(10000 x 200 / 3175)
  EXPECT_EQ(FakeLathe::engages[1].starts, 1u);
}

TEST_F(UiTest, EntryErrorsSayWhatIsWrongAndGoBack) {
  press(ui, "1");
  press(ui, "D");
  EXPECT_EQ(r0(), "Type a number   ");
  wait_ms(ui, 1490);
  EXPECT_EQ(ui.state(), State::message);
  wait_ms(ui, 20);
  EXPECT_EQ(r0(), "Pitch mm A:TPI  ");
  press(ui, "0D");
  EXPECT_EQ(r0(), "Out of range    ");
  EXPECT_EQ(r1(), "0.010..50.000   ");
  press(ui, "C");  // any key goes back, to the text as typed
  EXPECT_EQ(r1(), "0_              ");
  press(ui, "C1#2#");  // a second point is not typed
  EXPECT_EQ(r1(), "1.2_            ");
  press(ui, "CCC1#2345D");
  EXPECT_EQ(r0(), "Fewer decimals  ");
  press(ui, "CCCCCCC99999999D");  // saturates, still out of range
  EXPECT_EQ(r0(), "Out of range    ");
  press(ui, "CCCCCCCCC");
  EXPECT_EQ(r1(), "_               ");
  press(ui, "12C");  // C deletes the last digit
  EXPECT_EQ(r1(), "1_              ");
  press(ui, "CC");   // then goes back
  EXPECT_EQ(r0(), "1Thr 2Feed 3Move");
  EXPECT_TRUE(FakeLathe::engages.empty());
}

TEST_F(UiTest, RefusedCutAndMoveLeaveTheCarriageStill) {
  FakeLathe::refuse = true;
  press(ui, "1");
  press(ui, "1D11");
  press(ui, "5D");
  press(ui, "D");
  EXPECT_EQ(r0(), "Cut refused     ");
  EXPECT_EQ(r1(), "                ");
  wait_ms(ui, 1600);
  EXPECT_EQ(r0(), "OK to cut pass 1");
  press(ui, "C3");
  press(ui, "5D");
  EXPECT_EQ(r0(), "Move refused    ");
  EXPECT_EQ(FakeLathe::pos, 0);
  EXPECT_EQ(FakeLathe::motion, FakeLathe::idle);
}

TEST_F(UiTest, MoveWithSignAndProgressBar) {
  press(ui, "3");
  EXPECT_EQ(r0(), "Move mm *:minus ");
  press(ui, "*1#5*");  // '*' counts first only
  EXPECT_EQ(r1(), "-1.5_           ");
  press(ui, "D");
  ASSERT_EQ(FakeLathe::moves.size(), 1u);
  EXPECT_EQ(FakeLathe::moves[0].first, -94);  // -floor(1500 x 200 / 3175)
  FakeLathe::run(47);
  wait_ms(ui, 100);
  EXPECT_EQ(r0(), "Move    Z  -0.74");  // -47 x 3175 / 200 = -746.1 um
  EXPECT_EQ(r1(), "55555555        ");  // 47 of 94: 40 of 80 columns
  FakeLathe::run(46);
  wait_ms(ui, 100);
  EXPECT_EQ(r1(), "5555555555555554");  // 93 of 94: 79 columns
  FakeLathe::run(10);
  wait_ms(ui, 10);
  EXPECT_EQ(ui.state(), State::menu);
  EXPECT_EQ(FakeLathe::pos, -94);
}

TEST_F(UiTest, SettingsEditedValidatedAndSaved) {
  press(ui, "A");
  EXPECT_EQ(r0(), "Encoder lines   ");
  EXPECT_EQ(r1(), "40           1/8");
  press(ui, "D150D");
  EXPECT_EQ(r1(), "150          1/8");
  press(ui, "AD1D");  // quadrature: 150 lines x 4 = 600 counts
  EXPECT_EQ(r0(), "Quadrature 0/1  ");
  EXPECT_EQ(r1(), "1            2/8");
  press(ui, "A");
  EXPECT_EQ(r0(), "Lead mm         ");
  EXPECT_EQ(r1(), "3.175        3/8");
  press(ui, "AAA");
  EXPECT_EQ(r0(), "Microsteps      ");
  press(ui, "D0D");
  EXPECT_EQ(r0(), "Out of range    ");
  EXPECT_EQ(r1(), "1..256          ");
  press(ui, "C");
  press(ui, "C8D");
  EXPECT_EQ(r1(), "8            6/8");
  EXPECT_TRUE(FakeLathe::saved.empty());
  press(ui, "AAA");  // round to the first again
  EXPECT_EQ(r0(), "Encoder lines   ");
  press(ui, "C");
  EXPECT_EQ(r0(), "Settings saved  ");
  ASSERT_EQ(FakeLathe::saved.size(), 1u);
  am::ui::Settings<am::ui::Drive::stepper> s = FakeLathe::saved[0];
  EXPECT_EQ(s.value[am::ui::kFieldEncoderLines], 150u);
  EXPECT_EQ(s.value[am::ui::kFieldQuadrature], 1u);
  EXPECT_EQ(s.value[am::ui::kFieldMicrosteps], 8u);
  EXPECT_TRUE(am::ui::load_settings(s, seed_machine()));  // sealed: valid as written
  // The next cut uses them: 1.00 mm x 1600 / (3175 x 600) = 1600000 / 1905000 = 320/381.
  wait_ms(ui, 1600);
  press(ui, "1");
  press(ui, "1D11");
  press(ui, "0D");
  press(ui, "D");
  ASSERT_EQ(FakeLathe::engages.size(), 1u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.num, 320u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.den, 381u);
}

// Where the reduced ratio does not fit the follower's 32 bits, the panel
// refuses it: it never cuts an approximated thread.
TEST_F(UiTest, RatioThatCannotRunExactlyIsRefused) {
  am::ui::Settings<am::ui::Drive::stepper> s = default_settings();
  s.value[am::ui::kFieldEncoderLines] = 16381;
  s.value[am::ui::kFieldLeadUm] = 49999;
  am::ui::seal(s);
  ui.start(s, true);
  press(ui, "1A");
  press(ui, "199#9D11");
  press(ui, "0D");
  // (254000 / 1999) / 49999 x 200 / 16381: the reduced denominator is above 2^31.
  const am::GearRatio g = am::gear_ratio(am::ui::machine(s), {am::Pitch{254000, 1999}, 1, am::Hand::right});
  ASSERT_EQ(g.status, am::RatioStatus::approximated);
  EXPECT_EQ(r0(), "Ratio not exact ");
  press(ui, "D");
  EXPECT_EQ(r0(), "1Thr 2Feed 3Move");
  EXPECT_TRUE(FakeLathe::engages.empty());
}

// With kApproximate the same request is cut at the nearest ratio the
// follower holds: the message shows its lead's error per spindle turn, the
// one gear_ratio() reports (0 pm here, truncated toward zero; its continued fraction and error are held
// against brute force and the definition in test_lathe_ratio.cpp), then the
// pass is ready and engages that ratio.
TEST_F(UiTest, ApproximatingWorkflowCutsTheNearestRatioAndShowsItsError) {
  am::ui::Settings<am::ui::Drive::stepper> s = default_settings();
  s.value[am::ui::kFieldEncoderLines] = 16381;
  s.value[am::ui::kFieldLeadUm] = 49999;
  am::ui::seal(s);
  ApproxUi approx{};
  approx.start(s, true);
  press(approx, "1A");
  press(approx, "199#9D11");
  press(approx, "0D");
  const am::GearRatio g = am::gear_ratio(am::ui::machine(s), {am::Pitch{254000, 1999}, 1, am::Hand::right});
  ASSERT_EQ(g.status, am::RatioStatus::approximated);
  EXPECT_EQ(row(approx, 0), "Approx. ratio   ");
  char expect[32];
  const int32_t e = g.error_pm / 100;  // 0.0001 um
  std::snprintf(expect, sizeof expect, "err%s%d.%04dum/rev", e < 0 ? "-" : "", std::abs(e) / 10000, std::abs(e) % 10000);
  EXPECT_EQ(row(approx, 1), std::string(expect) + std::string(16 - std::strlen(expect), ' '));
  press(approx, "C");  // any key: the ready screen
  EXPECT_EQ(row(approx, 0), "OK to cut pass 1");
  press(approx, "D");
  ASSERT_EQ(FakeLathe::engages.size(), 1u);
  EXPECT_EQ(FakeLathe::engages[0].ratio.num, g.ratio.num);
  EXPECT_EQ(FakeLathe::engages[0].ratio.den, g.ratio.den);
  // An exact ratio shows no message: straight to the ready screen.
  ApproxUi exact{};
  exact.start(default_settings(), true);
  press(exact, "11D110D");
  EXPECT_EQ(row(exact, 0), "OK to cut pass 1");
}

TEST_F(UiTest, InvalidSettingsAtStartSayDefaults) {
  am::ui::Settings<am::ui::Drive::stepper> s;
  std::memset(&s, 0xFF, sizeof s);  // erased EEPROM
  const bool ok = am::ui::load_settings(s, seed_machine());
  EXPECT_FALSE(ok);
  ui.start(s, ok);
  ui.poll(0);
  EXPECT_EQ(r0(), "Defaults loaded ");
  wait_ms(ui, 1600);
  EXPECT_EQ(r0(), "1Thr 2Feed 3Move");
  EXPECT_EQ(ui.settings().value[am::ui::kFieldEncoderLines], 40u);
}

// Typed metric pitches over the whole range, with random hands and lengths
// on random machines: the engaged ratio is the hand-reduced fraction and the
// length floor(um x counts / lead), from 128-bit references.
TEST_F(UiTest, TypedPitchesAndLengthsSweep) {
  std::mt19937 rng(11);
  for (int n = 0; n < 400; ++n) {
    am::ui::Settings<am::ui::Drive::stepper> s = default_settings();
    const uint32_t lines = 1 + rng() % 4096, quad = rng() % 2, steps = 1 + rng() % 400, micro = 1 + rng() % 32;
    const uint32_t lead = 100 + rng() % 49901, counts = lines * (quad ? 4 : 1);
    s.value[am::ui::kFieldEncoderLines] = lines;
    s.value[am::ui::kFieldQuadrature] = quad;
    s.value[am::ui::kFieldMotorSteps] = steps;
    s.value[am::ui::kFieldMicrosteps] = micro;
    s.value[am::ui::kFieldLeadUm] = lead;
    am::ui::seal(s);
    FakeLathe::reset();
    ui.start(s, true);
    const uint32_t pitch = 10 + rng() % 49991;      // um
    const uint32_t length = rng() % 200001;         // 0.01 mm
    char keys[64];
    std::snprintf(keys, sizeof keys, "1%u#%03uD11%u#%02uD", pitch / 1000, pitch % 1000, length / 100, length % 100);
    press(ui, keys);
    ASSERT_EQ(ui.state(), State::ready) << keys;
    press(ui, "D");
    ASSERT_EQ(FakeLathe::engages.size(), 1u) << keys;
    const auto want = reduced((unsigned __int128)pitch * steps * micro, (unsigned __int128)lead * counts);
    EXPECT_EQ(FakeLathe::engages[0].ratio.num, want.first) << keys;
    EXPECT_EQ(FakeLathe::engages[0].ratio.den, want.second) << keys;
    const unsigned __int128 len_steps = (unsigned __int128)length * 10 * steps * micro / lead;
    EXPECT_EQ(FakeLathe::engages[0].length, int32_t(len_steps)) << keys;
  }
}

// The live line's Z: floor(|steps| x lead / counts) um, shown in 0.01 mm,
// for positions across the int32 range on random machines.
TEST_F(UiTest, LivePositionSweep) {
  std::mt19937 rng(12);
  for (int n = 0; n < 300; ++n) {
    am::ui::Settings<am::ui::Drive::stepper> s = default_settings();
    const uint32_t steps = 1 + rng() % 10000, micro = 1 + rng() % 256, lead = 100 + rng() % 49901;
    s.value[am::ui::kFieldMotorSteps] = steps;
    s.value[am::ui::kFieldMicrosteps] = micro;
    s.value[am::ui::kFieldLeadUm] = lead;
    am::ui::seal(s);
    ui.start(s, true);
    FakeLathe::pos = int32_t(rng() % 2000001) - 1000000;
    FakeLathe::rpm_now = uint16_t(rng() % 10000);
    wait_ms(ui, 100);
    const uint64_t mag = uint64_t(std::abs(int64_t(FakeLathe::pos))) * lead / (uint64_t(steps) * micro) / 10;
    char want[32];
    char z[32];
    std::snprintf(z, sizeof z, "%s%llu.%02llu", FakeLathe::pos < 0 && mag ? "-" : "", (unsigned long long)(mag / 100),
                  (unsigned long long)(mag % 100));
    if (std::strlen(z) > 7) std::snprintf(z, sizeof z, "*");
    std::snprintf(want, sizeof want, "%4urpm Z%7s", FakeLathe::rpm_now, z);
    if (z[0] == '*') std::snprintf(want, sizeof want, "%4urpm Z*      ", FakeLathe::rpm_now);
    EXPECT_EQ(r1(), std::string(want)) << FakeLathe::pos;
  }
}

}  // namespace
