// The operator's 2 x 16 HD44780 display on the simulated board: simavr's
// HD44780 part (examples/parts/hd44780.c, made to follow the datasheet by
// sim/simavr/patches/19-hd44780-datasheet-behaviour.patch) wired to the
// seed's pins, and the screen read back as text.
//
// Wiring (firmware/boards/m16.h): PA0..PA3 = D4..D7 both ways (the part
// drives them while the firmware reads the busy flag), PA4 RS, PA5 RW,
// PA6 E, from the firmware to the part.
//
// row(r) is what the display shows on row r (0 or 1): 16 characters from
// the display RAM, with the character-RAM glyphs 0..7 replaced by '0'..'7'
// so a progress bar reads as digits. busy_writes() counts instructions or
// characters the firmware sent while the controller was still busy (a real
// one would have dropped them). glyph(k) is the 8 rows of CGRAM glyph k.
// changes() counts the instructions after which the screen's text differed
// from before; on_change (if set) is called after each of them, e.g. to log
// every screen a test goes through. The model must outlive the machine's
// run: simavr's part keeps calling into it from the pins.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "machine.h"

struct hd44780_t;

namespace sim {

class LcdModel {
 public:
  explicit LcdModel(Machine& m);
  ~LcdModel();
  LcdModel(const LcdModel&) = delete;
  LcdModel& operator=(const LcdModel&) = delete;

  std::string row(int r) const;
  std::string text() const { return row(0) + "\n" + row(1); }
  uint32_t busy_writes() const;
  std::array<uint8_t, 8> glyph(int k) const;
  bool four_bit() const;
  bool display_on() const;
  uint64_t changes() const { return changes_; }
  std::function<void()> on_change;

 private:
  static void on_busy(struct avr_irq_t* irq, uint32_t value, void* param);
  std::unique_ptr<hd44780_t> lcd_;
  std::string shown_;
  uint64_t changes_ = 0;
};

}  // namespace sim
