// The lathe's settings: what the operator sets once per machine, stored in
// the EEPROM as one checked block.
//
// Contract
//   Settings<D> holds one uint32_t per field of the leadscrew's drive D
//   (field_count(D): the stepper's eight, kField* up to kFieldRapid; the DC
//   servo's eleven, the PID gains after them), each within the field's
//   [min, max] (field<D>()), and `check`, a Fletcher-16 sum over the values
//   started from the drive's layout version (settings_version()), so a
//   block written by another layout or the other drive, a half-written
//   block or erased cells (0xFF) never pass. load_settings() takes a block
//   read from the EEPROM: valid -> true and it is used as it is; otherwise
//   -> false and `defaults` (the board's machine: the firmware builds them
//   from its board header) replace it.
//   seal() recomputes the check before the block is written.
//   machine() turns the settings into core/lathe's Machine: spindle counts
//   per turn = encoder lines, x 4 for a quadrature encoder (both edges of
//   both channels); a lead in TPI (kFieldLeadTpi nonzero, 0.1 TPI) is used
//   instead of the lead in mm; leadscrew counts per turn = steps x
//   microsteps (stepper) or encoder pulses x gearbox (servo).
//   servo_gains() gives a servo block's PID gains (core/lathe/servo_pid.h's
//   units, x 1000): within their fields' ranges they are within the PID's
//   for every sample period of at least kServoMinSampleUs (servo_pid.h).
//
// Why one uint32_t per field: one range check, one entry screen and one
// table row serve every field; the stepper's block is 34 bytes, the servo's
// 46. Why a template on the drive: an image has one leadscrew, and links
// one table and one layout.
#pragma once
#include <stdint.h>

#include "../lathe/ratio.h"
#include "../lathe/servo_pid.h"
#include "flash.h"

