// Homing on the endstops (homing.h): one phase at a time, each a direct move
// from rest to rest, the next decided when the path is at rest again.
#include "homing.h"

#include <avr/pgmspace.h>

#include "../apps/cnc/reply.h"
#include "../board.h"
#include "../engine/limits.h"
#include "../engine/path.h"
#include "../engine/planner.h"
#include "../engine/step_engine.h"

namespace homing {
namespace {

using Endstops = board::Endstops;

const char kNotFound[] PROGMEM = "homing: endstop not found";

// The move the axis has just made, which the next step checks.
// An axis's top rate alone (planner::clamp()'s rule for a single axis).
constexpr uint32_t rate_cap(uint8_t axis) {
  return board::Axes::max_rate_at(axis) ? board::Axes::max_rate_at(axis) : board::kMaxStepRate;
}
enum class Phase : uint8_t { next_axis, seek, back_off, locate, pull_off };
Phase phase;
uint8_t running;  // the mask being homed; 0: not homing
uint8_t k;        // the switch being homed

// The board's own homing rates within its axes' (checked here, when the
// image compiles); settings (board::kSettings) are held within them when
// each move starts.
constexpr bool board_rates_fit(uint8_t k = 0) {
  return k == Endstops::count ||
         (board::kHomingSettings.axis[k].seek_rate <= rate_cap(Endstops::axis_at(k)) &&
          board::kHomingSettings.axis[k].locate_rate <= rate_cap(Endstops::axis_at(k)) && board_rates_fit(uint8_t(k + 1)));
}
static_assert(board::kSettings || board_rates_fit(), "a homing rate beyond its axis's top rate");
static_assert(board::kDefaultAccel <= board::kMaxAccel, "homing accelerates at the board's default");

// A move of switch k's axis, `steps` toward its switch (< 0: away).
void go(int32_t steps, uint16_t rate) {
  const uint8_t axis = Endstops::axis_at(k);
  planner::Move m{};
  m.steps[axis] = (Endstops::max_end & (1u << axis)) ? steps : -steps;
  planner::Ramp ramp{rate, board::kDefaultAccel};
  if (board::kSettings) planner::clamp(m, ramp);
  path::add_direct(m, ramp);
}

Result failed(const char* progmem_why) {
  reply::error(reply::code::homing_failed, progmem_why);
  limits::homing(false);
  limits::fail();
  running = 0;
  return Result::failed;
}

}  // namespace

Result run(uint8_t axes) {
  if (!running) {
    running = axes ? axes : Endstops::axes;
    phase = Phase::next_axis;
    k = 0xFF;
  }
  if (!path::at_rest()) return Result::busy;
  if (phase == Phase::next_axis) {
    do {
      if (++k == limits::kSwitches) {
        limits::homing(false);
        running = 0;
        return Result::homed;
      }
    } while (!(running & (1u << Endstops::axis_at(k))));
    limits::homing(true);
    // A switch closed already stops the seek at its first step: the
    // back-off then comes first.
    go(int32_t(limits::settings.axis[k].travel + limits::settings.axis[k].travel / 2),
       limits::settings.axis[k].seek_rate);
    phase = Phase::seek;
    return Result::busy;
  }
  const HomingAxis& s = limits::settings.axis[k];
  const bool closed = Endstops::closed_at(k, board::kPinPolarities && engine::inverted_switches() != 0);
  const bool found = limits::found();
  int32_t steps = -int32_t(s.back_off);  // away, unless a phase says otherwise
  uint16_t rate = s.seek_rate;
  const char* failure = nullptr;
  const Phase was = phase;
  phase = Phase(uint8_t(was) + 1);
  switch (was) {
    case Phase::seek:
      if (!found) failure = kNotFound;
      break;
    case Phase::back_off:
      if (closed) failure = PSTR("homing: endstop stays closed");
      steps = 2 * int32_t(s.back_off);
      rate = s.locate_rate;
      break;
    case Phase::locate:
      if (!found) failure = kNotFound;
      steps = -int32_t(s.pull_off);
      rate = s.locate_rate;
      break;
    default:  // the pull-off: done
      planner::set_position(Endstops::axis_at(k), s.home);
      limits::set_homed(k);
      phase = Phase::next_axis;
      return Result::busy;
  }
  if (failure) return failed(failure);
  go(steps, rate);
  return Result::busy;
}

void poll() {
  if (limits::news())
    reply::alarm(1, PSTR("hard limit: endstop hit, axes stopped, position lost"));
}

}  // namespace homing
