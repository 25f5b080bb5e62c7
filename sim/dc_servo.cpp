#include "dc_servo.h"

#include <sim_avr.h>
#include <sim_cycle_timers.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sim {

DcServo::DcServo(Machine& m, const ServoParams& p) : m_(m), p_(p) {
  const am::BoardDescriptor& b = m.board();
  pin_en_ = b.servo_pins[0];
  pin_in1_ = b.servo_pins[1];
  pin_in2_ = b.servo_pins[2];
  pin_enc_ = b.servo_pins[3];
  if (pin_en_ == am::kNoPin || pin_in1_ == am::kNoPin || pin_in2_ == am::kNoPin || pin_enc_ == am::kNoPin)
    throw std::runtime_error(std::string("board ") + b.board + " has no DC-servo leadscrew");
  if (p.tick_cycles == 0 || p.log_every == 0 || !(p.pole > 0) || p.coast_pole < 0) throw std::runtime_error("servo: bad parameters");
  x_ = p.start_position + 0.25;
  at_ = m.cycles();
  enc_level_ = std::floor(2 * x_) != 2 * std::floor(x_);
  m.hold_input(am::pin_port(pin_enc_), am::pin_bit(pin_enc_), enc_level_);
  const auto listen = [this](uint8_t pin, bool* level) {
    m_.listen_pin(am::pin_port(pin), am::pin_bit(pin), [this, level](bool v, uint64_t cycle) {
      advance(cycle);
      *level = v;
    });
  };
  listen(pin_en_, &en_);
  listen(pin_in1_, &in1_);
  listen(pin_in2_, &in2_);
  avr_cycle_timer_register(m.avr(), p_.tick_cycles, &DcServo::on_tick, this);
  m.after_reset([this] { avr_cycle_timer_register(m_.avr(), p_.tick_cycles, &DcServo::on_tick, this); });
}

double DcServo::drive() const {
  if (!en_ || in1_ == in2_) return 0;
  return in1_ ? 1 : -1;
}

void DcServo::advance(uint64_t cycle) {
  if (cycle <= at_) return;
  const double dt = double(cycle - at_) / m_.f_cpu();
  if (en_) (in1_ != in2_ ? driven_cycles_ : brake_cycles_) += cycle - at_;
  const double target = p_.gain * p_.full_scale * drive();  // pulses/s
  const double pole = en_ || !(p_.coast_pole > 0) ? p_.pole : p_.coast_pole;
  const double decay = std::exp(-pole * dt);
  x_ += target * dt + (w_ - target) * (1 - decay) / pole;
  w_ = target + (w_ - target) * decay;
  at_ = cycle;
  const bool level = std::floor(2 * x_) != 2 * std::floor(x_);  // frac(x) >= 0.5
  if (level != enc_level_) {
    enc_level_ = level;
    if (!level) falls_.push_back(cycle);
    m_.hold_input(am::pin_port(pin_enc_), am::pin_bit(pin_enc_), level);
  }
}

uint64_t DcServo::on_tick(avr_t*, uint64_t when, void* param) {
  auto* self = static_cast<DcServo*>(param);
  self->advance(when);
  if (++self->ticks_ % self->p_.log_every == 0) self->log_.push_back({when, self->x_, self->w_});
  return when + self->p_.tick_cycles;
}

double DcServo::position() {
  advance(m_.cycles());
  return x_;
}

double DcServo::speed() {
  advance(m_.cycles());
  return w_;
}

double DcServo::position_at(uint64_t cycle) const {
  if (log_.empty()) return x_;
  auto it = std::lower_bound(log_.begin(), log_.end(), cycle,
                             [](const ServoSample& s, uint64_t c) { return s.cycle < c; });
  if (it == log_.begin()) return it->position;
  if (it == log_.end()) return log_.back().position;
  const ServoSample& b = *it;
  const ServoSample& a = *(it - 1);
  const double f = double(cycle - a.cycle) / double(b.cycle - a.cycle);
  return a.position + f * (b.position - a.position);
}

}  // namespace sim