namespace am {
namespace ui {

enum class Drive : uint8_t { stepper, servo };

enum : uint8_t {
  kFieldEncoderLines,   // spindle encoder lines (slots) per turn
  kFieldQuadrature,     // 1: quadrature, counted x 4; 0: one channel (a servo's spindle: always)
  kFieldLeadUm,         // leadscrew pitch, um
  kFieldLeadTpi,        // leadscrew pitch in 0.1 TPI, 0 = use the mm value
  kFieldMotorSteps,     // full steps per motor turn; a servo: encoder pulses per motor turn
  kFieldMicrosteps,     // a servo: the gearbox's motor turns per leadscrew turn
  kFieldReversed,       // 1: positive steps move the carriage the other way
  kFieldRapid,          // retract and move rate, steps/s (servo counts/s)
  kFieldKp,             // servo only: Kp, duty per count, x 1000
  kFieldKi,             // Ki, duty per count and second, x 1000
  kFieldKd,             // Kd, duty s per count, x 1000
};

constexpr uint8_t field_count(Drive d) { return d == Drive::servo ? kFieldKd + 1 : kFieldRapid + 1; }
constexpr uint16_t settings_version(Drive d) { return d == Drive::servo ? 0x5331 : 0x4C32; }  // 'S1', 'L2'
constexpr uint32_t kMaxLines = 16383;  // x 4 still below 2^16 counts per turn
// The rapid rate's top: the stepper's 20000 steps/s; the seed's servo
// 1800 counts/s (84 % of its motor's top speed, so the loop keeps
// headroom). The firmware checks its board's figure against it.
constexpr uint32_t max_rapid(Drive d) { return d == Drive::servo ? 1800 : 20000; }
// A number the operator types: its prompt (16 columns at most), range and
// decimals (the value is kept x 10^decimals). Settings fields and the
// workflow's entries (workflow.h) share it.
struct FieldSpec {
  const char* label;
  int32_t min, max;
  uint8_t decimals;
};

template <Drive D>
struct Settings {
  uint32_t value[field_count(D)];
  uint16_t check;
};

template <Drive D>
inline const FieldSpec& field_row(uint8_t i) {
  static const char kLines[] AM_FLASH = "Encoder lines";
  static const char kQuad[] AM_FLASH = "Quadrature 0/1";
  static const char kOneChannel[] AM_FLASH = "Quadrature 0";
  static const char kLeadMm[] AM_FLASH = "Lead mm";
  static const char kLeadTpi[] AM_FLASH = "Lead TPI 0=mm";
  static const char kSteps[] AM_FLASH = "Steps/rev";
  static const char kMicro[] AM_FLASH = "Microsteps";
  static const char kPulses[] AM_FLASH = "Pulses/motor rev";
  static const char kGearbox[] AM_FLASH = "Gearbox 1:N";
  static const char kReversed[] AM_FLASH = "Reverse 0/1";
  static const char kRapid[] AM_FLASH = "Rapid steps/s";
  static const char kRapidCounts[] AM_FLASH = "Rapid counts/s";
  static const char kKp[] AM_FLASH = "Kp duty/count";
  static const char kKi[] AM_FLASH = "Ki duty/count s";
  static const char kKd[] AM_FLASH = "Kd duty s/count";
  static const FieldSpec kStepper[field_count(Drive::stepper)] AM_FLASH = {
      {kLines, 1, kMaxLines, 0}, {kQuad, 0, 1, 0},    {kLeadMm, 100, 50000, 3},
      {kLeadTpi, 0, 1000, 1},    {kSteps, 1, 10000, 0}, {kMicro, 1, 256, 0},
      {kReversed, 0, 1, 0},      {kRapid, 100, int32_t(max_rapid(Drive::stepper)), 0},
  };
  // The servo's spindle has one channel (its INT0 is the motor encoder's);
  // its gains within the PID's ranges (servo_pid.h) and below a typed
  // number's ceiling (entries.h: kTooLarge).
  static const FieldSpec kServo[field_count(Drive::servo)] AM_FLASH = {
      {kLines, 1, kMaxLines, 0}, {kOneChannel, 0, 0, 0},  {kLeadMm, 100, 50000, 3},
      {kLeadTpi, 0, 1000, 1},    {kPulses, 1, 10000, 0},  {kGearbox, 1, 256, 0},
      {kReversed, 0, 1, 0},      {kRapidCounts, 100, int32_t(max_rapid(Drive::servo)), 0},
      {kKp, 0, 255000, 3},       {kKi, 0, 999999, 3},     {kKd, 0, 4000, 3},
  };
  return D == Drive::servo ? kServo[i] : kStepper[i];
}

template <Drive D>
inline FieldSpec field(uint8_t i) {
  return flash_copy(&field_row<D>(i));
}

template <Drive D>
inline uint16_t settings_check(const Settings<D>& s) {
  constexpr uint16_t kVersion = settings_version(D);
  uint16_t a = uint8_t(kVersion), b = kVersion >> 8;
  const uint8_t* p = reinterpret_cast<const uint8_t*>(s.value);
  for (uint8_t i = 0; i < sizeof s.value; ++i) {
    a = uint16_t((a + p[i]) % 255);
    b = uint16_t((b + a) % 255);
  }
  return uint16_t(b << 8 | a);
}

template <Drive D>
inline void seal(Settings<D>& s) {
  s.check = settings_check(s);
}

template <Drive D>
inline bool settings_valid(const Settings<D>& s) {
  if (s.check != settings_check(s)) return false;
  for (uint8_t i = 0; i < field_count(D); ++i) {
    const FieldSpec f = field<D>(i);
    if (s.value[i] < uint32_t(f.min) || s.value[i] > uint32_t(f.max)) return false;
  }
  return true;
}

template <Drive D>
inline bool load_settings(Settings<D>& s, const Settings<D>& defaults) {
  if (settings_valid(s)) return true;
  s = defaults;
  seal(s);
  return false;
}

template <Drive D>
__attribute__((noinline)) inline Machine machine(const Settings<D>& s) {
  const uint32_t* v = s.value;
  const Pitch lead = v[kFieldLeadTpi] ? Pitch{254000, v[kFieldLeadTpi]} : pitch_um(v[kFieldLeadUm]);
  const uint16_t counts = uint16_t(v[kFieldEncoderLines] << (v[kFieldQuadrature] ? 2 : 0));
  // stepper_counts(steps, microsteps) and servo_counts(pulses, gearbox):
  // both the product, per leadscrew turn.
  return {lead, {v[kFieldMotorSteps] * v[kFieldMicrosteps], 1}, counts, v[kFieldReversed] != 0};
}

inline ServoGains servo_gains(const Settings<Drive::servo>& s) {
  return {s.value[kFieldKp], s.value[kFieldKi], s.value[kFieldKd]};
}

}  // namespace ui
}  // namespace am
