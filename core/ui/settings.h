// The lathe's settings: what the operator sets once per machine, stored in
// the EEPROM as one checked block.
//
// Contract
//   Settings holds one uint32_t per field (kField*), each within the field's
//   [min, max] (field()), and `check`, a Fletcher-16 sum over the values
//   started from kSettingsVersion, so a block written by another layout, a
//   half-written block or erased cells (0xFF) never pass. load_settings()
//   takes a block read from the EEPROM: valid -> true and it is used as it
//   is; otherwise -> false and `defaults` (the board's machine: the
//   firmware builds them from its board header) replace it.
//   seal() recomputes the check before the block is written.
//   machine() turns the settings into core/lathe's Machine: spindle counts
//   per turn = encoder lines, x 4 for a quadrature encoder (both edges of
//   both channels); a lead in TPI (kFieldLeadTpi nonzero, 0.1 TPI) is used
//   instead of the lead in mm.
//
// Why one uint32_t per field: one range check, one entry screen and one
// table row serve every field; the block is 34 bytes.
#pragma once
#include <stdint.h>

#include "../lathe/ratio.h"
#include "flash.h"

namespace am {
namespace ui {

enum : uint8_t {
  kFieldEncoderLines,   // spindle encoder lines (slots) per turn
  kFieldQuadrature,     // 1: quadrature, counted x 4; 0: one channel
  kFieldLeadUm,         // leadscrew pitch, um
  kFieldLeadTpi,        // leadscrew pitch in 0.1 TPI, 0 = use the mm value
  kFieldMotorSteps,     // full steps per motor turn
  kFieldMicrosteps,
  kFieldReversed,       // 1: positive steps move the carriage the other way
  kFieldRapid,          // retract and move rate, steps/s
  kFieldCount
};

constexpr uint16_t kSettingsVersion = 0x4C32;  // 'L2'
constexpr uint32_t kMaxLines = 16383;  // x 4 still below 2^16 counts per turn

// A number the operator types: its prompt (16 columns at most), range and
// decimals (the value is kept x 10^decimals). Settings fields and the
// workflow's entries (workflow.h) share it.
struct FieldSpec {
  const char* label;
  int32_t min, max;
  uint8_t decimals;
};

struct Settings {
  uint32_t value[kFieldCount];
  uint16_t check;
};

inline const FieldSpec& field_row(uint8_t i) {
  static const char kLines[] AM_FLASH = "Encoder lines";
  static const char kQuad[] AM_FLASH = "Quadrature 0/1";
  static const char kLeadMm[] AM_FLASH = "Lead mm";
  static const char kLeadTpi[] AM_FLASH = "Lead TPI 0=mm";
  static const char kSteps[] AM_FLASH = "Steps/rev";
  static const char kMicro[] AM_FLASH = "Microsteps";
  static const char kReversed[] AM_FLASH = "Reverse 0/1";
  static const char kRapid[] AM_FLASH = "Rapid steps/s";
  static const FieldSpec kFields[kFieldCount] AM_FLASH = {
      {kLines, 1, kMaxLines, 0}, {kQuad, 0, 1, 0},    {kLeadMm, 100, 50000, 3}, {kLeadTpi, 0, 1000, 1},
      {kSteps, 1, 10000, 0},     {kMicro, 1, 256, 0}, {kReversed, 0, 1, 0},     {kRapid, 100, 20000, 0},
  };
  return kFields[i];
}

inline FieldSpec field(uint8_t i) { return flash_copy(&field_row(i)); }

inline uint16_t settings_check(const Settings& s) {
  uint16_t a = uint8_t(kSettingsVersion), b = kSettingsVersion >> 8;
  const uint8_t* p = reinterpret_cast<const uint8_t*>(s.value);
  for (uint8_t i = 0; i < sizeof s.value; ++i) {
    a = uint16_t((a + p[i]) % 255);
    b = uint16_t((b + a) % 255);
  }
  return uint16_t(b << 8 | a);
}

inline void seal(Settings& s) { s.check = settings_check(s); }

inline bool settings_valid(const Settings& s) {
  if (s.check != settings_check(s)) return false;
  for (uint8_t i = 0; i < kFieldCount; ++i) {
    const FieldSpec f = field(i);
    if (s.value[i] < uint32_t(f.min) || s.value[i] > uint32_t(f.max)) return false;
  }
  return true;
}

inline bool load_settings(Settings& s, const Settings& defaults) {
  if (settings_valid(s)) return true;
  s = defaults;
  seal(s);
  return false;
}

__attribute__((noinline)) inline Machine machine(const Settings& s) {
  const uint32_t* v = s.value;
  const Pitch lead = v[kFieldLeadTpi] ? Pitch{254000, v[kFieldLeadTpi]} : pitch_um(v[kFieldLeadUm]);
  const uint16_t counts = uint16_t(v[kFieldEncoderLines] << (v[kFieldQuadrature] ? 2 : 0));
  return {lead, stepper_counts(v[kFieldMotorSteps], v[kFieldMicrosteps]), counts, v[kFieldReversed] != 0};
}

}  // namespace ui
}  // namespace am
