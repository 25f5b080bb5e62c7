// The settings service (settings.h): the board's layout and defaults, the
// block in the EEPROM, applying it.
#include "settings.h"

#include <avr/pgmspace.h>
#include <math.h>
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
#include "../engine/step_engine.h"
#include "heater.h"

namespace settings {
namespace {

using namespace am::settings;
constexpr uint8_t kAxes = board::Axes::count;
using Endstops = board::Endstops;
constexpr uint8_t kParts =
    uint8_t((board::kHeater ? kHeaterGains : 0) | (board::kPinPolarities ? kPinPolarities : 0) |
            (board::kPrinterCodes ? kPathAccels : 0) | (board::kFirmwareRetract ? kRetraction : 0));
using Table = Layout<kAxes, Endstops::axes, kParts>;
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

// M207's and M208's settings in the retraction kinds' order, in the
// interpreter's units (1/10000 mm; the settings' are thousandths).
using Retraction = am::GcodeRetraction;
int32_t Retraction::* const kRetractionFields[5] = {&Retraction::length, &Retraction::feed, &Retraction::hop,
                                                    &Retraction::extra, &Retraction::recover_feed};
uint32_t retraction_value(const Retraction& r, uint8_t k) { return uint32_t((r.*kRetractionFields[k] + 5) / 10); }

// The board header's figures, in the settings' units. (The kinds of the
// switches, the heater and the printer's only where the board has them.)
void defaults(Values& b) {
  for (uint8_t i = 0; i < Table::kCount; ++i) {
    const Entry e = Table::at(i);
    const uint32_t spm = board::Axes::steps_per_m_at(e.axis);
    uint32_t v;
    if (Table::has(kPinPolarities) && e.kind <= Kind::limit_invert)  // the pins as the board has them
      v = 0;
    else if (e.kind == Kind::junction)
      v = path::kJunctionDeviationUm;
    else if (e.kind == Kind::steps)
      v = spm;
    else if (e.kind == Kind::rate)
      v = rate_mm(top_rate(e.axis), spm);
    else if (e.kind == Kind::accel)
      v = accel_mm(board::kDefaultAccel, spm);
    else if (e.kind == Kind::protocol)  // the style in force: the board's at boot, kept by $RST=$ and M502
      v = board::kProtocolSwitch ? uint32_t(reply::marlin()) : uint32_t(board::kProtocol);
    else if (Table::has(kHeaterGains) && e.kind >= Kind::gain_p)
      v = e.kind == Kind::gain_p ? 22200 : e.kind == Kind::gain_i ? 1080 : 114000;  // Marlin's DEFAULT_Kp/Ki/Kd
    else if (Table::has(kPathAccels) && e.kind == Kind::path_accel)
      v = 0;  // no cap beyond the axes' own
    else if (Table::has(kRetraction) && e.kind >= Kind::retract_length && e.kind <= Kind::recover_feed)
      v = retraction_value(Retraction(), uint8_t(uint8_t(e.kind) - uint8_t(Kind::retract_length)));  // Marlin's
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

// A machine code's figure held within its setting's range: M207's and
// M208's feeds are above 0 in 1/10000 mm/min, and one below 0.0005 mm/min
// would round to none in thousandths.
uint32_t within(Kind k, uint32_t v) {
  const uint32_t lo = range_min(k), hi = range_max(k);
  return v < lo ? lo : v > hi ? hi : v;
}

// The machine codes' settings in force (M301's or an autotune's gains,
// M204's accelerations, M207's and M208's retraction) in place of the
// block's: what `$$` shows and a change stores.
void machine_codes_in_force(Values& b) {
  if (Table::has(kHeaterGains)) {
    constexpr uint8_t p = Table::first(Kind::gain_p);
    const am::PidGains& g = heater::gains();
    b.value[p] = g.kp_milli;
    b.value[p + 1] = g.ki_milli;
    b.value[p + 2] = g.kd_milli;
  }
  if (Table::has(kPathAccels)) {
    constexpr uint8_t p = Table::first(Kind::path_accel);
    for (uint8_t k = 0; k < 3; ++k) {
      const float a = path::path_accel_cap(path::PathAccel(k));  // mm/s^2, infinite: no cap
      b.value[p + k] = a > 1e6f ? 0 : within(Kind::path_accel, uint32_t(a * 1000 + 0.5f));
    }
  }
  if (Table::has(kRetraction)) {
    constexpr uint8_t p = Table::first(Kind::retract_length);
    const Retraction r = gcode::retraction();
    for (uint8_t k = 0; k < 5; ++k) b.value[p + k] = within(Kind(uint8_t(Kind::retract_length) + k), retraction_value(r, k));
  }
}

// The block in force: the EEPROM's (the defaults if it is bad), with the
// machine codes' settings as the machine runs on them.
void read_in_force(Values& b) {
  read(b);
  machine_codes_in_force(b);
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
  reply::set_marlin(value<Kind::protocol>(b) != 0);  // from the next line on (board::kProtocolSwitch)
  if (Table::has(kPinPolarities))
    engine::set_polarities(uint8_t(value<Kind::dir_invert>(b)),
                           Endstops::count && value<Kind::limit_invert>(b) ? Endstops::pins : 0);
  // The block's gains are within HeaterPid's ranges (the table's: validate()).
  if (Table::has(kHeaterGains))
    heater::set_gains(am::PidGains{value<Kind::gain_p>(b), value<Kind::gain_i>(b), value<Kind::gain_d>(b)});
  if (Table::has(kPathAccels)) {
    for (uint8_t k = 0; k < 3; ++k) {
      const uint32_t a = value<Kind::path_accel>(b, k);
      path::set_path_accel(path::PathAccel(k), a ? float(a) * 1e-3f : INFINITY);
    }
  }
  if (Table::has(kRetraction)) {
    Retraction r;
    for (uint8_t k = 0; k < 5; ++k) r.*kRetractionFields[k] = int32_t(value<Kind::retract_length>(b, k) * 10);
    gcode::set_retraction(r);  // its state (retracted or not) kept
  }
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

namespace {

void refuse(Error e) {
  const uint8_t n = uint8_t(e) - 1;
  reply::error(pgm_read_byte(&kRefusalCode[n]), reinterpret_cast<const char*>(pgm_read_word(&kRefusal[n])));
}

// A changed block: stored, applied and answered.
void commit(Values& b) {
  store(b);
  apply(b);
  reply::ok();
}

// M503's value: thousandths with three decimals.
void write_value(uint32_t v) {
  char buf[14];
  am::format_fixed(buf, int32_t(v), 3);
  hal::uart::write(buf);
}

}  // namespace

// `$$`: every setting as `$N=value`. M503 (marlin_lines): Marlin's lines for
// the settings Marlin has a code for (M205 J, M92, M203 in mm/s, M201),
// `$N=value` for the others, in the table's order, each an info line
// (`echo:  M92 X1000.000 ...`).
void list(bool marlin_lines) {
  static const char kCodes[][5] PROGMEM = {"M92", "M203", "M201"};
  Values b;
  read_in_force(b);
  char line[24];
  for (uint8_t i = 0; i < Table::kCount; ++i) {
    const Entry e = Table::at(i);
    uint32_t v = b.value[i];
    const bool grouped = marlin_lines && (e.kind == Kind::steps || e.kind == Kind::rate || e.kind == Kind::accel);
    if (marlin_lines && (!grouped || e.axis == 0)) {
      reply::info_begin();
      hal::uart::write_P(PSTR("  "));
    }
    if (grouped) {
      if (e.axis == 0) hal::uart::write_P(kCodes[uint8_t(e.kind) - uint8_t(Kind::steps)]);
      hal::uart::write(' ');
      hal::uart::write(uint8_t(board::Axes::name_at(e.axis)));
      if (e.kind == Kind::rate) v = (v + 30) / 60;  // mm/min to mm/s, rounded
      write_value(v);
      if (e.axis != kAxes - 1) continue;
    } else if (marlin_lines && e.kind == Kind::junction) {
      hal::uart::write_P(PSTR("M205 J"));
      write_value(v);
    } else {
      format(line, e, v);
      hal::uart::write(line);
    }
    if (marlin_lines)
      reply::info_end();
    else
      hal::uart::write('\n');
  }
}

void change(const char* text) {
  Values b;
  if (strcmp_P(text, PSTR("RST=$")) == 0) {
    defaults(b);
  } else {
    read_in_force(b);
    uint16_t n = 0;
    uint8_t digits = 0;
    for (; *text >= '0' && *text <= '9' && digits < 4; ++text, ++digits) n = uint16_t(n * 10 + (*text - '0'));
    Error e = Error::unknown;
    if (digits && *text == '=') e = Table::set(b, n, text + 1, engine());
    // The style is settable only where both are in the image.
    if (!board::kProtocolSwitch && n == 200 && e == Error::none) e = Error::read_only;
    if (e != Error::none) return refuse(e);
  }
  commit(b);
}

namespace {

// M92 M201 M203 M205 M500 M502 (marlin()): their block on this frame alone,
// so no second one is on the stack below it (list() and boot() have theirs).
[[gnu::noinline]] void marlin_change(uint16_t code, char* words) {
  Values b;
  if (code == 502) {
    defaults(b);
    return commit(b);
  }
  read_in_force(b);
  // M500 stores the settings in force (what the EEPROM holds already,
  // unless its block was bad: then the defaults; the heater's gains as it
  // runs on them); M92, M201, M203, M205
  // set every word's setting, all or none.
  for (;;) {
    while (*words == ' ' || *words == '\t') ++words;
    if (code == 500 || *words == '\0') break;
    const char letter = char(*words++ & ~0x20);
    char* end = words;
    while (*end != ' ' && *end != '\t' && *end != '\0') ++end;
    const char after = *end;
    *end = '\0';  // the word's number alone, as `$N=`'s
    const int8_t axis = board::Axes::index_of(letter);
    const uint16_t n = code == 205 ? 11 : uint16_t((code == 92 ? 100 : code == 203 ? 110 : 120) + axis);
    // M205's other words (jerk, minimum feeds and segment time): taken, not used.
    const Error e = code == 205 ? (letter == 'J' ? Table::set(b, n, words, engine()) : Error::none)
                    : axis < 0  ? Error::unknown
                                : Table::set(b, n, words, engine(), code == 203);
    *end = after;
    words = end;
    if (e != Error::none) return refuse(e);
  }
  commit(b);
}

}  // namespace

void marlin(uint16_t code, char* words) {
  if (code == 501) {  // the block as at boot: its defaults and its line if it is bad
    const char* news = boot();
    if (news) reply::info_P(news);
    return reply::ok();
  }
  if (code != 503) return marlin_change(code, words);
  list(true);
  reply::ok();
}

}  // namespace settings
