#include "endstops.h"

#include <sim_avr.h>
#include <sim_cycle_timers.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

namespace sim {

Endstops::Endstops(Machine& m, const EndstopParams& p) : m_(m), p_(p) {
  const am::BoardDescriptor& b = m.board();
  switches_.reserve(b.axis_count);  // the timers and listeners keep pointers
  for (uint8_t i = 0; i < b.axis_count; ++i) {
    const am::AxisDescriptor& d = b.axes[i];
    if (d.endstop == am::kNoPin) continue;
    Switch s;
    s.owner = this;
    s.name = d.name;
    s.port = am::pin_port(d.endstop);
    s.bit = am::pin_bit(d.endstop);
    s.at_max = d.option & am::kEndstopAtMax;
    s.closed_high = bool(d.option & am::kEndstopClosedHigh) != p.normally_closed;
    s.axis = m.axis(d.name);
    s.level = !s.closed_high;  // open: the machine holds it so from construction
    switches_.push_back(s);
  }
  for (Switch& s : switches_) {
    follow(s, m.cycles());
    const am::AxisDescriptor* d = nullptr;
    for (uint8_t i = 0; i < b.axis_count; ++i)
      if (b.axes[i].name == s.name) d = &b.axes[i];
    Switch* sp = &s;
    m.listen_pin(am::pin_port(d->pins[0]), am::pin_bit(d->pins[0]),
                 [this, sp](bool level, uint64_t cycle) {
                   if (level) follow(*sp, cycle);
                 });
  }
  // A reset drops simavr's timers: a burst under way ends on the contact.
  m.after_reset([this] {
    for (Switch& s : switches_) {
      s.pending.clear();
      drive(s, s.contact == s.closed_high, m_.cycles());
    }
  });
}

bool Endstops::has(char name) const {
  for (const Switch& s : switches_)
    if (s.name == name) return true;
  return false;
}

Endstops::Switch& Endstops::find(char name) {
  for (Switch& s : switches_)
    if (s.name == name) return s;
  throw std::runtime_error(std::string("no endstop on axis ") + name);
}

const Endstops::Switch& Endstops::find(char name) const { return const_cast<Endstops*>(this)->find(name); }

void Endstops::set_position(char name, int64_t steps) {
  Switch& s = find(name);
  s.at = steps;
  follow(s, m_.cycles());
}

bool Endstops::closed(char name) const { return find(name).contact; }
const std::vector<PinEdge>& Endstops::edges(char name) const { return find(name).edges; }
const std::vector<uint64_t>& Endstops::contact_changes(char name) const { return find(name).changes; }

void Endstops::drive(Switch& s, bool level, uint64_t cycle) {
  if (level == s.level) return;
  s.level = level;
  s.edges.push_back({cycle, level});
  m_.hold_input(s.port, s.bit, level);
}

// The contact as the axis's position says; a change starts a burst.
void Endstops::follow(Switch& s, uint64_t cycle) {
  const int64_t pos = s.axis ? s.axis->position : 0;
  const bool contact = s.at_max ? pos >= s.at : pos <= s.at;
  if (contact == s.contact && !s.changes.empty()) return;
  const bool first = s.changes.empty();
  s.contact = contact;
  s.changes.push_back(cycle);
  const bool level = contact == s.closed_high;
  s.pending.clear();
  avr_cycle_timer_cancel(m_.avr(), &Endstops::on_toggle, &s);
  drive(s, level, cycle);
  if (first || p_.bounce_us <= 0 || p_.bounce_toggles == 0) return;
  const uint64_t span = uint64_t(p_.bounce_us * m_.f_cpu() / 1e6);
  if (span == 0) return;
  std::uniform_int_distribution<uint64_t> at(1, span);
  for (unsigned i = 1; i < p_.bounce_toggles; ++i) s.pending.push_back(cycle + at(rng_));
  std::sort(s.pending.begin(), s.pending.end());
  s.pending.push_back(cycle + span);
  avr_cycle_timer_register(m_.avr(), s.pending.front() - m_.cycles(), &Endstops::on_toggle, &s);
}

uint64_t Endstops::on_toggle(avr_t*, uint64_t when, void* param) {
  auto* s = static_cast<Switch*>(param);
  // Every toggle due by now; the last leaves the pin on the contact.
  while (!s->pending.empty() && s->pending.front() <= when) {
    s->pending.erase(s->pending.begin());
    s->owner->drive(*s, s->pending.empty() ? s->contact == s->closed_high : !s->level, when);
  }
  return s->pending.empty() ? 0 : s->pending.front();
}

bool parse_endstop_position(const std::string& text, char& axis, int64_t& steps) {
  if (text.size() < 3 || text[1] != '=') return false;
  axis = char(std::toupper(static_cast<unsigned char>(text[0])));
  char* end = nullptr;
  steps = std::strtoll(text.c_str() + 2, &end, 10);
  return end && *end == '\0';
}

}  // namespace sim
