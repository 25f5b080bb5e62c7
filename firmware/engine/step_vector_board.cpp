// The step vector's per-board numbers. firmware/engine/step_vector.S is
// preprocessed as C, so it cannot include the C++ board header; this file can.
// The build compiles it for each image that links the engine, with that
// image's flags, but does not link it: it copies the section
// .avrmotion_step_vector out of the object, the text of a header of
// #defines, to step_vector_board.h in the image's build folder, which the
// vector includes (firmware/CMakeLists.txt). The numbers are thus the
// compiler's own, from the same board header the C++ engine sees.
#include <stdint.h>

#include "../board.h"

namespace {

// The timer-pulsed STEP ends at the FOC strobe of the vector, 24 cycles
// after its match without padding (4 response + 3 JMP + 17 in the vector);
// the board asks for kTimerPulseCycles. Three cycles per turn of the padding
// loop. A segment's last step ends its pulse later, after the next segment's
// period is set (36 cycles after the match at the earliest, when nothing is
// chained; 51 when the next segment is): it needs no padding.
constexpr uint8_t kPulsePathCycles = 24;
constexpr uint8_t kPulsePadTurns =
    board::kTimerPulseCycles > kPulsePathCycles ? (board::kTimerPulseCycles - kPulsePathCycles + 2) / 3 : 0;
static_assert(board::kTimerPulseCycles <= 36, "the fast path's segment switch ends its pulse 36 cycles after the match");

// Whether the board has a timer-pulsed axis (engine::kTimerAxes != 0): the
// vector's fast path exists only then.
constexpr uint8_t kTimerAxis = board::Axes::timer_mask != 0 ? 1 : 0;

// Never called: its assembly only fills the section (a number operand
// prints as a plain decimal).
__attribute__((used)) void emit() {
  asm(".pushsection .avrmotion_step_vector\n\t"
      ".ascii \"/* Generated from firmware/engine/step_vector_board.cpp: do not edit. */\\n\"\n\t"
      ".ascii \"#define STEP_VECTOR_TIMER_AXIS %[timer_axis]\\n\"\n\t"
      ".ascii \"#define STEP_VECTOR_PAD_TURNS %[pad]\\n\"\n\t"
      ".popsection" ::[timer_axis] "n"(kTimerAxis),
      [pad] "n"(kPulsePadTurns));
}

}  // namespace
