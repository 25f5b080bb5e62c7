// The operator panel (contract in operator.h): the workflow's lathe
// interface mapped onto the leadscrew API, the settings block in the
// EEPROM, the keypad and the display.
#include <avr/pgmspace.h>
#define AM_TEXT(s) PSTR(s)
#define AM_TEXT_BYTE(p) pgm_read_byte(p)
#define AM_FLASH PROGMEM

#include "operator.h"

#include "../../../core/ui/workflow.h"
#include "../../../hal/avr/eeprom.h"
#include "../../board.h"
#include "../../devices/hd44780.h"
#include "../../devices/keypad.h"
#include "../../engine/clock.h"
#include "leadscrew.h"

namespace operator_ui {
namespace {

constexpr uint16_t kSettingsAddress = 0;

constexpr am::ui::Drive kDrive = board::kServoLeadscrew ? am::ui::Drive::servo : am::ui::Drive::stepper;
using Block = am::ui::Settings<kDrive>;
static_assert(board::kLeadscrewMaxRate == am::ui::max_rapid(kDrive), "the rapid rate's range is the board's");

// The board's machine as the settings' defaults: the stepper's counts as
// steps x 1 microstep, the servo's as its encoder's pulses x its gearbox,
// and the servo's gains (the servo's figures are read through ServoMotor,
// a name every board has, so that a stepper board compiles without them).
constexpr am::Pitch kLead = board::kLeadscrewPitch;
static_assert(kLead.num % kLead.den == 0 || kLead.num == 25400, "a lead in whole um or in TPI");
static_assert(board::kLeadscrewCounts.den == 1, "no belt ratio in the settings");
#define AM_MACHINE_FIELDS                                                                                  \
  board::kSpindleLines, board::kSpindleQuadrature, kLead.num / kLead.den, kLead.num == 25400 ? kLead.den * 10 : 0
template <class Motor = board::ServoMotor>
constexpr am::ui::Settings<am::ui::Drive::servo> board_defaults(am::ui::Settings<am::ui::Drive::servo>*) {
  return {{AM_MACHINE_FIELDS, Motor::kPulses, Motor::kGearbox, board::kLeadscrewReversed, board::kLeadscrewMaxRate,
           Motor::kGains.kp_milli, Motor::kGains.ki_milli, Motor::kGains.kd_milli},
          0};
}
constexpr am::ui::Settings<am::ui::Drive::stepper> board_defaults(am::ui::Settings<am::ui::Drive::stepper>*) {
  return {{AM_MACHINE_FIELDS, board::kLeadscrewCounts.num, 1, board::kLeadscrewReversed, board::kLeadscrewMaxRate / 5},
          0};
}
#undef AM_MACHINE_FIELDS
const Block kDefaults PROGMEM = board_defaults(static_cast<Block*>(nullptr));

// The settings the leadscrew takes: the encoder, and a servo's gains.
inline void apply_gains(const am::ui::Settings<am::ui::Drive::stepper>&) {}
inline void apply_gains(const am::ui::Settings<am::ui::Drive::servo>& s) { leadscrew::set_gains(am::ui::servo_gains(s)); }
void apply(const Block& s) {
  leadscrew::set_encoder(s.value[am::ui::kFieldQuadrature] != 0, uint16_t(s.value[am::ui::kFieldEncoderLines]));
  apply_gains(s);
}

struct Lathe {
  static constexpr am::ui::Drive kDrive = operator_ui::kDrive;
  static constexpr bool kApproximate = board::kApproximateRatios;
  static bool engage(const am::Ratio& r, bool reversed, int32_t length, uint8_t start, uint8_t starts) {
    return leadscrew::engage(r, reversed, length, start, starts) == leadscrew::Refusal::none;
  }
  static bool synced() { return leadscrew::state() != leadscrew::State::armed; }
  static bool busy() { return leadscrew::busy(); }
  static void stop_now() { leadscrew::stop_now(); }
  static int32_t position() { return leadscrew::position(); }
  static int32_t following_error() { return leadscrew::following_error(); }
  static uint16_t rpm() {
    const int16_t r = leadscrew::spindle_rpm();
    return uint16_t(r < 0 ? -r : r);
  }
  static bool move_to(int32_t steps, uint32_t rate) { return leadscrew::move_to(steps, rate) == leadscrew::Refusal::none; }
  __attribute__((noinline)) static uint16_t ms() { return uint16_t(clock::now() / clock::ticks_per_ms); }
  static void save(const Block& s) {
    hal::eeprom::update(kSettingsAddress, &s, sizeof s);
    apply(s);
  }
};

am::ui::Workflow<Lathe> workflow;

}  // namespace

void init() {
  Block s;
  hal::eeprom::read(kSettingsAddress, &s, sizeof s);
  const Block defaults = am::ui::flash_copy(&kDefaults);
  const bool loaded = am::ui::load_settings(s, defaults);
  apply(s);
  keypad::init();
  hd44780::init();
  workflow.start(s, loaded);
}

void poll() {
  workflow.poll(keypad::poll());
  hd44780::poll(workflow.screen());
}

}  // namespace operator_ui
