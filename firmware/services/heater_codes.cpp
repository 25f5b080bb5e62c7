// The heater M-codes on the service (heater_codes.h).
#include "heater_codes.h"

#include <avr/pgmspace.h>

#include "../../hal/avr/uart.h"
#include "../engine/clock.h"
#include "heater.h"

namespace heater {
namespace {

constexpr int16_t kWaitWindow = am::centi_c(1);  // Marlin's TEMP_WINDOW
bool waiting;
uint32_t next_status;

void ok() { hal::uart::write_P(PSTR("ok\n")); }
void error(const char* progmem_text) {
  hal::uart::write_P(PSTR("error: "));
  hal::uart::write_P(progmem_text);
  hal::uart::write('\n');
}

void write_gain(const char* progmem_label, uint32_t milli) {
  hal::uart::write_P(progmem_label);
  const uint32_t centi = (milli + 5) / 10;
  hal::uart::write_u32(centi / 100);
  hal::uart::write('.');
  hal::uart::write(uint8_t('0' + centi / 10 % 10));
  hal::uart::write(uint8_t('0' + centi % 10));
}

void write_gains(const char* progmem_head, const am::PidGains& g) {
  hal::uart::write_P(progmem_head);
  write_gain(PSTR("p:"), g.kp_milli);
  write_gain(PSTR(" i:"), g.ki_milli);
  write_gain(PSTR(" d:"), g.kd_milli);
  hal::uart::write('\n');
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
  bool done = false;
  if (fault() != am::HeaterFault::none) {
    error(PSTR("heater halted"));
    done = true;
  } else if (hal::uart::available()) {
    if (c.code == am::GcodeCode::m303) autotune_stop();
    error(PSTR("wait ended by the host"));
    done = true;
  } else if (c.code == am::GcodeCode::m109 ? reached(c.wait_cooling) : !tuning().running()) {
    done = true;
    if (c.code == am::GcodeCode::m109) {
      ok();
    } else if (tuning().state() == am::AutotuneState::done && pid().set_gains(tuning().gains())) {
      write_gains(PSTR("PID Autotune finished: "), pid().gains());
      ok();
    } else {
      error(tuning().state() == am::AutotuneState::failed_overshoot ? PSTR("autotune failed: overshoot")
            : tuning().state() == am::AutotuneState::failed_timeout ? PSTR("autotune failed: timeout")
            : tuning().state() == am::AutotuneState::failed_sensor  ? PSTR("autotune failed: sensor")
                                                                     : PSTR("autotune failed: gains out of range"));
    }
  } else if (clock::due(next_status, clock::ms(1000))) {
    write_status();
    hal::uart::write('\n');
  }
  if (done) waiting = false;
  return done;
}

bool refuse_halted() {
  hal::uart::write_P(PSTR("error: heater halted ("));
  hal::uart::write_P(fault_text());
  hal::uart::write_P(PSTR("), reset to clear\n"));
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
      if (!waiting && !autotune(c.target, c.count)) return refuse_halted();
      return wait_turn(c);
    case am::GcodeCode::m105:
      hal::uart::write_P(PSTR("ok "));
      write_status();
      hal::uart::write('\n');
      return true;
    case am::GcodeCode::m155:
      auto_report(c.count);
      ok();
      return true;
    case am::GcodeCode::m301: {
      am::PidGains g = pid().gains();
      if (c.gains_given & 1) g.kp_milli = c.gains[0];
      if (c.gains_given & 2) g.ki_milli = c.gains[1];
      if (c.gains_given & 4) g.kd_milli = c.gains[2];
      // The interpreter checked the ranges set_gains() takes.
      pid().set_gains(g);
      write_gains(PSTR("echo: "), pid().gains());
      ok();
      return true;
    }
    default:  // M108: nothing waits when it is read
      ok();
      return true;
  }
}

}  // namespace heater
