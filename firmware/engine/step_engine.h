// The step engine: turns queued StepSegments into step pulses, timed by
// Timer1 in CTC mode (hal/avr/step_timer.h).
//
// Contract
//   The main loop pushes segments with push() (false = queue full, try again
//   later) and never touches the timer. start() sets an idle engine going on
//   what has been queued (the planner fills the queue first, so a move's first
//   steps never wait for the planner); the engine stops itself when the queue
//   runs dry. busy() is true while steps remain. The interrupt only pops segments; it never
//   computes a ramp: that happens in the planner, outside interrupt context.
//   On a board with endstops every step event first reads the switches its
//   segment runs toward and stops the engine at a closed one (hard limits,
//   homing: firmware/engine/limits.h).
//
// Why it is built this way
//   The timer, not software, measures every interval: the compare match fires
//   exactly `interval` cycles after the previous one, whatever the interrupt
//   latency was, so latency can delay a software pulse by a few cycles but
//   can never accumulate into the schedule; a timer-pulsed axis (OC1A) has its
//   edge made by the match itself. Intervals longer than the 16-bit timer are
//   split by the planner into equal periods of at least 32768 ticks, and the
//   interrupt merely counts them, so it needs no 32-bit arithmetic. Every
//   period must outlast the interrupt path that programs the next one: the
//   axes' rate limits (protocol.cpp) keep step intervals above it. The
//   timer-pulsed axis's cruise runs in an assembly fast path that also
//   switches segments by itself: the compare-A vector, in its own file
//   firmware/engine/step_vector.S, which jumps to the C handlers in
//   step_engine.cpp for everything else (docs/step-engine.md).
#pragma once
#include <stdint.h>

#include "../../core/motion/line_dda.h"
#include "../../core/motion/step_queue.h"
#include "../board.h"

namespace engine {

constexpr uint8_t kQueueSize = 16;

// Coordinated blocks: a segment of several axes names a block (its `block`
// byte, a serial number), and at each of its events that block's
// interpolator says which axes step. The main loop sets a block up with
// begin_block() before it pushes the block's segments; a slot is reused only
// once the interrupt has moved past every block that used it. One-axis
// segments need no block.
constexpr uint8_t kBlockRing = 4;
using Dda = am::LineDda<board::Axes::count>;
// Whether a slot is free for a new block; then begin_block() hands it out
// with the serial its segments carry.
bool block_available();
Dda* begin_block(uint8_t& serial);

// For counting positions as the interrupt steps (firmware/engine/odometer.h):
// the ring index of the segment the interrupt runs (every segment before it
// is finished; while stopped, every queued one is) and how many steps of it
// it has made, read at one instant; the ring index after the newest
// segment; a queued segment by ring index; a block's interpolator by serial.
struct Progress {
  uint8_t tail;
  uint16_t made;  // of the segment at `tail`; 0 while stopped
};
Progress progress();
uint8_t head();
const am::StepSegment& segment(uint8_t index);
const Dda& block(uint8_t serial);

void init();
// The pin polarities (board::kPinPolarities; grbl's $3 and $5): the
// direction lines of the axes in `dir_mask` (bit i: axis i) driven inverted
// from the next segment on, and the switches on the pins in `switch_pins`
// (of board::Endstops::pins) read inverted, their latches re-armed for it.
// Positions, endstops and reports keep the commanded direction.
// inverted_switches() is that pin mask.
void set_polarities(uint8_t dir_mask, uint8_t switch_pins);
uint8_t inverted_switches();
bool push(am::StepSegment segment);
void start();
bool busy();
// A step event found a switch closed that its segment ran toward
// (board::Endstops): the engine stopped before that step, its queue kept,
// and start() does nothing until clear_trip() has dropped the queue.
bool stopped_at_endstop();
void clear_trip();
bool queue_full();
// Segments queued, the running one included.
uint8_t queued();

}  // namespace engine
