#include "limits.h"

namespace limits {

Settings settings = board::kHomingSettings;
bool soft_limits = true, homing_enabled = true;

namespace {

bool alarmed;
bool reported = true;  // news() has said so
bool seeking;          // a homing move runs
bool seen;             // and has found its switch
uint8_t homed_switches;

}  // namespace

bool alarm() { return alarmed; }

void unlock() { alarmed = false; }

void fail() {
  alarmed = true;
  homed_switches = 0;
}

void tripped() {
  if (seeking) {
    seen = true;
    return;
  }
  fail();
  reported = false;
}

bool news() {
  if (reported) return false;
  reported = true;
  return true;
}

void homing(bool on) {
  seeking = on;
  seen = false;
}

bool found() {
  const bool was = seen;
  seen = false;
  return was;
}

void set_homed(uint8_t k) { homed_switches = uint8_t(homed_switches | (1u << k)); }

bool outside(const planner::Move& move) {
  if (board::kSettings && !soft_limits) return false;
  for (uint8_t k = 0; k != kSwitches; ++k) {
    if (!(homed_switches & (1u << k))) continue;
    const HomingAxis& a = settings.axis[k];
    const uint8_t axis = board::Endstops::axis_at(k);
    const int32_t position = planner::position(axis) + move.steps[axis];
    // The distance from home toward the far end, modulo 2^32: a position on
    // the switch's side of home wraps to far above any travel.
    const uint32_t away = (board::Endstops::max_end & (1u << axis)) ? uint32_t(a.home) - uint32_t(position)
                                                                    : uint32_t(position) - uint32_t(a.home);
    if (away > a.travel) return true;
  }
  return false;
}

}  // namespace limits
