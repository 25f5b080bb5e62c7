// The heater M-codes on the service (heater_codes.h).
#include "heater_codes.h"

#include <avr/pgmspace.h>

#include "../../hal/avr/uart.h"
#include "../apps/cnc/reply.h"
#include "../engine/clock.h"
#include "../engine/limits.h"
#include "../engine/planner.h"
#include "heater.h"

namespace heater {
namespace {

constexpr int16_t kWaitWindow = am::centi_c(1);  // Marlin's TEMP_WINDOW
bool waiting;
uint32_t next_status;

using reply::error;
using reply::ok;

void write_gain(const char* progmem_label, uint32_t milli) {
  hal::uart::write_P(progmem_label);
  write_centi(int32_t((milli + 5) / 10));
}

// The gains after a head: Marlin's own line (`echo: p:.. i:.. d:..` and the
// like), or `[MSG:<label>p:.. i:.. d:..]` in grbl style.
void write_gains(const char* progmem_marlin_head, const char* progmem_grbl_label, const am::PidGains& g) {
  if (reply::marlin()) {
    hal::uart::write_P(progmem_marlin_head);
  } else {
    reply::info_begin();
    hal::uart::write_P(progmem_grbl_label);
  }
  write_gain(PSTR("p:"), g.kp_milli);
  write_gain(PSTR(" i:"), g.ki_milli);
  write_gain(PSTR(" d:"), g.kd_milli);
  if (reply::marlin()) hal::uart::write('\n');
  else reply::info_end();
}

bool reached(bool cooling_too) {
  const am::TempReading t = reading();
  const int16_t goal = target();
  if (goal <= 0) return true;
  if (!t.ok()) return false;
  return cooling_too ? t.centi <= goal + kWaitWindow && t.centi >= goal - kWaitWindow
                     : t.centi >= goal - kWaitWindow;
}

// One turn of a wait: false while it goes on; prints the answer when it ends.
bool wait_turn(const am::GcodeHeaterCommand& c) {
  if (!waiting) {
    waiting = true;
    next_status = clock::now() + clock::ms(1000);
  }
  const bool m303 = board::kAutotune && c.code == am::GcodeCode::m303;
  const char* failed = nullptr;
  bool apply = false;
  if (fault() != am::HeaterFault::none) {
    failed = PSTR("heater halted");
  } else if (limits::alarm()) {
    failed = planner::refusal_text(planner::Refusal::alarm);
  } else if (hal::uart::available()) {
    failed = PSTR("wait ended by the host");
  } else if (m303 ? tuning()->running() : !reached(c.wait_cooling)) {
    if (clock::due(next_status, clock::ms(1000))) write_status_line();
    return false;
  } else if (m303) {
    const am::AutotuneState s = tuning()->state();
    apply = s == am::AutotuneState::done;  // "gains out of range" unless set_gains() takes them
    failed = s == am::AutotuneState::failed_overshoot ? PSTR("autotune: overshoot")
             : s == am::AutotuneState::failed_timeout ? PSTR("autotune: timeout")
             : s == am::AutotuneState::failed_sensor  ? PSTR("autotune: sensor")
                                                      : PSTR("autotune: gains out of range");
  }
  waiting = false;
  if (m303 && autotune_end(apply)) {
    write_gains(PSTR("PID Autotune finished: "), PSTR("PID Autotune finished: "), gains());
    failed = nullptr;
  }
  if (failed) error(reply::code::heater, failed);
  else ok();
  return true;
}

// A target refused (set_target(), autotune()): in an alarm, which keeps the
// heater off until unlocked (heater.cpp), or after a fault, until reset.
bool refuse_halted() {
  if (limits::alarm()) {
    error(reply::code::alarm_lock, planner::refusal_text(planner::Refusal::alarm));
    return true;
  }
  reply::error_begin();
  hal::uart::write_P(PSTR("heater halted ("));
  hal::uart::write_P(fault_text());
  hal::uart::write_P(PSTR("), reset to clear"));
  reply::error_end(reply::code::heater);
  return true;
}

}  // namespace

bool run(const am::GcodeHeaterCommand& c) {
  switch (c.code) {
    case am::GcodeCode::m104:
      if (!set_target(c.target)) return refuse_halted();
      ok();
      return true;
    case am::GcodeCode::m109:
      if (!waiting && !set_target(c.target)) return refuse_halted();
      return wait_turn(c);
    case am::GcodeCode::m303:
      if (!board::kAutotune || (!waiting && !autotune(c.target, c.count))) return refuse_halted();
      return wait_turn(c);
    case am::GcodeCode::m105:  // Marlin: `ok T:...`; grbl: the status, then `ok`
      if (reply::marlin()) {
        hal::uart::write_P(PSTR("ok "));
        write_status_line();
      } else {
        write_status_line();
        ok();
      }
      return true;
    case am::GcodeCode::m155:
      auto_report(c.count);
      ok();
      return true;
    case am::GcodeCode::m301: {
      am::PidGains g = gains();
      if (c.gains_given & 1) g.kp_milli = c.gains[0];
      if (c.gains_given & 2) g.ki_milli = c.gains[1];
      if (c.gains_given & 4) g.kd_milli = c.gains[2];
      // The interpreter checked the ranges set_gains() takes.
      set_gains(g);
      write_gains(PSTR("echo: "), PSTR(""), gains());
      ok();
      return true;
    }
    case am::GcodeCode::m500:
      store_gains();
      write_gains(PSTR("echo:Settings Stored: "), PSTR("Settings Stored: "), gains());
      ok();
      return true;
    default:  // M108: nothing waits when it is read; M106, M107: the board has no fan output (docs/heater.md)
      ok();
      return true;
  }
}

}  // namespace heater
