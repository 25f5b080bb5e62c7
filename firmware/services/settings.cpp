// The settings service (settings.h): the board's layout and defaults, the
// block in the EEPROM, applying it.
#include "settings.h"

#include <avr/pgmspace.h>
#include <string.h>

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

EngineLimits<kAxes> engine() {
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

// The board header's figures, in the settings' units.
void defaults(Values& b) {
  for (uint8_t i = 0; i < Table::count(); ++i) {
    const Entry e = Table::at(i);
    const uint32_t spm = board::Axes::steps_per_m_at(e.axis);
    const bool per_switch = e.kind == Kind::travel || e.kind >= Kind::locate;
    const HomingAxis h = board_homing(Endstops::count && per_switch ? switch_of(e.axis) : 0);
    uint32_t v;
    switch (e.kind) {
      case Kind::junction: v = path::kJunctionDeviationUm; break;
      case Kind::homing_dir: v = Endstops::max_end; break;
      case Kind::steps: v = spm; break;
      case Kind::rate: v = rate_mm(top_rate(e.axis), spm); break;
      case Kind::accel: v = accel_mm(board::kDefaultAccel, spm); break;
      case Kind::travel: v = length_mm(h.travel, spm); break;
      case Kind::protocol: v = uint32_t(board::kProtocol); break;
      case Kind::locate: v = rate_mm(h.locate_rate, spm); break;
      case Kind::seek: v = rate_mm(h.seek_rate, spm); break;
      case Kind::pull_off: v = length_mm(h.pull_off, spm); break;
      case Kind::gain_p: v = 22200; break;  // Marlin's DEFAULT_Kp/Ki/Kd
      case Kind::gain_i: v = 1080; break;
      case Kind::gain_d: v = 114000; break;
      default: v = 1; break;  // soft limits, hard limits, homing: on
    }
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
uint32_t value(const Values& b, Kind kind, uint8_t a = 0) { return b.value[Table::first(kind) + a]; }

void apply(const Values& b) {
  for (uint8_t a = 0; a < kAxes; ++a) {
    const uint32_t spm = value(b, Kind::steps, a);
    gcode::set_scale(a, spm);
    path::set_axis(a, spm, uint32_t(rate_steps(value(b, Kind::rate, a), spm)),
                   uint32_t(accel_steps(value(b, Kind::accel, a), spm)));
  }
  gcode::rescale();
  path::set_junction_um(value(b, Kind::junction));
  if (!Endstops::count) return;
  limits::soft_limits = value(b, Kind::soft_limits) != 0;
  limits::homing_enabled = value(b, Kind::homing) != 0;
  for (uint8_t k = 0; k != Endstops::count; ++k) {
    const uint8_t a = Endstops::axis_at(k);
    const uint32_t spm = value(b, Kind::steps, a);
    HomingAxis& h = limits::settings.axis[k];
    h.seek_rate = uint16_t(rate_steps(value(b, Kind::seek, k), spm));
    h.locate_rate = uint16_t(rate_steps(value(b, Kind::locate, k), spm));
    h.pull_off = uint16_t(length_steps(value(b, Kind::pull_off, k), spm));
    h.travel = length_steps(value(b, Kind::travel, k), spm);
    // The back-off is no setting: the board's length in mm.
    const uint32_t back_off = length_steps(length_mm(board_homing(k).back_off, board::Axes::steps_per_m_at(a)), spm);
    h.back_off = uint16_t(back_off > 0xFFFF ? 0xFFFF : back_off);
  }
}

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
  for (uint8_t i = 0; i < Table::count(); ++i) {
    format(line, Table::at(i), b.value[i]);
    hal::uart::write(line);
    hal::uart::write('\n');
  }
}

void change(const char* text) {
  Values b;
  if (text[0] == 'R' && text[1] == 'S' && text[2] == 'T' && text[3] == '=' && text[4] == '$' && text[5] == '\0') {
    defaults(b);
  } else {
    read(b);
    uint16_t n = 0;
    uint8_t digits = 0;
    for (; *text >= '0' && *text <= '9' && digits < 4; ++text, ++digits) n = uint16_t(n * 10 + (*text - '0'));
    Error e = Error::unknown;
    if (digits && *text == '=') e = Table::set(b, n, text + 1, engine());
    switch (e) {
      case Error::none: break;
      case Error::unknown: return reply::error(reply::code::bad_system_command, PSTR("no such setting"));
      case Error::read_only: return reply::error(reply::code::bad_system_command, PSTR("setting is read-only"));
      case Error::bad_number: return reply::error(reply::code::bad_number, PSTR("bad number"));
      case Error::out_of_range: return reply::error(reply::code::out_of_range, PSTR("setting out of range"));
      default:
        return reply::error(reply::code::step_rate, PSTR("setting beyond the engine's step rate or acceleration"));
    }
  }
  store(b);
  apply(b);
  reply::ok();
}

}  // namespace settings
