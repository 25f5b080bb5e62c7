// The operator panel on the real m16-panel image: the HD44780 model reads
// the screen back from the simulated controller, the keypad model presses
// keys (with contact bounce) through the firmware's own scan. Start-up,
// every screen of the settings menu, the EEPROM round trip, a corrupted
// settings block.
#include <simavr/avr_eeprom.h>
#include <simavr/sim_avr.h>

#include <string>
#include <vector>

#include "keypad_model.h"
#include "lcd_model.h"
#include "sim_fixture.h"

namespace {

constexpr uint32_t kSettingsBytes = 34;  // 8 fields x 4 + the check

struct Panel {
  std::unique_ptr<sim::Machine> m;
  std::unique_ptr<sim::LcdModel> lcd;
  std::unique_ptr<sim::KeypadModel> keys;
  explicit Panel(const std::vector<uint8_t>& eeprom = {}) : m(new sim::Machine(simtest::image("m16-panel"))) {
    if (!eeprom.empty()) {
      std::vector<uint8_t> bytes = eeprom;
      avr_eeprom_desc_t d{bytes.data(), 0, uint32_t(bytes.size())};
      avr_ioctl(m->avr(), AVR_IOCTL_EEPROM_SET, &d);
    }
    lcd.reset(new sim::LcdModel(*m));
    keys.reset(new sim::KeypadModel(*m));
  }
  double now() const { return double(m->cycles()) / m->f_cpu(); }
  void run_to(double t_s) { m->run([] { return false; }, uint64_t(t_s * m->f_cpu()) - m->cycles()); }
  // Types `k` now and runs until 0.25 s per key later.
  void type(const std::string& k) { run_to(keys->type(k, now() + 0.01)); }
  std::vector<uint8_t> eeprom() {
    avr_eeprom_desc_t d{nullptr, 0, kSettingsBytes};
    avr_ioctl(m->avr(), AVR_IOCTL_EEPROM_GET, &d);
    return d.ee ? std::vector<uint8_t>(d.ee, d.ee + kSettingsBytes) : std::vector<uint8_t>();
  }
};

TEST(LatheOperator, StartsWithTheMenuAndTheBarGlyphs) {
  Panel p;
  p.run_to(0.3);
  EXPECT_TRUE(p.lcd->four_bit());
  EXPECT_TRUE(p.lcd->display_on());
  // Erased EEPROM: the defaults, with a message, then the menu.
  EXPECT_EQ(p.lcd->row(0), "Settings reset  ");
  EXPECT_EQ(p.lcd->row(1), "to defaults     ");
  p.run_to(2.0);
  EXPECT_EQ(p.lcd->row(0), "1Cut 2Move 3Set ");
  EXPECT_EQ(p.lcd->row(1), "   0rpm Z   0.00");
  for (int k = 1; k <= 5; ++k) {
    const uint8_t bits = uint8_t(0x1F & ~(0x1F >> k));  // k columns lit from the left
    for (uint8_t row : p.lcd->glyph(k)) EXPECT_EQ(int(row), int(bits)) << k;
  }
  EXPECT_EQ(p.lcd->busy_writes(), 0u);
}

}  // namespace
