// The HD44780 part on port A (contract in lcd_model.h).
#include "lcd_model.h"

#include <simavr/avr_ioport.h>
#include <simavr/sim_avr.h>

#include <stdexcept>

extern "C" {
#include "hd44780.h"
}

namespace sim {

LcdModel::LcdModel(Machine& m) : lcd_(new hd44780_t) {
  avr_t* avr = m.avr();
  hd44780_init(avr, lcd_.get(), 16, 2);
  auto pin = [avr](uint8_t bit) {
    avr_irq_t* irq = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('A'), bit);
    if (!irq) throw std::runtime_error("LcdModel: no port A on this MCU");
    return irq;
  };
  for (uint8_t i = 0; i < 4; ++i) {
    avr_connect_irq(pin(i), lcd_->irq + IRQ_HD44780_D4 + i);
    avr_connect_irq(lcd_->irq + IRQ_HD44780_D4 + i, pin(i));
  }
  avr_connect_irq(pin(4), lcd_->irq + IRQ_HD44780_RS);
  avr_connect_irq(pin(5), lcd_->irq + IRQ_HD44780_RW);
  avr_connect_irq(pin(6), lcd_->irq + IRQ_HD44780_E);
  avr_irq_register_notify(lcd_->irq + IRQ_HD44780_BUSY, &LcdModel::on_busy, this);
  shown_ = text();
}

LcdModel::~LcdModel() = default;

// The part raises BUSY after it has carried out an instruction or a write.
void LcdModel::on_busy(avr_irq_t*, uint32_t value, void* param) {
  auto* self = static_cast<LcdModel*>(param);
  if (!value) return;
  std::string now = self->text();
  if (now == self->shown_) return;
  self->shown_ = std::move(now);
  ++self->changes_;
  if (self->on_change) self->on_change();
}

std::string LcdModel::row(int r) const {
  std::string s(reinterpret_cast<const char*>(lcd_->vram) + (r ? 0x40 : 0), 16);
  for (char& c : s)
    if (uint8_t(c) < 8) c = char('0' + c);
  return s;
}

uint32_t LcdModel::busy_writes() const { return lcd_->busy_writes; }

std::array<uint8_t, 8> LcdModel::glyph(int k) const {
  std::array<uint8_t, 8> g;
  for (int r = 0; r < 8; ++r) g[r] = lcd_->vram[80 + 8 * k + r];
  return g;
}

bool LcdModel::four_bit() const { return !hd44780_get_flag(lcd_.get(), HD44780_FLAG_D_L); }
bool LcdModel::display_on() const { return hd44780_get_flag(lcd_.get(), HD44780_FLAG_D); }

}  // namespace sim
