#include "thermal_plant.h"

#include <avr_adc.h>
#include <sim_avr.h>
#include <sim_cycle_timers.h>
#include <sim_io.h>
#include <sim_irq.h>

#include <cmath>
#include <stdexcept>

namespace sim {

bool parse_thermal_fault(const std::string& name, ThermalFault& fault) {
  for (ThermalFault f : {ThermalFault::sensor_open, ThermalFault::sensor_shorted, ThermalFault::heater_disconnected,
                         ThermalFault::heater_stuck_on}) {
    if (name == thermal_fault_name(f)) {
      fault = f;
      return true;
    }
  }
  return false;
}

const char* thermal_fault_name(ThermalFault f) {
  switch (f) {
    case ThermalFault::sensor_open: return "open";
    case ThermalFault::sensor_shorted: return "shorted";
    case ThermalFault::heater_disconnected: return "disconnected";
    case ThermalFault::heater_stuck_on: return "stuck_on";
    default: return "none";
  }
}

ThermalPlant::ThermalPlant(Machine& m, const ThermalParams& p)
    : m_(m), p_(p), block_(p.initial_c), sensor_(p.initial_c), peak_(p.initial_c),
      target_(find_symbol(m.elf_path(), "_ZN6heater12_GLOBAL__N_17target_E")) {
  const am::BoardDescriptor& b = m.board();
  if (b.heater_pin == am::kNoPin || b.heater_adc > 7)
    throw std::runtime_error(std::string("board ") + b.board + " has no heater");
  adc_channel_ = b.heater_adc;
  step_cycles_ = m.f_cpu() / 1000;
  pipe_.assign(size_t(p.delay_s * 1000 + 0.5), 0.0);
  edges_ = &m.watch_pin(am::pin_port(b.heater_pin), am::pin_bit(b.heater_pin));
  last_cycle_ = m.cycles();
  m.set_adc_millivolts(adc_channel_, input_mv());
  avr_irq_register_notify(avr_io_getirq(m.avr(), AVR_IOCTL_ADC_GETIRQ, ADC_IRQ_OUT_TRIGGER),
                          &ThermalPlant::on_adc_trigger, this);
  avr_cycle_timer_register(m.avr(), step_cycles_, &ThermalPlant::on_step, this);
  // The plant's time goes on through a reset (a --pty client's open).
  m.after_reset([this, &m] {
    m.set_adc_millivolts(adc_channel_, input_mv());
    avr_cycle_timer_register(m.avr(), step_cycles_, &ThermalPlant::on_step, this);
  });
}

uint64_t ThermalPlant::on_step(avr_t*, uint64_t when, void* param) {
  auto* self = static_cast<ThermalPlant*>(param);
  self->step(when);
  return when + self->step_cycles_;
}

// A conversion starts: the input it will read, with fresh noise.
void ThermalPlant::on_adc_trigger(avr_irq_t*, uint32_t, void* param) {
  auto* self = static_cast<ThermalPlant*>(param);
  self->m_.set_adc_millivolts(self->adc_channel_, self->input_mv());
}

namespace {

double divider_mv(const ThermalParams& p, double c) {
  const double r = p.r0_ohm * std::exp(p.beta * (1 / (c + 273.15) - 1 / (p.t0_c + 273.15)));
  return p.vref_mv * r / (r + p.pullup_ohm);
}

}  // namespace

uint32_t thermistor_input_mv(const ThermalParams& p, double c) {
  return uint32_t(std::lround(divider_mv(p, c) * 1024 / 1023));
}

uint32_t ThermalPlant::input_mv() {
  if (fault_ == ThermalFault::sensor_open) return uint32_t(std::lround(p_.vref_mv * 1024 / 1023));
  if (fault_ == ThermalFault::sensor_shorted) return 0;
  const double mv = divider_mv(p_, sensor_) + p_.noise_mv * noise_(rng_);
  return uint32_t(std::lround(std::max(0.0, mv * 1024 / 1023)));
}

void ThermalPlant::step(uint64_t now) {
  for (auto e = events_.begin(); e != events_.end();) {
    if (e->cycle > now) {
      ++e;
      continue;
    }
    if (e->fan < 0) fault_ = e->fault;
    else fan_ = e->fan;
    e = events_.erase(e);
  }
  // The pin's high time since the last step, from its edges.
  double high = 0;
  for (; next_edge_ < edges_->size() && (*edges_)[next_edge_].cycle <= now; ++next_edge_) {
    const PinEdge& e = (*edges_)[next_edge_];
    if (level_) high += double(e.cycle - last_cycle_);
    last_cycle_ = e.cycle;
    level_ = e.level;
  }
  if (level_) high += double(now - last_cycle_);
  last_cycle_ = now;
  const double duty = high / double(step_cycles_);
  high_cycles_ += high;

  double power = fault_ == ThermalFault::heater_disconnected ? 0
                 : fault_ == ThermalFault::heater_stuck_on   ? 1
                                                             : duty;
  if (!pipe_.empty()) {
    std::swap(power, pipe_[pipe_at_]);
    pipe_at_ = (pipe_at_ + 1) % pipe_.size();
  }
  const double dt = 1e-3;
  const double loss = (p_.loss_w_per_k + fan_ * p_.fan_w_per_k) * (block_ - p_.ambient_c);
  block_ += dt * (p_.heater_w * power - loss) / p_.capacity_j_per_k;
  sensor_ += dt * (block_ - sensor_) / p_.sensor_tau_s;
  if (sensor_ > peak_) peak_ = sensor_;
  if (++steps_in_log_ == 100) {
    double target = std::nan("");
    if (target_.found) {
      const uint16_t at = uint16_t(target_.value & 0xFFFF);  // the data-space offset of 0x800000 + address
      target = int16_t(m_.avr()->data[at] | m_.avr()->data[at + 1] << 8) / 100.0;
    }
    log_.push_back({double(now) / m_.f_cpu(), block_, sensor_, high_cycles_ / double(100 * step_cycles_), target});
    steps_in_log_ = 0;
    high_cycles_ = 0;
  }
}

}  // namespace sim
