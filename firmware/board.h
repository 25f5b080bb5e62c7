// The board this image is built for. CMake passes the header of one board
// (firmware/boards/<name>.h) as AVRMOTION_BOARD_HEADER; nothing else in the
// firmware names a board.
#pragma once
#include AVRMOTION_BOARD_HEADER

// What a board header may leave out. A board's own declaration wins:
// `board::kHeater` finds the board's name first and looks into the namespaces
// `board` uses only when the board has none (qualified lookup).
namespace board_defaults {
constexpr bool kHeater = false;  // no heater service, heater M-codes refused
struct Heater;  // a heater's wiring (firmware/boards/m32.h), only with kHeater
// The odometer (firmware/engine/odometer.h, about 1 KB of flash): M114
// counts where the motors are while they move. Without it, where the
// queued motion ends (Marlin's logical position).
constexpr bool kOdometer = true;
// The lathe program's operator panel (firmware/apps/lathe/operator.h) in
// place of its UART front end.
constexpr bool kOperatorPanel = false;
// A lathe's spindle encoder and limit switch (firmware/boards/m16-lathe.h),
// named in the descriptor for the simulator.
constexpr bool kSpindleEncoder = false;
struct SpindlePins;  // A, B, Index, Limit: only with kSpindleEncoder
}  // namespace board_defaults
namespace board {
using namespace board_defaults;
}  // namespace board

// Every board lists its hardware claims; completing the type runs their
// compile-time checks (hal/avr/claims.h).
static_assert(sizeof(board::Claims) > 0, "board::Claims");
