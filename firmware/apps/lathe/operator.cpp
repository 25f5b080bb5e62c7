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

// The board's machine as the settings' defaults.
constexpr am::Pitch kLead = board::kLeadscrewPitch;
static_assert(kLead.num % kLead.den == 0 || kLead.num == 25400, "a lead in whole um or in TPI");
const am::ui::Settings kDefaults PROGMEM = {
    {board::kSpindleLines, board::kSpindleQuadrature, kLead.num / kLead.den, kLead.num == 25400 ? kLead.den * 10 : 0,
     board::kLeadscrewCounts.num, 1, board::kLeadscrewReversed, board::kLeadscrewMaxRate / 5},
    0};
static_assert(board::kLeadscrewCounts.den == 1, "no belt ratio in the settings");

void apply_encoder(const am::ui::Settings& s) {
  leadscrew::set_encoder(s.value[am::ui::kFieldQuadrature] != 0, uint16_t(s.value[am::ui::kFieldEncoderLines]));
}

struct Lathe {
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
  static void save(const am::ui::Settings& s) {
    hal::eeprom::update(kSettingsAddress, &s, sizeof s);
    apply_encoder(s);
  }
};

am::ui::Workflow<Lathe> workflow;

}  // namespace

void init() {
  am::ui::Settings s;
  hal::eeprom::read(kSettingsAddress, &s, sizeof s);
  const am::ui::Settings defaults = am::ui::flash_copy(&kDefaults);
  const bool loaded = am::ui::load_settings(s, defaults);
  apply_encoder(s);
  keypad::init();
  hd44780::init();
  workflow.start(s, loaded);
}

void poll() {
  workflow.poll(keypad::poll());
  hd44780::poll(workflow.screen());
}

}  // namespace operator_ui
