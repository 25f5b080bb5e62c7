#include "spindle_encoder.h"

#include <sim_avr.h>
#include <sim_cycle_timers.h>
#include <sim_io.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sim {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kEps = 1e-13;  // seconds: a root at the present is not the next crossing

// Earliest tau in (kEps, len] with a0 + w tau + alpha tau^2 / 2 = target, or
// infinity. The roots in the cancellation-free form.
double first_root(double a0, double w, double alpha, double target, double len) {
  const double d = target - a0;
  double r1 = kInf, r2 = kInf;
  if (alpha == 0) {
    if (w != 0) r1 = d / w;
  } else {
    const double disc = w * w + 2 * alpha * d;
    if (disc < 0) return kInf;
    const double q = -0.5 * (w + (w >= 0 ? 1 : -1) * std::sqrt(disc));
    if (q != 0) {
      r1 = q / (0.5 * alpha);
      r2 = -d / q;
    } else {
      r1 = std::sqrt(2 * d / alpha);
    }
  }
  double best = kInf;
  for (double r : {r1, r2})
    if (r > kEps && r <= len && r < best) best = r;
  return best;
}

}  // namespace

SpindleEncoder::SpindleEncoder(Machine& m, const SpindleParams& p) : m_(m), p_(p), rng_(p.seed) {
  const am::BoardDescriptor& b = m.board();
  pin_a_ = b.spindle_pins[0];
  pin_b_ = b.spindle_pins[1];
  pin_index_ = b.spindle_pins[2];
  if (pin_a_ == am::kNoPin || pin_index_ == am::kNoPin)
    throw std::runtime_error(std::string("board ") + b.board + " has no spindle encoder");
  if (p.quadrature && pin_b_ == am::kNoPin)
    throw std::runtime_error(std::string("board ") + b.board + " has no quadrature B channel");
  if (p.lines == 0 || p.profile.empty()) throw std::runtime_error("spindle: lines and an rpm profile needed");
  for (size_t i = 1; i < p.profile.size(); ++i)
    if (!(p.profile[i].t_s > p.profile[i - 1].t_s)) throw std::runtime_error("spindle: profile times must rise");
  phases_per_turn_ = uint32_t(p.lines) * (p.quadrature ? 4 : 2);
  now_s_ = double(m.cycles()) / m.f_cpu();
  last_cycle_ = m.cycles();
  set_pins(m.cycles(), false, false);
  const uint64_t first = schedule();
  if (first) avr_cycle_timer_register(m.avr(), first - m.cycles(), &SpindleEncoder::on_transition, this);
  m.after_reset([this] {
    const uint64_t next = schedule();
    if (next) avr_cycle_timer_register(m_.avr(), next > m_.cycles() ? next - m_.cycles() : 1,
                                       &SpindleEncoder::on_transition, this);
  });
}

double SpindleEncoder::rpm_at(double t) const {
  const std::vector<RpmPoint>& pr = p_.profile;
  if (t <= pr.front().t_s) return pr.front().rpm;
  for (size_t i = 1; i < pr.size(); ++i) {
    if (t < pr[i].t_s) {
      const double f = (t - pr[i - 1].t_s) / (pr[i].t_s - pr[i - 1].t_s);
      return pr[i - 1].rpm + f * (pr[i].rpm - pr[i - 1].rpm);
    }
  }
  return pr.back().rpm;
}

double SpindleEncoder::omega(double t) const { return rpm_at(t) / 60 * phases_per_turn_; }

bool SpindleEncoder::next_crossing(double& t_s, int& direction) const {
  const std::vector<RpmPoint>& pr = p_.profile;
  double t = now_s_, a = angle_;
  const double up = double(phase_ + 1), down = double(phase_);
  for (;;) {
    // The segment [t, end) with omega linear in it.
    double end = kInf;
    for (const RpmPoint& pt : pr) {
      if (pt.t_s > t) {
        end = pt.t_s;
        break;
      }
    }
    const double w = omega(t);
    const double alpha = end == kInf || t < pr.front().t_s ? 0 : (omega(end) - w) / (end - t);
    const double len = end - t;
    const double tu = first_root(a, w, alpha, up, len), td = first_root(a, w, alpha, down, len);
    if (tu < kInf || td < kInf) {
      direction = tu <= td ? 1 : -1;
      t_s = t + (tu <= td ? tu : td);
      return true;
    }
    if (end == kInf) return false;
    a += w * len + 0.5 * alpha * len * len;
    t = end;
  }
}

uint64_t SpindleEncoder::schedule() {
  if (!next_crossing(next_s_, next_direction_)) return 0;
  double cycle = next_s_ * m_.f_cpu();
  if (p_.jitter_us > 0) {
    std::uniform_real_distribution<double> j(-p_.jitter_us, p_.jitter_us);
    cycle += j(rng_) * 1e-6 * m_.f_cpu();
  }
  uint64_t c = cycle <= 0 ? 0 : uint64_t(std::llround(cycle));
  const uint64_t earliest = std::max(last_cycle_, m_.cycles()) + 1;
  return c < earliest ? earliest : c;
}

void SpindleEncoder::set_pins(uint64_t cycle, bool logged, bool count) {
  const int64_t p = ((phase_ % phases_per_turn_) + phases_per_turn_) % phases_per_turn_;
  const bool index = p_.quadrature ? p == 0 : (p == 0 || p == int64_t(phases_per_turn_) - 1);
  bool a, b = false;
  if (p_.quadrature) {
    static const bool kA[4] = {false, true, true, false}, kB[4] = {false, false, true, true};
    a = kA[p % 4];
    b = kB[p % 4];
  } else {
    a = (p % 2) == 1;  // low in the first half line, high in the second
  }
  drive(pin_index_, index);
  if (p_.quadrature) drive(pin_b_, b);
  drive(pin_a_, a);
  if (logged) log_.push_back({cycle, phase_, count, index});
}

void SpindleEncoder::drive(uint8_t pin, bool level) {
  // The encoder drives its pins: held as simavr's "external" levels of the
  // port (Machine::hold_input, one registry per port for every model on
  // it), so the firmware's pull-ups (a PORT write) do not override them.
  m_.hold_input(am::pin_port(pin), am::pin_bit(pin), level);
}

uint64_t SpindleEncoder::on_transition(avr_t*, uint64_t when, void* param) {
  auto* self = static_cast<SpindleEncoder*>(param);
  const int d = self->next_direction_;
  self->phase_ += d;
  self->angle_ = double(d > 0 ? self->phase_ : self->phase_ + 1);
  self->now_s_ = self->next_s_;
  self->last_cycle_ = when;
  // A count for the firmware: every transition in quadrature; single
  // channel: A falling, into an even phase from either side.
  const bool count = self->p_.quadrature || (self->phase_ % 2 == 0);
  if (count) self->counts_ += self->p_.quadrature ? d : 1;
  self->set_pins(when, true, count);
  return self->schedule();
}

}  // namespace sim
