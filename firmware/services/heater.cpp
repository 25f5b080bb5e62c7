// The heater service's control loop (heater.h): sampling, PID or autotune,
// safety, the outputs, the fault and auto-report lines.
#include "heater.h"

#include <avr/pgmspace.h>

#include "../../core/text/gcode_interpreter.h"
#include "../../core/thermal/adc_filter.h"
#include "../../core/thermal/thermistor.h"
#include "../../hal/avr/adc.h"
#include "../../hal/avr/eeprom.h"
#include "../../hal/avr/uart.h"
#include "../apps/cnc/reply.h"
#include "../board.h"
#include "../engine/clock.h"
#include "../engine/limits.h"

namespace heater {
namespace {

using Hw = board::Heater;

// The gains M500 stores, at the start of the EEPROM: a tag that says what
// the bytes are (an erased EEPROM reads 0xFF), the gains, and a sum of
// their bytes that a torn write would break.
constexpr uint16_t kStoredAt = 0;
constexpr uint16_t kStoredTag = 0xA701;
struct Stored {
  uint16_t tag;
  am::PidGains gains;
  uint16_t sum;
};
uint16_t checksum(const am::PidGains& g) {
  const uint8_t* b = reinterpret_cast<const uint8_t*>(&g);
  uint16_t sum = 0x5A5A;
  for (uint8_t i = 0; i < sizeof g; ++i) sum = uint16_t((sum << 1 | sum >> 15) ^ b[i]);
  return sum;
}
using Table = am::ThermistorTable<am::kHotendThermistorPoints>;
const Table kTable PROGMEM = Table(am::kHotendThermistor);
const am::HeaterFaultText kFaultText PROGMEM = am::kHeaterFaultText;
static_assert(am::SafetyLimits().maxtemp - am::centi_c(15) == am::kGcodeMaxTarget, "M104's limit: MAXTEMP - 15 C");

struct FlashFetch {
  am::ThermistorPoint operator()(const am::ThermistorPoint* p) const {
    return {pgm_read_word(&p->x), int16_t(pgm_read_word(&p->centi))};
  }
};

am::AdcOversampler<2> sampler;
// The PID and an autotune never run at once, so they share their RAM (the
// m32 has 2 KB; docs/boards.md): `tuning_` says which one is alive, `kept`
// holds the PID's gains meanwhile. Both are trivially copyable, so an
// assignment starts the other member's life.
union Control {
  am::HeaterPid pid;
  am::RelayAutotune tune;
  constexpr Control() : pid() {}
} control;
bool tuning_;
am::PidGains kept;
am::HeaterSafety safety;
am::TempReading reading_{0, am::SensorState::open};
int16_t target_, tune_target;
uint8_t duty_;
bool halted;  // the fault latched and its line went out
uint32_t next_sample, now_ms;
uint32_t report_period, next_report;  // ticks; 0: no auto-report

// The fault's line, once: Marlin's `Error:<fault>, ...`; in grbl style an
// info line (`error:` is an answer to a line there, and none is pending).
void halt() {
  halted = true;
  target_ = 0;
  if (reply::marlin())
    reply::error_begin();
  else
    reply::info_begin();
  hal::uart::write_P(fault_text());
  hal::uart::write_P(PSTR(", heater halted until reset"));
  if (reply::marlin()) hal::uart::write('\n');
  else reply::info_end();
}

// `T:<cur> /<target> @:<duty>`, without a line end.
void write_status() {
  hal::uart::write_P(PSTR("T:"));
  if (reading_.ok()) write_centi(reading_.centi);
  else hal::uart::write_P(reading_.state == am::SensorState::open ? PSTR("open") : PSTR("shorted"));
  hal::uart::write_P(PSTR(" /"));
  write_centi(target());
  hal::uart::write_P(PSTR(" @:"));
  hal::uart::write_u32(duty_);
}

void convert() {
  reading_ = am::thermistor_temperature<am::AdcOversampler<2>::kBits>(kTable, sampler.value(), FlashFetch());
}

bool temp_ok;  // the TEMP_OK output (safety.h: its hysteresis)

void sample_period() {
  convert();
  const uint8_t wanted = board::kAutotune && tuning_ ? control.tune.update(reading_) : control.pid.update(reading_, target_);
  duty_ = safety.check(now_ms, reading_, target(), wanted);
  now_ms += kPeriodMs;
  Hw::Pwm::set(duty_);
  temp_ok = safety.temp_ok(reading_, target_, temp_ok);
  Hw::TempOk::set(temp_ok);
  if (safety.faulted() && !halted) halt();
}

}  // namespace

void init() {
  Hw::Pwm::init();
  Stored stored;
  if (!board::kSettings) hal::eeprom::read(kStoredAt, &stored, sizeof stored);
  if (board::kSettings || stored.tag != kStoredTag || stored.sum != checksum(stored.gains) || !set_gains(stored.gains))
    set_gains(am::PidGains{22200, 1080, 114000});  // Marlin's DEFAULT_Kp/Ki/Kd
  hal::adc::init(hal::adc::Prescaler::div128, false);  // 125 kHz: 104 us a conversion
  hal::adc::select(Hw::adc_channel);
  // A first reading before anything asks for one (16 conversions, 1.9 ms).
  do {
    hal::adc::start();
    while (hal::adc::busy()) {
    }
  } while (!sampler.add(hal::adc::read10()));
  convert();
  hal::adc::start();
  next_sample = clock::ms(kPeriodMs);  // the clock starts at 0 after this
}

void store_gains() {
  const Stored stored{kStoredTag, gains(), checksum(gains())};
  hal::eeprom::update(kStoredAt, &stored, sizeof stored);
}

// A machine alarm (a hard limit, a failed homing, a reset in motion) turns
// the heater off, as a fault does, but without latching: once unlocked, a
// new target heats again (set_target() refuses one during the alarm, and
// heater_codes.cpp ends an autotune's wait, which ends the tune).
void alarm_off() {
  target_ = 0;
  duty_ = 0;
  Hw::Pwm::set(0);  // now, not at the next sample
  reply::info_P(PSTR("heater off: alarm"));
}

void poll() {
  if (target_ > 0 && limits::alarm()) alarm_off();
  if (!hal::adc::busy()) {
    sampler.add(hal::adc::read10());
    hal::adc::start();
  }
  if (clock::due(next_sample, clock::ms(kPeriodMs))) sample_period();
  if (report_period && clock::due(next_report, report_period)) write_status_line();
}

bool set_target(int16_t centi) {
  if (halted || limits::alarm()) return false;
  target_ = centi;
  return true;
}
int16_t target() { return tuning_ && control.tune.running() ? tune_target : target_; }
am::TempReading reading() { return reading_; }
am::HeaterFault fault() { return safety.fault(); }
const char* fault_text() { return kFaultText.text[uint8_t(safety.fault())]; }
const am::PidGains& gains() { return control.pid.gains(); }
// One copy of HeaterPid::set_gains (about 450 bytes) for every caller.
__attribute__((noinline)) bool set_gains(const am::PidGains& g) { return control.pid.set_gains(g, kPeriodMs); }

bool autotune(int16_t centi, uint8_t cycles) {
  if (halted || limits::alarm()) return false;
  am::AutotuneConfig config;
  config.target = tune_target = centi;
  config.cycles = cycles;
  config.period_ms = kPeriodMs;
  kept = control.pid.gains();
  control.tune = am::RelayAutotune();
  control.tune.start(config);
  tuning_ = true;
  target_ = 0;  // what follows the tune
  return true;
}

bool autotune_end(bool apply) {
  const bool done = apply && control.tune.state() == am::AutotuneState::done;
  const am::PidGains tuned = control.tune.gains();
  tuning_ = false;
  control.pid = am::HeaterPid();
  if (done && set_gains(tuned)) return true;
  set_gains(kept);
  return false;
}

const am::RelayAutotune* tuning() { return tuning_ ? &control.tune : nullptr; }

void auto_report(uint8_t seconds) {
  report_period = clock::ms(1000ul * seconds);
  next_report = clock::now() + report_period;
}

void write_centi(int32_t c) {
  if (c < 0) hal::uart::write('-');
  const uint32_t m = uint32_t(c < 0 ? -c : c);
  hal::uart::write_u32(m / 100);
  hal::uart::write('.');
  hal::uart::write(uint8_t('0' + m / 10 % 10));
  hal::uart::write(uint8_t('0' + m % 10));
}

void write_status_line() {
  if (!reply::marlin()) reply::info_begin();
  write_status();
  if (reply::marlin()) hal::uart::write('\n');
  else reply::info_end();
}

}  // namespace heater
