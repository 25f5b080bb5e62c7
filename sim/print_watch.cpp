// The print's measurements (print_watch.h).
#include "print_watch.h"

#include <avr_ioport.h>
#include <sim_avr.h>

#include <cmath>
#include <stdexcept>

namespace sim {

PrintWatch::PrintWatch(Machine& m, const ThermalPlant* plant, const Endstops* switches)
    : m_(m), plant_(plant), switches_(switches) {
  const am::BoardDescriptor& b = m.board();
  const AxisTrace* e = m.axis('E');
  uint8_t step_pin = am::kNoPin;
  for (uint8_t i = 0; i < b.axis_count; ++i)
    if (b.axes[i].name == 'E' && b.axes[i].kind == am::AxisKind::step_dir) step_pin = b.axes[i].pins[0];
  if (!e || step_pin == am::kNoPin) throw std::runtime_error("PrintWatch: the board has no step/dir axis E");
  most_e_ = e->steps();
  m.listen_pin(am::pin_port(step_pin), am::pin_bit(step_pin), [this, e](bool, uint64_t cycle) {
    if (first_extrusion_ || e->steps() <= most_e_) {
      if (e->steps() > most_e_) most_e_ = e->steps();
      return;
    }
    first_extrusion_ = cycle ? cycle : 1;
    if (plant_) {
      sensor_c_ = plant_->sensor_c();
      block_c_ = plant_->block_c();
    }
  });
}

std::string PrintWatch::enabled_now() const {
  const am::BoardDescriptor& b = m_.board();
  std::string out;
  for (uint8_t i = 0; i < b.axis_count; ++i) {
    const am::AxisDescriptor& a = b.axes[i];
    if (a.kind != am::AxisKind::step_dir || a.pins[2] == am::kNoPin) continue;
    avr_ioport_state_t st;
    if (avr_ioctl(m_.avr(), AVR_IOCTL_IOPORT_GETSTATE(am::pin_port(a.pins[2])), &st) != 0) continue;
    const unsigned bit = 1u << am::pin_bit(a.pins[2]);
    const bool output = st.ddr & bit, high = st.port & bit, active_low = a.option & 1;
    if (output && high != active_low) out += a.name;
  }
  return out;
}

unsigned PrintWatch::switch_closes(char name) const {
  if (!switches_ || !switches_->has(name)) return 0;
  const size_t n = switches_->contact_changes(name).size();
  if (n == 0) return 0;
  // The changes alternate; the first is the contact at the start.
  const bool first_closed = switches_->closed(name) == ((n - 1) % 2 == 0);
  return unsigned(first_closed ? (n + 1) / 2 : n / 2);
}

bool PrintWatch::heater_pin_now() const {
  if (!plant_) return false;
  const std::vector<PinEdge>& edges = plant_->heater_pin();
  return !edges.empty() && edges.back().level;
}

double PrintWatch::heater_duty_last() const {
  return plant_ && !plant_->log().empty() ? plant_->log().back().duty : -1;
}

double PrintWatch::target_c_last() const {
  if (!plant_ || plant_->log().empty() || std::isnan(plant_->log().back().target_c)) return -1;
  return plant_->log().back().target_c;
}

}  // namespace sim
