// The settings service (settings.h): the board's layout and defaults, the
// block in the EEPROM, applying it.
#include "settings.h"

#include <avr/pgmspace.h>
#include <string.h>

#define AM_SETTINGS_FLASH PROGMEM
#define AM_SETTINGS_BYTE(p) pgm_read_byte(p)
#include "../../core/board/settings.h"
#include "../../hal/avr/eeprom.h"
#include "../../hal/avr/uart.h"
#include "../apps/cnc/gcode.h"
#include "../apps/cnc/reply.h"
#include "../board.h"
#include "../engine/limits.h"
#include "../engine/path.h"

namespace settings {
namespace {

using namespace am::settings;
constexpr uint8_t kAxes = board::Axes::count;
using Endstops = board::Endstops;
using Table = Layout<kAxes, Endstops::axes, board::kHeater>;
using Values = Table::Values;

// The block's version: a new layout or meaning of a value needs a new one
// (a block of another version loads the defaults).
constexpr uint8_t kVersion = 1;
constexpr uint16_t kStoredAt = 0;

template <typename Set>
struct StepDirOnly;
template <typename... A>
struct StepDirOnly<AxisSet<A...>> {
  static constexpr bool all(bool first = true) { return first; }
  template <typename... More>
  static constexpr bool all(bool first, bool second, More... more) {
    return first && all(second, more...);
  }
  static constexpr bool value = all(OwnUnits<A>::per_full_step == 1 ...);
};
static_assert(StepDirOnly<board::Axes>::value, "settings: steps/mm are a step/dir axis's (one position unit a step)");

uint32_t top_rate(uint8_t axis) {
  const uint32_t own = board::Axes::max_rate_at(axis);
  return own ? own : board::kMaxStepRate;
}

// One out-of-line copy (read() and change() both need it).
[[gnu::noinline]] EngineLimits<kAxes> engine() {
  EngineLimits<kAxes> e;
  for (uint8_t a = 0; a < kAxes; ++a) e.max_rate[a] = top_rate(a);
  e.max_accel = board::kMaxAccel;
  return e;
}

// The board's homing figures, in flash (an indexed constexpr object would
// be copied into RAM).
const HomingSettings<limits::kSwitches ? limits::kSwitches : 1> kBoardHoming PROGMEM = board::kHomingSettings;
HomingAxis board_homing(uint8_t k) {
  HomingAxis h;
  memcpy_P(&h, &kBoardHoming.axis[k], sizeof h);
  return h;
}

// The switch of an axis (the caller knows it has one).
uint8_t switch_of(uint8_t axis) {
  uint8_t k = 0;
  while (Endstops::axis_at(k) != axis) ++k;
  return k;
}

// A homing kind's default: the board's figure of the axis's switch.
uint32_t homing_default(Entry e, uint32_t spm) {
  const HomingAxis h = board_homing(switch_of(e.axis));
  return e.kind == Kind::homing_dir ? Endstops::max_end
         : e.kind == Kind::travel   ? length_mm(h.travel, spm)
         : e.kind == Kind::locate   ? rate_mm(h.locate_rate, spm)
         : e.kind == Kind::seek     ? rate_mm(h.seek_rate, spm)
         : e.kind == Kind::pull_off ? length_mm(h.pull_off, spm)
                                    : 1;  // soft limits, hard limits, homing: on
}

// The board header's figures, in the settings' units. (The kinds of the
// switches and the heater only where the board has them.)
void defaults(Values& b) {
  for (uint8_t i = 0; i < Table::kCount; ++i) {
    const Entry e = Table::at(i);
    const uint32_t spm = board::Axes::steps_per_m_at(e.axis);
    uint32_t v;
    if (e.kind == Kind::junction)
      v = path::kJunctionDeviationUm;
    else if (e.kind == Kind::steps)
      v = spm;
    else if (e.kind == Kind::rate)
      v = rate_mm(top_rate(e.axis), spm);
    else if (e.kind == Kind::accel)
      v = accel_mm(board::kDefaultAccel, spm);
    else if (e.kind == Kind::protocol)
      v = uint32_t(board::kProtocol);
    else if (board::kHeater && e.kind >= Kind::gain_p)
      v = e.kind == Kind::gain_p ? 22200 : e.kind == Kind::gain_i ? 1080 : 114000;  // Marlin's DEFAULT_Kp/Ki/Kd
    else
      v = Endstops::count ? homing_default(e, spm) : 1;
    b.value[i] = v;
  }
}

Loaded read(Values& b) {
  hal::eeprom::read(kStoredAt, &b, Values::kSummed + 2);
  const Loaded l = Table::examine(b, kVersion, engine());
  if (l != Loaded::ok) defaults(b);
  return l;
}

void store(Values& b) {
  Table::seal(b, kVersion);
  hal::eeprom::update(kStoredAt, &b, Values::kSummed + 2);
}

// Axis a's value of a per-axis kind, switch k's of a per-switch kind, a
// single kind's.
template <Kind K>
uint32_t value(const Values& b, uint8_t a = 0) {
  constexpr uint8_t first = Table::first(K);
  return b.value[first + a];
}

void apply(const Values& b) {
  for (uint8_t a = 0; a < kAxes; ++a) {
    const uint32_t spm = value<Kind::steps>(b, a);
    gcode::set_scale(a, spm);
    path::set_axis(a, spm, uint32_t(rate_steps(value<Kind::rate>(b, a), spm)),
                   uint32_t(accel_steps(value<Kind::accel>(b, a), spm)));
  }
  gcode::rescale();
  path::set_junction_um(value<Kind::junction>(b));
  if (!Endstops::count) return;
  limits::soft_limits = value<Kind::soft_limits>(b) != 0;
  limits::homing_enabled = value<Kind::homing>(b) != 0;
  for (uint8_t k = 0; k != Endstops::count; ++k) {
    const uint8_t a = Endstops::axis_at(k);
    const uint32_t spm = value<Kind::steps>(b, a);
    HomingAxis& h = limits::settings.axis[k];
    h.seek_rate = uint16_t(rate_steps(value<Kind::seek>(b, k), spm));
    h.locate_rate = uint16_t(rate_steps(value<Kind::locate>(b, k), spm));
    h.pull_off = uint16_t(length_steps(value<Kind::pull_off>(b, k), spm));
    h.travel = length_steps(value<Kind::travel>(b, k), spm);
    // The back-off is no setting: the board's length in mm.
    const uint32_t back_off = length_steps(length_mm(board_homing(k).back_off, board::Axes::steps_per_m_at(a)), spm);
    h.back_off = uint16_t(back_off > 0xFFFF ? 0xFFFF : back_off);
  }
}

// The refusals, by Error (less none): grbl's code and the reason, in flash.
const char kUnknown[] PROGMEM = "no such setting";
const char kReadOnly[] PROGMEM = "setting is read-only";
const char kBadNumber[] PROGMEM = "bad number";
const char kOutOfRange[] PROGMEM = "setting out of range";
const char kEngineLimit[] PROGMEM = "setting beyond the engine's step rate or acceleration";
const char* const kRefusal[] PROGMEM = {kUnknown, kReadOnly, kBadNumber, kOutOfRange, kEngineLimit};
const uint8_t kRefusalCode[] PROGMEM = {reply::code::bad_system_command, reply::code::bad_system_command,
                                        reply::code::bad_number, reply::code::out_of_range, reply::code::step_rate};
static_assert(uint8_t(Error::engine_limit) == 5, "one refusal per Error but none");

}  // namespace

const char* boot() {
  Values b;
  const Loaded l = read(b);
  apply(b);
  return l == Loaded::older     ? PSTR("EEPROM settings of another version: defaults loaded")
         : l == Loaded::corrupt ? PSTR("EEPROM settings corrupt: defaults loaded")
                                : nullptr;
}

void list() {
  Values b;
  read(b);
  char line[24];
  for (uint8_t i = 0; i < Table::kCount; ++i) {
    format(line, Table::at(i), b.value[i]);
    hal::uart::write(line);
    hal::uart::write('\n');
  }
}

void change(const char* text) {
  Values b;
  if (strcmp_P(text, PSTR("RST=$")) == 0) {
    defaults(b);
  } else {
    read(b);
    uint16_t n = 0;
    uint8_t digits = 0;
    for (; *text >= '0' && *text <= '9' && digits < 4; ++text, ++digits) n = uint16_t(n * 10 + (*text - '0'));
    Error e = Error::unknown;
    if (digits && *text == '=') e = Table::set(b, n, text + 1, engine());
    if (e != Error::none) {
      const uint8_t n = uint8_t(e) - 1;
      return reply::error(pgm_read_byte(&kRefusalCode[n]), reinterpret_cast<const char*>(pgm_read_word(&kRefusal[n])));
    }
  }
  store(b);
  apply(b);
  reply::ok();
}

}  // namespace settings
