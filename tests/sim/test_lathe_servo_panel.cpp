// The m32-servo-panel image: the seed's DC-servo lathe with the operator
// panel, its settings (the servo's encoder, gearbox and PID gains) in the
// EEPROM. The display and keypad models drive it (sim/lcd_model.h,
// sim/keypad_model.h), the DC servo plant and the spindle model are the
// m16-servo tests'. Checked: every settings screen; the gains typed reach
// the PID (its coefficients read from the firmware's RAM against their
// definitions, after the edit and after a power cycle) and the EEPROM block
// (against the test's own sum); a torn block gives the board's gains back;
// a pass cut from the keys follows the helix within the servo's bound.
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "board_info.h"
#include "core/lathe/ratio.h"
#include "dc_servo.h"
#include "panel_rig.h"
#include "servo_pass.h"

namespace {

constexpr const char* kImage = "m32-servo-panel";
constexpr uint32_t kBlockBytes = 46;  // 11 fields x 4 bytes + the check (core/ui/settings.h)
constexpr double kSampleS = 16 * 1024 / 16e6;  // the PID's period (m16-servo.h: 16 PWM periods)

struct ServoPanel : simtest::PanelRig {
  std::unique_ptr<sim::DcServo> servo;

  explicit ServoPanel(const std::vector<uint8_t>& eeprom = {}, const sim::SpindleParams& sp = sim::SpindleParams())
      : PanelRig(kImage, eeprom, sp), servo(new sim::DcServo(*m, sim::ServoParams())) {}
  std::vector<uint8_t> eeprom() { return PanelRig::eeprom(kBlockBytes); }
  // The PID's coefficients Kp (Q8), Ki Ts (Q16), Kd / Ts (Q8) as they are in
  // the firmware's RAM (core/lathe/servo_pid.h: ServoPid begins with them).
  std::vector<int32_t> coefficients() const {
    const uint16_t pid = sim::read_data_symbol(simtest::image(kImage), "_ZN9leadscrew12_GLOBAL__N_13pidE");
    std::vector<int32_t> c;
    for (uint32_t k = 0; k < 3; ++k) {
      uint32_t v = 0;
      for (uint32_t b = 0; b < 4; ++b) v |= uint32_t(m->avr()->data[pid + 4 * k + b]) << (8 * b);
      c.push_back(int32_t(v));
    }
    return c;
  }
};

std::string padded(const std::string& s) { return s + std::string(16 - s.size(), ' '); }

// A settings screen's second row: the value, then "N/11" at the row's end.
std::string setting_row(const std::string& value, int n) {
  char tail[8];
  std::snprintf(tail, sizeof tail, "%2d/11", n);
  return value + std::string(11 - value.size(), ' ') + tail;
}

uint32_t le32(const std::vector<uint8_t>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}

// Fletcher-16 over the values, started from the servo layout's 'S1'.
uint16_t fletcher(const std::vector<uint8_t>& b) {
  uint32_t lo = '1', hi = 'S';
  for (size_t i = 0; i + 2 < b.size(); ++i) {
    lo = (lo + b[i]) % 255;
    hi = (hi + lo) % 255;
  }
  return uint16_t(hi << 8 | lo);
}

// The coefficients' definitions for gains in thousandths: Kp x 2^8, Ki Ts x
// 2^16, Kd / Ts x 2^8 (the last rounded twice: Kd / Ts to 0.001 first).
void expect_coefficients(const std::vector<int32_t>& c, double kp_milli, double ki_milli, double kd_milli) {
  ASSERT_EQ(c.size(), 3u);
  EXPECT_LE(std::fabs(c[0] - kp_milli / 1000 * 256), 0.5) << c[0];
  EXPECT_LE(std::fabs(c[1] - ki_milli / 1000 * kSampleS * 65536), 0.5) << c[1];
  EXPECT_LE(std::fabs(c[2] - kd_milli / 1000 / kSampleS * 256), 0.63) << c[2];
}

TEST(LatheServoPanel, EverySettingsScreenShowsTheServosMachine) {
  ServoPanel p;
  p.run_to(0.3);
  EXPECT_EQ(p.row0(), padded("Defaults loaded"));
  p.run_to(1.8);
  EXPECT_EQ(p.row0(), padded("1Thr 2Feed 3Move"));
  const std::vector<std::pair<std::string, std::string>> screens = {
      {"Encoder lines", "40"},   {"Quadrature 0", "0"},    {"Lead mm", "3.175"},          {"Lead TPI 0=mm", "8.0"},
      {"Pulses/motor rev", "30"}, {"Gearbox 1:N", "26"},    {"Reverse 0/1", "1"},          {"Rapid counts/s", "1800"},
      {"Kp duty/count", "72.037"}, {"Ki duty/count s", "82.608"}, {"Kd duty s/count", "0.672"},
  };
  p.type("A");
  for (size_t i = 0; i < screens.size(); ++i) {
    EXPECT_EQ(p.row0(), padded(screens[i].first)) << i;
    EXPECT_EQ(p.row1(), setting_row(screens[i].second, int(i + 1))) << i;
    p.type("A");
  }
  EXPECT_EQ(p.row0(), padded("Encoder lines"));  // after the last, the first
  // The board's gains are in the PID from power-up.
  expect_coefficients(p.coefficients(), 72037, 82608, 672);
}

TEST(LatheServoPanel, GainsGoThroughTheEepromIntoThePid) {
  std::vector<uint8_t> stored;
  {
    ServoPanel p;
    p.run_to(1.8);
    p.type("A");
    p.type("AD1D");  // quadrature: the servo's spindle has one channel
    EXPECT_EQ(p.row0(), padded("Out of range"));
    EXPECT_EQ(p.row1(), padded("0..0"));
    p.run_to(p.now() + 1.6);
    p.type("CC");  // back from the entry to the field
    EXPECT_EQ(p.row0(), padded("Quadrature 0"));
    p.type("AAAAAAA");
    EXPECT_EQ(p.row0(), padded("Kp duty/count"));
    p.type("D50#5D");
    EXPECT_EQ(p.row1(), setting_row("50.500", 9));
    p.type("AD0D");
    EXPECT_EQ(p.row1(), setting_row("0.000", 10));
    p.type("AD5D");  // Kd beyond the PID's Kd / Ts range
    EXPECT_EQ(p.row0(), padded("Out of range"));
    EXPECT_EQ(p.row1(), padded("0.000..4.000"));
    p.run_to(p.now() + 1.6);
    p.type("C1#25D");
    EXPECT_EQ(p.row1(), setting_row("1.250", 11));
    // Not taken before the settings are left.
    expect_coefficients(p.coefficients(), 72037, 82608, 672);
    p.type("C");
    EXPECT_EQ(p.row0(), padded("Settings saved"));
    p.run_to(p.now() + 0.5);  // 46 bytes at 3.4 ms each: written by now
    expect_coefficients(p.coefficients(), 50500, 0, 1250);
    stored = p.eeprom();
  }
  ASSERT_EQ(stored.size(), kBlockBytes);
  EXPECT_EQ(le32(stored, 16), 30u);  // pulses
  EXPECT_EQ(le32(stored, 20), 26u);  // gearbox
  EXPECT_EQ(le32(stored, 32), 50500u);
  EXPECT_EQ(le32(stored, 36), 0u);
  EXPECT_EQ(le32(stored, 40), 1250u);
  EXPECT_EQ(uint16_t(stored[44] | stored[45] << 8), fletcher(stored));
  {  // A power cycle: no message, the stored gains in the PID from the start.
    ServoPanel p(stored);
    p.run_to(0.3);
    EXPECT_EQ(p.row0(), padded("1Thr 2Feed 3Move"));
    expect_coefficients(p.coefficients(), 50500, 0, 1250);
  }
  for (size_t at : {size_t(0), size_t(33), size_t(45)}) {  // a value byte, a gain's, the check
    std::vector<uint8_t> torn = stored;
    torn[at] ^= 0x10;
    ServoPanel p(torn);
    p.run_to(0.3);
    EXPECT_EQ(p.row0(), padded("Defaults loaded")) << at;
    expect_coefficients(p.coefficients(), 72037, 82608, 672);
  }
}

// A ratio the follower cannot hold in 32 bits (a 16381-line encoder, a
// 49.999 mm lead, 199.9 TPI: the host tests' case) is approximated on this
// image, not refused: the screen shows the error the host-tested core
// reports for it, then the pass is ready.
TEST(LatheServoPanel, ARatioBeyond32BitsIsApproximatedWithItsError) {
  const am::Machine m = {am::pitch_um(49999), am::servo_counts(30, 26), 16381, true};
  const am::GearRatio g = am::gear_ratio(m, {am::Pitch{254000, 1999}, 1, am::Hand::right});
  ASSERT_EQ(g.status, am::RatioStatus::approximated);
  ASSERT_EQ(am::gear_ratio_exact(m, {am::Pitch{254000, 1999}, 1, am::Hand::right}).status,
            am::RatioStatus::out_of_range);
  const int32_t e = g.error_pm / 100;
  char err[32];
  std::snprintf(err, sizeof err, "err%s%d.%04dum/rev", e < 0 ? "-" : "", std::abs(e) / 10000, std::abs(e) % 10000);
  ServoPanel p;
  p.run_to(1.8);
  p.type("AD16381D");
  p.type("AAD49#999D");
  EXPECT_EQ(p.row1(), setting_row("49.999", 3));
  p.type("AD0D");
  EXPECT_EQ(p.row1(), setting_row("0.0", 4));
  p.type("C");
  p.run_to(p.now() + 1.6);
  EXPECT_EQ(p.row0(), padded("1Thr 2Feed 3Move"));
  p.type("1A199#9D11");
  EXPECT_EQ(p.row0(), padded("Length mm 0=run"));
  p.type("0D");
  EXPECT_EQ(p.row0(), padded("Approx. ratio"));
  EXPECT_EQ(p.row1(), padded(err));
  p.type("D");  // any key
  EXPECT_EQ(p.row0(), padded("OK to cut pass 1"));
}

// A 1.00 mm right-hand thread, 5 mm long, cut from the keys on the seed's
// disc: the spindle from rest to 300 rpm once the pass is armed.
TEST(LatheServoPanel, APassFromTheKeysFollowsTheHelix) {
  sim::SpindleParams sp;
  sp.lines = 40;
  sp.profile = {{0, 0}, {4.0, 0}, {5.0, 300}, {9.0, 300}, {10.0, 0}};
  ServoPanel p({}, sp);
  p.run_to(1.8);
  p.type("11D");  // a thread, 1 mm
  p.type("1");    // right hand
  p.type("1");    // one start
  EXPECT_EQ(p.row0(), padded("Length mm 0=run"));
  p.type("5D");
  EXPECT_EQ(p.row0(), padded("OK to cut pass 1"));
  const double base = p.servo->position();
  const uint64_t armed = p.m->cycles();
  p.type("D");
  EXPECT_EQ(p.row0(), padded("Wait index"));
  ASSERT_LT(p.now(), 4.0);
  const uint64_t budget = uint64_t(12 * p.m->f_cpu());
  p.m->run([&] { return p.row0().rfind("Done slip", 0) == 0; }, budget);
  ASSERT_EQ(p.row0().substr(0, 9), "Done slip") << p.row0();
  // 5 mm at 780 counts per 3.175 mm: the pass ends on the count whose
  // target reaches 1228 counts towards the chuck.
  const servotest::PassFigures f = servotest::measure(p, armed, base, -1228, p.m->cycles());
  ASSERT_TRUE(f.index_found);
  EXPECT_GT(f.end_cycle, f.index_cycle);
  EXPECT_GT(f.samples, 1000u);
  EXPECT_LE(f.worst, servotest::kFollowBound) << "lag " << f.max_lag << " lead " << f.max_lead;
  std::printf("m32-servo-panel pass from the keys: %zu servo samples, lag <= %.2f, lead <= %.2f counts (bound %.0f)\n",
              f.samples, f.max_lag, f.max_lead, servotest::kFollowBound);
  // The image within the ATmega32 with the lathe images' 10 % to spare; the
  // session's deepest stack (the ratio's set-up on the length) within RAM.
  const simtest::ImageSize size = simtest::avr_size(kImage, "atmega32");
  ASSERT_GT(size.flash, 0u);
  const unsigned stack = p.m->stack_bytes(), free_ram = p.m->free_ram();
  std::printf("m32-servo-panel: %lu B of flash (limit 29491 B, 90 %% of 32768), %lu B of RAM (.data + .bss), "
              "stack %u B of the %u B above them\n",
              size.flash, size.ram, stack, free_ram);
  EXPECT_LE(size.flash, 29491u);
  EXPECT_LE(size.ram, 2048u);
  EXPECT_LE(stack + 64, free_ram) << "less than 64 B of stack to spare";
}

}  // namespace
