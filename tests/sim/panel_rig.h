// A lathe image with the operator panel (m16-panel, m32-servo-panel) for the
// panel tests: its EEPROM preloaded (or erased), the HD44780 model read back,
// the keypad model pressing keys through the firmware's own scan, and the
// spindle model; time in simulated seconds.
#pragma once
#include <simavr/sim_avr.h>

#include <memory>
#include <string>
#include <vector>

#include "keypad_model.h"
#include "lcd_model.h"
#include "sim_fixture.h"
#include "spindle_encoder.h"

namespace simtest {

struct PanelRig {
  std::unique_ptr<sim::Machine> m;
  std::unique_ptr<sim::LcdModel> lcd;
  std::unique_ptr<sim::KeypadModel> keys;
  std::unique_ptr<sim::SpindleEncoder> spindle;

  PanelRig(const char* name, const std::vector<uint8_t>& eeprom, const sim::SpindleParams& sp,
           const sim::KeypadTiming& keypad = sim::KeypadTiming())
      : m(new sim::Machine(image(name))) {
    if (!eeprom.empty()) m->set_eeprom(eeprom);
    lcd.reset(new sim::LcdModel(*m));
    keys.reset(new sim::KeypadModel(*m, keypad));
    spindle.reset(new sim::SpindleEncoder(*m, sp));
  }
  double now() const { return double(m->cycles()) / m->f_cpu(); }
  void run_to(double t_s) {
    const uint64_t at = uint64_t(t_s * m->f_cpu());
    if (at > m->cycles()) m->run([] { return false; }, at - m->cycles());
  }
  // Types `k` from 10 ms on, a key every 0.25 s, and runs past the last.
  void type(const std::string& k) { run_to(keys->type(k, now() + 0.01)); }
  std::string row0() const { return lcd->row(0); }
  std::string row1() const { return lcd->row(1); }
  // The first `bytes` of the EEPROM (the settings block).
  std::vector<uint8_t> eeprom(uint32_t bytes) { return m->eeprom(bytes); }
};

}  // namespace simtest
