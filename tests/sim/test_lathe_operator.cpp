// The operator panel on the real m16-panel image: the HD44780 model reads
// the screen back from the simulated controller, the keypad model presses
// keys (every contact bouncing) through the firmware's own scan, the spindle
// model turns the encoder. A whole threading session from the keys alone
// with every screen checked, both passes against the independent helix check
// (sim/lathe_check.h) while the screen is being written; the settings menu
// through the EEPROM and back; a corrupted settings block.
#include <simavr/sim_avr.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "lathe_check.h"
#include "panel_rig.h"

namespace {

constexpr uint32_t kSettingsBytes = 34;  // 8 fields x 4 bytes + the check (core/ui/settings.h)

struct Panel : simtest::PanelRig {
  const std::vector<sim::PinEdge>* step;

  explicit Panel(const std::vector<uint8_t>& eeprom = {}, double rpm = 0,
                 const sim::KeypadTiming& keypad = sim::KeypadTiming())
      : PanelRig("m16-panel", eeprom, seed_disc(rpm), keypad), step(&m->watch_pin('C', 0)) {}
  static sim::SpindleParams seed_disc(double rpm) {
    sim::SpindleParams p;  // the seed's 40-slot disc
    p.profile = {{0, rpm}};
    return p;
  }
  // Runs until row 1 reads `text` (the driver writes row 0 first, so the
  // whole screen is then up); false after `budget_s`.
  bool until_row1(const std::string& text, double budget_s) {
    return m->run([&] { return row1() == text; }, uint64_t(budget_s * m->f_cpu())) == sim::RunEnd::done;
  }
  // The live line's rpm (its first 4 columns) is within 1 % of `rpm`: the
  // leadscrew measures it over 0.5 s, 100 spindle counts at 300 rpm.
  bool live_rpm_near(double rpm) const {
    const std::string r = row1();
    return r.substr(4, 5) == "rpm Z" && std::abs(std::atoi(r.substr(0, 4).c_str()) - rpm) <= rpm / 100;
  }
  std::vector<uint8_t> eeprom() { return PanelRig::eeprom(kSettingsBytes); }
  // The cycle of the spindle index's last rise so far.
  uint64_t last_index() const {
    uint64_t at = 0;
    bool was = false;
    for (const sim::SpindleTransition& t : spindle->log()) {
      if (t.index && !was) at = t.cycle;
      was = t.index;
    }
    return at;
  }
};

uint32_t le32(const std::vector<uint8_t>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}

TEST(LatheOperator, StartsWithTheMenuAndTheBarGlyphs) {
  Panel p;
  p.run_to(0.3);
  EXPECT_TRUE(p.lcd->four_bit());
  EXPECT_TRUE(p.lcd->display_on());
  // Erased EEPROM: the defaults, with a message, then the menu.
  EXPECT_EQ(p.row0(), "Defaults loaded ");
  EXPECT_EQ(p.row1(), "                ");
  p.run_to(2.0);
  EXPECT_EQ(p.row0(), "1Thr 2Feed 3Move");
  EXPECT_EQ(p.row1(), "   0rpm Z   0.00");
  for (int k = 1; k <= 5; ++k) {
    const uint8_t bits = uint8_t(0x1F & ~(0x1F >> k));  // k columns lit from the left
    for (uint8_t row : p.lcd->glyph(k)) EXPECT_EQ(int(row), int(bits)) << k;
  }
  EXPECT_EQ(p.lcd->busy_writes(), 0u);
}

// Presses D 5 ms after an index edge, so the pass arms (debounced within
// 25 ms) long before the next one (every 200 ms at 300 rpm): the pass's
// index is the first after the press. Returns the press's cycle.
uint64_t press_ok_after_index(Panel& p) {
  const uint64_t from = p.m->cycles();
  p.m->run([&] { return p.last_index() > from; }, p.m->f_cpu());
  const double at = double(p.last_index()) / p.m->f_cpu() + 0.005;
  p.keys->press('D', at);
  p.run_to(at + 0.03);
  return uint64_t(at * p.m->f_cpu());
}

// A 1.00 mm right-hand thread, 20 mm long, two passes, on the seed's disc at
// 300 rpm, from the keys alone.
TEST(LatheOperator, WholeThreadingSessionFromTheKeys) {
  Panel p({}, 300);
  p.run_to(1.8);  // past "Defaults loaded"
  EXPECT_EQ(p.row0(), "1Thr 2Feed 3Move");
  EXPECT_TRUE(p.live_rpm_near(300)) << p.row1();
  EXPECT_EQ(p.row1().substr(9), "   0.00");
  p.type("1");
  EXPECT_EQ(p.row0(), "Pitch mm A:TPI  ");
  EXPECT_EQ(p.row1(), "_               ");
  p.type("1#0");
  EXPECT_EQ(p.row1(), "1.0_            ");  // every bouncing key counted once
  p.type("D");
  EXPECT_EQ(p.row0(), "Hand            ");
  EXPECT_EQ(p.row1(), "1Right 2Left    ");
  p.type("1");
  EXPECT_EQ(p.row0(), "Starts 1..8     ");
  EXPECT_EQ(p.row1(), "1 = one start   ");
  p.type("1");
  EXPECT_EQ(p.row0(), "Length mm 0=run ");
  p.type("20D");
  EXPECT_EQ(p.row0(), "OK to cut pass 1");
  EXPECT_TRUE(p.live_rpm_near(300)) << p.row1();

  // 20 mm on 800 steps per 3.175 mm: floor(20000 x 800 / 3175) = 5039 steps,
  // toward the chuck (negative) for a right-hand thread.
  const int64_t end = -5039;
  sim::ThreadSpec spec;
  spec.pitch_num = 1000;
  spec.pitch_den = 1;
  spec.counts_per_turn = 40;
  for (int pass = 1; pass <= 2; ++pass) {
    const uint64_t changes_before = p.lcd->changes();
    const uint64_t armed = press_ok_after_index(p);
    EXPECT_EQ(p.row0(), "Wait index      ") << pass;
    // Mid-cut: 1.00 mm per turn at 300 rpm is 5 mm/s.
    p.run_to(p.now() + 2.0);
    EXPECT_EQ(p.row0(), "Cut  err       0") << pass;
    EXPECT_TRUE(p.live_rpm_near(300)) << p.row1();
    // Z on the live line: the carriage where the display was last written,
    // within the 100 ms refresh (5 mm/s: 0.5 mm) of where it is.
    const double z_mm = std::atof(p.row1().substr(9).c_str()), z_now = p.m->axis('Z')->position * 3.175 / 800;
    EXPECT_LT(z_mm, 0) << p.row1();
    EXPECT_NEAR(z_mm, z_now, 0.6) << p.row1();
    ASSERT_TRUE(p.until_row1("OK=retract C=end", 5)) << pass;
    const uint64_t until = p.m->cycles();
    EXPECT_EQ(p.row0(), "Done slip      0") << pass;
    const sim::PassResult r = sim::check_pass(*p.spindle, *p.m->axis('Z'), *p.step, spec, 0, armed, until, &end);
    ASSERT_TRUE(r.index_found) << pass;
    EXPECT_TRUE(r.locked) << pass;
    EXPECT_EQ(r.mismatches, 0u) << pass;
    EXPECT_EQ(r.position, end) << pass;
    EXPECT_EQ(r.expected, end) << pass;
    // The screen was being written all through the pass (the live line every
    // 100 ms): the helix was followed exactly meanwhile.
    const uint64_t changes = p.lcd->changes() - changes_before;
    EXPECT_GT(changes, 20u) << pass;
    std::printf("pass %d: %zu counts after the index, locked after %zu, %lld steps = the helix's; %llu screen "
                "changes during the pass; spindle count to step: at most %llu cycles\n",
                pass, r.counts, r.locked_after, (long long)r.position, (unsigned long long)changes,
                (unsigned long long)r.max_latency);
    p.type("D");  // retract
    EXPECT_EQ(p.row0().substr(0, 9), "Retract Z") << pass;
    ASSERT_TRUE(p.m->run([&] { return p.row0() == "OK to cut pass " + std::to_string(pass + 1); },
                         uint64_t(5 * p.m->f_cpu())) == sim::RunEnd::done)
        << pass;
    EXPECT_EQ(p.m->axis('Z')->position, 0) << pass;
  }
  p.type("C");
  EXPECT_EQ(p.row0(), "1Thr 2Feed 3Move");
  EXPECT_EQ(p.m->axis('Z')->decode_errors, 0u);
  EXPECT_EQ(p.lcd->busy_writes(), 0u);
  // The session's deepest stack (the ratio's 128-bit set-up on the length's
  // D) against the RAM left above .data and .bss.
  EXPECT_LT(p.m->stack_bytes(), p.m->free_ram());
  std::printf("m16-panel session: stack %u B of %u B free above .data and .bss\n", p.m->stack_bytes(),
              p.m->free_ram());
}

// A three-start thread from the keys: 0.50 mm pitch, 1.50 mm lead, 10 mm,
// on the seed's disc at 300 rpm. Each pass offers the next start; each
// start's pass is checked count by count against its own helix, start k
// k/3 of a turn (40/3 counts: not a whole count, held exactly) after start
// 0, from the same base; after the third start the first again, pass 2.
TEST(LatheOperator, MultiStartPassesFromTheKeysLandOnTheirPhase) {
  Panel p({}, 300);
  p.run_to(1.8);
  p.type("1");
  p.type("0#5D");
  EXPECT_EQ(p.row0(), "Hand            ");
  p.type("1");
  EXPECT_EQ(p.row0(), "Starts 1..8     ");
  EXPECT_EQ(p.row1(), "1 = one start   ");
  p.type("3");
  EXPECT_EQ(p.row0(), "Length mm 0=run ");
  p.type("10D");
  // floor(10000 x 800 / 3175) = 2519 steps toward the chuck.
  const int64_t end = -2519;
  const char* offers[] = {"OK pass 1 st 1/3", "OK pass 1 st 2/3", "OK pass 1 st 3/3", "OK pass 2 st 1/3",
                          "OK pass 2 st 2/3"};
  for (int n = 0; n < 4; ++n) {
    const int k = n % 3;
    EXPECT_EQ(p.row0(), offers[n]) << n;
    const uint64_t armed = press_ok_after_index(p);
    EXPECT_EQ(p.row0(), "Wait index      ") << n;
    p.run_to(p.now() + 0.8);  // the pass takes 6.7 turns, 1.33 s
    EXPECT_EQ(p.row0(), "Cut  err       0") << n;
    ASSERT_TRUE(p.until_row1("OK=retract C=end", 3)) << n;
    EXPECT_EQ(p.row0(), "Done slip      0") << n;
    sim::ThreadSpec spec;
    spec.pitch_num = 500;
    spec.pitch_den = 1;
    spec.starts = 3;
    spec.start = k;
    spec.counts_per_turn = 40;
    const sim::PassResult r = sim::check_pass(*p.spindle, *p.m->axis('Z'), *p.step, spec, 0, armed, p.m->cycles(), &end);
    ASSERT_TRUE(r.index_found) << n;
    EXPECT_TRUE(r.locked) << n;
    EXPECT_EQ(r.mismatches, 0u) << n;
    EXPECT_EQ(r.position, end) << n;
    EXPECT_EQ(r.expected, end) << n;
    // The start's helix at the index (s = 0): floor(lambda k C / 3) steps
    // from start 1's, which a pass cut on another start's phase would miss.
    sim::ThreadSpec start0 = spec;
    start0.start = 0;
    const int64_t offset = sim::target_steps(spec, 0) - sim::target_steps(start0, 0);
    std::printf("pass %d start %d of 3: %zu counts after the index, locked after %zu, %lld steps = the start's "
                "helix, %lld steps from start 1's at the index\n",
                n / 3 + 1, k + 1, r.counts, r.locked_after, (long long)r.position, (long long)offset);
    p.type("D");
    EXPECT_EQ(p.row0().substr(0, 9), "Retract Z") << n;
    ASSERT_TRUE(p.m->run([&] { return p.row0() == offers[n + 1]; }, uint64_t(3 * p.m->f_cpu())) == sim::RunEnd::done)
        << n;
    // Row 1 follows row 0 on the bus: the live line within its 100 ms refresh.
    ASSERT_TRUE(p.m->run([&] { return p.live_rpm_near(300); }, uint64_t(0.2 * p.m->f_cpu())) == sim::RunEnd::done)
        << p.row1();
    EXPECT_EQ(p.m->axis('Z')->position, 0) << n;
  }
  EXPECT_EQ(p.m->axis('Z')->decode_errors, 0u);
  EXPECT_EQ(p.lcd->busy_writes(), 0u);
}

// The panel image within the ATmega16's flash with 10 % to spare (avr-size
// of the toolchain that built it).
TEST(LatheOperator, PanelImageLeavesTenPercentOfTheFlash) {
  const simtest::ImageSize size = simtest::avr_size("m16-panel", "atmega16");
  const unsigned long flash = size.flash, ram = size.ram;
  ASSERT_GT(flash, 0u);
  std::printf("m16-panel: %lu B of flash (limit 14745 B, 90 %% of 16384), %lu B of RAM (.data + .bss)\n", flash, ram);
  EXPECT_LE(flash, 14745u);
  EXPECT_LE(ram, 1024u);
}

// The retract's progress bar, read from the display while it moves.
TEST(LatheOperator, MoveShowsItsProgressBar) {
  Panel p;
  p.run_to(1.8);
  p.type("3");
  EXPECT_EQ(p.row0(), "Move mm *:minus ");
  p.type("*10D");  // -10 mm: floor(10000 x 800 / 3175) = 2519 steps at 4000 steps/s
  std::vector<std::string> bars;
  p.m->run(
      [&] {
        const bool moving = p.row0().rfind("Move    Z", 0) == 0 && p.m->axis('Z')->position != -2519;
        if (moving && (bars.empty() || bars.back() != p.row1())) bars.push_back(p.row1());
        return p.row1() == "   0rpm Z  -9.99";  // -2519 x 3175 / 800 = -9997.3 um
      },
      uint64_t(3 * p.m->f_cpu()));
  EXPECT_EQ(p.row0(), "1Thr 2Feed 3Move");
  EXPECT_EQ(p.m->axis('Z')->position, -2519);
  // The bar only grows, glyph by glyph (5 columns each), and got to full.
  size_t lit_before = 0, full = 0;
  for (const std::string& b : bars) {
    ASSERT_EQ(b.find_first_not_of("12345 "), std::string::npos) << b;
    size_t lit = 0;
    for (char c : b) lit += c == ' ' ? 0 : size_t(c - '0');
    EXPECT_GE(lit, lit_before) << b;
    lit_before = lit;
    full = std::max(full, lit);
  }
  EXPECT_GE(full, 75u);
  EXPECT_GT(bars.size(), 10u);
}

// The keypad through the firmware's scan: a key held 1.5 s types once,
// contacts bouncing for up to 12 ms (10 flips) still type once each, and
// two keys of one row held together read as the first in scan order.
TEST(LatheOperator, KeysTypeOncePerPressWhateverTheBounce) {
  sim::KeypadTiming rough;
  rough.bounce_s = 0.012;
  rough.bounces = 10;
  Panel p({}, 0, rough);
  p.run_to(1.8);
  p.type("1");
  EXPECT_EQ(p.row0(), "Pitch mm A:TPI  ");
  p.keys->press('7', p.now() + 0.01, 1.5);
  p.run_to(p.now() + 1.8);
  EXPECT_EQ(p.row1(), "7_              ");
  p.type("#25");
  EXPECT_EQ(p.row1(), "7.25_           ");
  const double at = p.now() + 0.01;
  p.keys->press('4', at, 0.3);  // 4 and 6 share a row; 4's column is scanned first
  p.keys->press('6', at, 0.3);
  p.run_to(at + 0.5);
  EXPECT_EQ(p.row1(), "7.254_          ");
  EXPECT_GT(p.keys->applied(), 100u);  // the flips did reach the pins
}

TEST(LatheOperator, SettingsGoThroughTheEepromAndBack) {
  std::vector<uint8_t> stored;
  {
    Panel p;
    p.run_to(1.8);
    p.type("A");
    EXPECT_EQ(p.row0(), "Encoder lines   ");
    EXPECT_EQ(p.row1(), "40           1/8");
    p.type("D600D");
    EXPECT_EQ(p.row1(), "600          1/8");
    p.type("AD1D");
    EXPECT_EQ(p.row0(), "Quadrature 0/1  ");
    EXPECT_EQ(p.row1(), "1            2/8");
    p.type("AA");
    EXPECT_EQ(p.row0(), "Lead TPI 0=mm   ");
    EXPECT_EQ(p.row1(), "8.0          4/8");  // the board's 8 TPI leadscrew
    p.type("A");
    EXPECT_EQ(p.row0(), "Steps/rev       ");
    EXPECT_EQ(p.row1(), "800          5/8");  // the board's 200 x 4
    p.type("D0D");
    EXPECT_EQ(p.row0(), "Out of range    ");
    EXPECT_EQ(p.row1(), "1..10000        ");
    p.run_to(p.now() + 1.6);
    EXPECT_EQ(p.row1(), "0_              ");
    p.type("C3200D");
    EXPECT_EQ(p.row1(), "3200         5/8");
    p.type("C");
    EXPECT_EQ(p.row0(), "Settings saved  ");
    p.run_to(p.now() + 0.5);  // 34 bytes at 3.4 ms each: written by now
    stored = p.eeprom();
  }
  ASSERT_EQ(stored.size(), kSettingsBytes);
  EXPECT_EQ(le32(stored, 0), 600u);
  EXPECT_EQ(le32(stored, 4), 1u);
  EXPECT_EQ(le32(stored, 12), 80u);
  EXPECT_EQ(le32(stored, 16), 3200u);
  {  // A power cycle with that EEPROM: no message, the stored values.
    Panel p(stored);
    p.run_to(0.3);
    EXPECT_EQ(p.row0(), "1Thr 2Feed 3Move");
    p.type("A");
    EXPECT_EQ(p.row1(), "600          1/8");
    p.type("AAAA");
    EXPECT_EQ(p.row1(), "3200         5/8");
  }
  for (size_t at : {size_t(0), size_t(17), size_t(33)}) {  // a value byte, another, the check
    std::vector<uint8_t> torn = stored;
    torn[at] ^= 0x04;
    Panel p(torn);
    p.run_to(0.3);
    EXPECT_EQ(p.row0(), "Defaults loaded ") << at;
    p.run_to(1.8);
    p.type("A");
    EXPECT_EQ(p.row1(), "40           1/8") << at;  // the board's machine
  }
}

}  // namespace
