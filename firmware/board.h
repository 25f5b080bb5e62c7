// The board this image is built for. CMake passes the header of one board
// (firmware/boards/<name>.h) as AVRMOTION_BOARD_HEADER; nothing else in the
// firmware names a board.
#pragma once
#include <stdint.h>

// The line protocol's style (docs/protocol.md): grbl 1.1 for CNC senders,
// Marlin for printer hosts. The board constant `kProtocol` is the image's
// style; an image holds one style only (the compiler drops the other's
// code: both do not fit beside a printer's codes in 32 KB), except where
// the board sets `kProtocolSwitch` (the m32-direct): both styles are then
// in the image and the settings' `$200` chooses at run time, `kProtocol`
// being its default.
enum class Protocol : uint8_t { grbl, marlin };

#include AVRMOTION_BOARD_HEADER

#include "axes/endstops.h"

// What a board header may leave out. A board's own declaration wins:
// `board::kHeater` finds the board's name first and looks into the namespaces
// `board` uses only when the board has none (qualified lookup).
namespace board_defaults {
constexpr bool kGcode = false;  // the line protocol takes G-code (docs/gcode.md)
constexpr bool kHeater = false;  // no heater service, heater M-codes refused
struct Heater;  // a heater's wiring (firmware/boards/m32.h), only with kHeater
// With a heater: M303's relay autotune (about 1.9 KB of flash), and the
// printer codes a slicer's file carries (M73 progress, M117 message, the
// M201/M203/M204/M205 machine limits, M220 feed and M221 flow overrides:
// firmware/services/printer_codes.h, about 2 KB). The m32 has room for one
// of the two: the Marlin printer (m32) takes the printer codes, the grbl
// printer (m32-grbl) the autotune (docs/boards.md).
constexpr bool kAutotune = true;
constexpr bool kPrinterCodes = false;
// Firmware retraction (core/text/gcode_retraction.h): G10/G11 and their
// settings M207/M208, about 0.6 KB; the grbl printer's (m32-grbl): the
// Marlin printer's flash is full.
constexpr bool kFirmwareRetract = false;
// The odometer (firmware/engine/odometer.h, about 1 KB of flash): M114
// counts where the motors are while they move. Without it, where the
// queued motion ends (Marlin's logical position).
constexpr bool kOdometer = true;
// grbl's realtime bytes (firmware/apps/cnc/realtime.h): `?` status, `!`
// feed hold, `~` resume, Ctrl-X soft reset, taken in the receive interrupt
// and never put into a line.
constexpr bool kRealtime = false;
constexpr Protocol kProtocol = Protocol::grbl;
// Both styles in the image, chosen by the setting `$200` (stored in the
// EEPROM, applied at boot; kProtocol the default): only with kSettings
// (docs/protocol.md, "Choosing the style at run time"). Without it the
// style is the constant and reply::marlin() folds at compile time.
constexpr bool kProtocolSwitch = false;
// The direct controls MOVE, POS, WAIT, RELEASE, MODE (docs/protocol.md)
// beside G-code; about 2 KB of flash.
constexpr bool kCommands = true;
// Endstops (firmware/axes/endstops.h): none, so no hard limits. kHoming
// links the homing service (G28, firmware/services/homing.h) beside them;
// kHomingSettings (one HomingAxis per endstop) is then the board's own.
using Endstops = EndstopSet<AxisSet<>, false>;
constexpr bool kHoming = false;
constexpr HomingSettings<1> kHomingSettings = {};
// The machine settings in the EEPROM (firmware/services/settings.h,
// docs/settings.md): steps/mm, rates, accelerations, junction deviation,
// homing and limits, `$$` and `$N=value` (grbl) or M500..M503 (Marlin).
// Only for boards whose axes are all step/dir (one position unit a step).
constexpr bool kSettings = false;
// With settings: the pin polarities among them, grbl's $3 (direction
// invert mask: each segment's direction lines flipped for its axes) and,
// with endstops, $5 (the switches read inverted: normally-closed ones). The
// step interrupt reads both from RAM: an LDS and an EOR, 3 cycles, on a
// step event that watches a switch and on a segment's load.
constexpr bool kPinPolarities = false;
// The lathe program's operator panel (firmware/apps/lathe/operator.h) in
// place of its UART front end; with kApproximateRatios, a thread whose ratio
// the follower cannot hold exactly is cut at the nearest one it can (the
// continued fraction of core/lathe/ratio.h, about 1.6 KB) and its error
// shown, instead of refused.
constexpr bool kOperatorPanel = false;
constexpr bool kApproximateRatios = false;
// A lathe's spindle encoder and limit switch (firmware/boards/m16-lathe.h),
// named in the descriptor for the simulator.
constexpr bool kSpindleEncoder = false;
struct SpindlePins;  // A, B, Index, Limit: only with kSpindleEncoder
// The lathe's leadscrew driven by a DC servo (firmware/boards/m16-servo.h)
// instead of a stepper; its pins named in the descriptor for the simulator.
constexpr bool kServoLeadscrew = false;
struct ServoPins;   // Pwm, In1, In2, Encoder: only with kServoLeadscrew
struct ServoMotor;  // kPulses, kGearbox, kGains: only with kServoLeadscrew
}  // namespace board_defaults
namespace board {
using namespace board_defaults;
}  // namespace board

// The style is chosen by a setting, so a board that switches styles keeps
// the settings.
static_assert(!board::kProtocolSwitch || board::kSettings, "kProtocolSwitch needs kSettings ($200)");
static_assert(!board::kPinPolarities || board::kSettings, "kPinPolarities needs kSettings ($3, $5)");

// Every board lists its hardware claims; completing the type runs their
// compile-time checks (hal/avr/claims.h).
static_assert(sizeof(board::Claims) > 0, "board::Claims");
