#include "step_engine.h"

#include <avr/interrupt.h>

#include "../../hal/avr/step_timer.h"
#include "../board.h"

namespace engine {
namespace {

am::StepQueue<kQueueSize> queue;
volatile bool running;

// The segment being executed, copied out of the queue so the interrupt reads
// fixed addresses instead of indexing the ring on every step.
uint16_t remaining;
uint16_t compare;
uint16_t wrap_compare;
uint8_t wraps;
uint8_t wraps_left;
uint8_t axes;
uint8_t dirs;

// Loads the queue's front segment and programs the timer for its first
// interval; returns that interval's first compare value.
inline uint16_t load_front() {
  const am::StepSegment& s = queue.front();
  remaining = s.count;
  compare = s.compare;
  wrap_compare = s.wrap_compare;
  wraps = s.wraps;
  axes = s.axes;
  dirs = s.dirs;
  board::Axes::set_direction(axes, dirs);
  wraps_left = wraps;
  return wraps ? wrap_compare : compare;
}

}  // namespace

void init() { hal::step_timer::init(); }

bool queue_full() { return queue.full(); }

bool busy() { return running || !queue.empty(); }

bool push(const am::StepSegment& segment) {
  if (!queue.push(segment)) return false;
  // The interrupt clears `running` only after it found the queue empty, so if
  // it is still set here the interrupt will see this segment.
  if (!running) {
    running = true;
    hal::step_timer::start(load_front());
  }
  return true;
}

}  // namespace engine

// One compare match: either one more 65536-tick wrap of a long interval, or a
// step. Everything on the step path before pulse_begin is the same for every
// step, so each pulse trails its compare match by a constant number of cycles.
// The step line stays high for the bookkeeping plus the board's pad, which
// together meet the drivers' minimum pulse width (docs/step-engine.md).
ISR(TIMER1_COMPA_vect) {
  using namespace engine;
  if (wraps_left) {
    if (--wraps_left == 0) hal::step_timer::set_compare(compare);
    return;
  }
  board::Axes::pulse_begin(axes, dirs);
  if (--remaining != 0) {
    wraps_left = wraps;
    hal::step_timer::set_compare(wraps ? wrap_compare : compare);
    __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
    board::Axes::pulse_end(axes);
    return;
  }
  __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
  board::Axes::pulse_end(axes);
  queue.pop();
  if (queue.empty()) {
    hal::step_timer::stop();
    running = false;
    return;
  }
  hal::step_timer::set_compare(load_front());
}
