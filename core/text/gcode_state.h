// What the G-code interpreter (gcode_interpreter.h) keeps and hands out:
// its axes' table entries, the modal state, the per-axis positions, the
// firmware retraction's settings and the action one accepted line asks of
// the machine, with the heater codes' command and the plane tables the arc
// words use. The meaning of every
// field is in gcode_interpreter.h's contract.
#pragma once
#include <stdint.h>

#include "gcode_parser.h"

namespace am {

// M350 modes an axis accepts, one bit per mode number.
constexpr uint8_t kModeWave = 1;       // 0
constexpr uint8_t kModeTwoPhase = 2;   // 1
constexpr uint8_t kModeHalf = 4;       // 2
constexpr uint8_t kModeMicro16 = 8;    // 16
constexpr uint8_t kModeMicro32 = 16;   // 32
constexpr uint8_t kModeMicro64 = 32;   // 64
constexpr uint8_t kModesShield = 63;   // Motor Shield steppers: all six
constexpr uint8_t kModesUnipolar = 7;  // ULN2003: wave, two-phase, half

constexpr uint8_t kNoAxis = 0xFF;

// The firmware retraction's settings and state (gcode_retraction.h),
// lengths in 1/10000 mm, feeds in 1/10000 mm/min; Marlin's defaults.
struct GcodeRetraction {
  int32_t length = 30000;          // M207 S: 3 mm (Marlin's RETRACT_LENGTH)
  int32_t feed = 27000000;         // M207 F: 2700 mm/min (45 mm/s)
  int32_t hop = 0;                 // M207 Z: the nozzle's lift
  int32_t extra = 0;               // M208 S: pushed back beyond the length
  int32_t recover_feed = 4800000;  // M208 F: 480 mm/min (8 mm/s)
  bool retracted = false;
};

struct GcodeAxis {
  char letter;           // 'X', 'Y', 'Z', 'E', 'U', 'A', 'B' or 'C'
  uint8_t modes;         // kMode* bits; 0: no excitation modes (step/dir)
  uint32_t steps_per_m;  // position units (steps) per metre of travel
};

enum class Motion : uint8_t { rapid, linear, arc_cw, arc_ccw };  // G0 G1 G2 G3
enum class Plane : uint8_t { xy, zx, yz };                        // G17 G18 G19

struct GcodeModal {
  Motion motion;
  Plane plane;
  bool incremental;  // G91
  bool inches;       // G20
  bool e_relative;   // M83, or G91 until the next M82
  int32_t feed;      // 1/10000 mm/min; 0 until the first F
};

struct GcodeAxisState {
  int32_t coord;   // program position, 1/10000 mm
  int32_t offset;  // G92 offset, steps
  int32_t steps;   // machine position, steps
};

template <uint8_t N>
struct GcodeState {
  GcodeModal modal;
  GcodeAxisState axis[N];
};

enum class GcodeActionKind : uint8_t {
  none, move, arc, dwell, set_position, report_position, enable, release, wait, set_mode, program_end, heater, home,
  unlock, printer,
};

// The highest target a heater code takes: Marlin's HEATER_0_MAXTEMP (275 C,
// core/thermal/safety.h) less HOTEND_OVERSHOOT (15 C), in 0.01 C.
constexpr int16_t kGcodeMaxTarget = 26000;
constexpr int16_t kGcodeAutotuneDefault = 15000;  // M303 without S: 150 C (Marlin)
constexpr uint8_t kGcodeAutotuneCycles = 5;       // M303 without C (Marlin)

// What a heater M-code asks (GcodeActionKind::heater, see Heater codes).
struct GcodeHeaterCommand {
  GcodeCode code;       // m104 m105 m106 m107 m108 m109 m155 m301 m303 m500
  bool wait_cooling;    // M109 R
  uint8_t gains_given;  // M301: bit 0 P, 1 I, 2 D
  uint8_t count;        // M155: seconds; M303: cycles; M106: the fan's duty 0 .. 255
  int16_t target;       // M104 M109 M303: 0.01 C
  uint32_t gains[3];    // M301: P I D, thousandths
};

// What a printer M-code asks (GcodeActionKind::printer, see Printer codes):
// the words of the code's slots, bit k of `given` for slot k. Slots:
// M201/M203 the board's axes in order; M204 P T R S; M205 J; M73 P R;
// M220 S; M221 S. Lengths (M201 M203 M204 mm/s^2 or mm/s, M205 J mm) in
// 1/10000 mm, percent and minutes whole, T as given (0).
template <uint8_t N>
struct GcodePrinterCommand {
  GcodeCode code;  // m73 m201 m203 m204 m205 m220 m221
  uint8_t given;
  int32_t value[N > 4 ? N : 4];
};

template <uint8_t N>
struct GcodeAction {
  GcodeActionKind kind;
  uint8_t axes;              // bit i: the line named axis i
  bool rapid;                // move: G0
  bool clockwise;            // arc: G2
  uint8_t plane_axis[3];     // arc: first, second plane axis, normal (kNoAxis)
  int32_t target[N];         // machine position after the line, steps
  int32_t coord[N];          // program position after the line, 1/10000 mm
  int32_t feed;              // move/arc: 1/10000 mm/min
  int32_t centre[2];         // arc: centre - start, steps
  int32_t centre_length[2];  // arc: centre - start, 1/10000 mm
  int32_t radius;            // arc: 1/10000 mm
  uint32_t dwell_ms;         // dwell
  uint8_t mode[N];           // set_mode: M350 mode per named axis
  union {
    GcodeHeaterCommand heater;        // heater
    GcodePrinterCommand<N> printer;  // printer
  };
};

namespace gcode_detail {

// The plane's axis letters: first | second << 8 | normal << 16.
inline uint32_t plane_axes(Plane p) {
  return p == Plane::xy   ? 'X' | uint32_t('Y') << 8 | uint32_t('Z') << 16
         : p == Plane::zx ? 'Z' | uint32_t('X') << 8 | uint32_t('Y') << 16
                          : 'Y' | uint32_t('Z') << 8 | uint32_t('X') << 16;
}

// The plane's offset letters: first | second << 8.
inline uint16_t plane_offsets(Plane p) {
  return p == Plane::xy   ? uint16_t('I' | 'J' << 8)
         : p == Plane::zx ? uint16_t('K' | 'I' << 8)
                          : uint16_t('J' | 'K' << 8);
}

}  // namespace gcode_detail

}  // namespace am
