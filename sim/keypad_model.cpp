// The scripted 4x4 keypad (contract in keypad_model.h).
#include "keypad_model.h"

#include <simavr/avr_ioport.h>
#include <simavr/sim_avr.h>
#include <simavr/sim_cycle_timers.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace sim {
namespace {
const char kLayout[] = "123A456B789C*0#D";
}

KeypadModel::KeypadModel(Machine& m, const KeypadTiming& t) : m_(m), timing_(t) {
  avr_irq_t* all = avr_io_getirq(m.avr(), AVR_IOCTL_IOPORT_GETIRQ('B'), IOPORT_IRQ_PIN_ALL);
  if (!all) throw std::runtime_error("KeypadModel: no port B on this MCU");
  avr_irq_register_notify(all, &KeypadModel::on_port, this);
  m.after_reset([this] { arm(); });
}

KeypadModel::~KeypadModel() {
  avr_cycle_timer_cancel(m_.avr(), &KeypadModel::on_timer, this);
  avr_irq_unregister_notify(avr_io_getirq(m_.avr(), AVR_IOCTL_IOPORT_GETIRQ('B'), IOPORT_IRQ_PIN_ALL),
                            &KeypadModel::on_port, this);
}

void KeypadModel::transition(uint8_t key, uint64_t at, bool closed) {
  const uint64_t span = uint64_t(timing_.bounce_s * m_.f_cpu());
  std::vector<uint64_t> flips;
  for (int i = 0; i < timing_.bounces && span > 0; ++i) flips.push_back(at + rng_() % span);
  std::sort(flips.begin(), flips.end());
  // Every flip alternates the contact; an even count of bounces after the
  // first edge ends where the transition goes.
  bool state = closed;
  events_.push_back({at, key, state});
  for (size_t i = 0; i + (flips.size() % 2) < flips.size(); ++i) {
    state = !state;
    events_.push_back({flips[i], key, state});
  }
  events_.push_back({at + span, key, closed});
}

void KeypadModel::press(char key, double at_s, double hold_s) {
  const char* p = std::strchr(kLayout, key);
  if (!key || !p) throw std::runtime_error(std::string("KeypadModel: no key '") + key + "'");
  if (hold_s < 0) hold_s = timing_.hold_s;
  const uint8_t k = uint8_t(p - kLayout);
  const uint64_t down = uint64_t(at_s * m_.f_cpu()), up = uint64_t((at_s + hold_s) * m_.f_cpu());
  if (down < m_.cycles()) throw std::runtime_error("KeypadModel: a press in the past");
  transition(k, down, true);
  transition(k, up, false);
  std::stable_sort(events_.begin() + long(next_), events_.end(),
                   [](const Event& a, const Event& b) { return a.cycle < b.cycle; });
  arm();
}

double KeypadModel::type(const std::string& keys, double at_s, double every_s) {
  for (char k : keys) {
    press(k, at_s, every_s / 2);
    at_s += every_s;
  }
  return at_s;
}

void KeypadModel::arm() {
  avr_t* avr = m_.avr();
  avr_cycle_timer_cancel(avr, &KeypadModel::on_timer, this);
  if (next_ >= events_.size()) return;
  const uint64_t now = avr->cycle, at = events_[next_].cycle;
  avr_cycle_timer_register(avr, at > now ? at - now : 1, &KeypadModel::on_timer, this);
}

uint64_t KeypadModel::on_timer(avr_t* avr, uint64_t when, void* param) {
  auto* self = static_cast<KeypadModel*>(param);
  while (self->next_ < self->events_.size() && self->events_[self->next_].cycle <= when) {
    const Event& e = self->events_[self->next_++];
    self->closed_[e.key] = e.closed;
  }
  self->update_rows();
  if (self->next_ >= self->events_.size()) return 0;
  const uint64_t at = self->events_[self->next_].cycle;
  (void)avr;
  return at > when ? at : when + 1;
}

void KeypadModel::on_port(avr_irq_t*, uint32_t, void* param) { static_cast<KeypadModel*>(param)->update_rows(); }

void KeypadModel::update_rows() {
  avr_ioport_state_t st;
  if (avr_ioctl(m_.avr(), AVR_IOCTL_IOPORT_GETSTATE('B'), &st) != 0) return;
  const uint8_t driven_low = uint8_t(st.ddr & ~st.port);
  for (uint8_t r = 0; r < 4; ++r) {
    bool low = false;
    for (uint8_t c = 0; c < 4; ++c)
      if (closed_[r * 4 + c] && (driven_low & (0x80 >> c))) low = true;
    const uint8_t bit = uint8_t(3 - r);
    // A row no key pulls down reads what the firmware's pull-up makes it.
    if (low) m_.set_input('B', bit, false);
    else m_.set_input('B', bit, (st.port >> bit) & 1);
  }
}

}  // namespace sim
