#include "step_engine.h"

#include <avr/interrupt.h>

#include "../../hal/avr/step_timer.h"
#include "../board.h"

// Read and written by the assembly fast path below, hence C names.
extern "C" {
volatile uint16_t step_remaining;  // steps left in the current segment
volatile uint8_t step_fast;        // the fast path may take the next match
volatile uint8_t step_armed;       // the next match raises the timer-pulsed STEP
}

namespace engine {
namespace {

constexpr uint8_t kTimerAxes = board::Axes::timer_mask;

am::StepQueue<kQueueSize> queue;
volatile bool running;

// The segment being executed, copied out of the queue so the interrupt reads
// fixed addresses instead of indexing the ring on every step. (`remaining`
// and the fast-path flag live outside: the assembly fast path names them.)
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
  step_remaining = s.count;
  compare = s.compare;
  wrap_compare = s.wrap_compare;
  wraps = s.wraps;
  axes = s.axes;
  dirs = s.dirs;
  board::Axes::set_direction(axes, dirs);
  wraps_left = wraps;
  // The fast path handles a match only when all it has to do is end the
  // timer pulse, re-arm it and count: a segment of the timer-pulsed axis
  // alone, one timer period per step.
  step_fast = kTimerAxes != 0 && axes == kTimerAxes && wraps == 0;
  return wraps ? wrap_compare : compare;
}

// Arms the hardware pulse when the period just programmed ends in a step of
// the timer-pulsed axis. Compiles to nothing on boards without one.
inline void arm_if_step_period() {
  if (!kTimerAxes) return;
  step_armed = wraps_left == 0 && (axes & kTimerAxes);
  if (step_armed) hal::step_timer::arm_pulse();
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
    const uint16_t first = load_front();
    arm_if_step_period();
    hal::step_timer::start(first);
  }
  return true;
}

}  // namespace engine

// The compare-A vector. Steady cruise of the timer-pulsed axis is the hot
// path and is written in assembly: ending the pulse, re-arming it and counting
// take about 50 cycles including the interrupt response and RETI, where a C handler
// would spend more than that saving and restoring the 17 registers its calls
// may clobber. Every other case (segment end, long intervals, software-pulsed
// axes) restores the two registers it used and jumps to the C handler, which
// then runs exactly as if it were the vector.
ISR(TIMER1_COMPA_vect, ISR_NAKED) {
  asm volatile(
      "push r24\n\t"
      "in r24, __SREG__\n\t"
      "push r24\n\t"
      // A match that raised STEP: end the pulse now, whatever comes next.
      "lds r24, step_armed\n\t"
      "tst r24\n\t"
      "breq 3f\n\t"
      "ldi r24, %[clear]\n\t"
      "sts %[tccr1a], r24\n\t"
      "ldi r24, %[force]\n\t"
      "sts %[force_reg], r24\n\t"
      "3:\n\t"
      "lds r24, step_fast\n\t"
      "tst r24\n\t"
      "breq 1f\n\t"
      // The last step of a segment goes to the C handler (remaining == 1).
      "lds r24, step_remaining\n\t"
      "cpi r24, 1\n\t"
      "brne 2f\n\t"
      "lds r24, step_remaining+1\n\t"
      "tst r24\n\t"
      "breq 1f\n\t"
      "2:\n\t"
      "ldi r24, %[set]\n\t"
      "sts %[tccr1a], r24\n\t"
      "lds r24, step_remaining\n\t"
      "subi r24, 1\n\t"
      "sts step_remaining, r24\n\t"
      "lds r24, step_remaining+1\n\t"
      "sbci r24, 0\n\t"
      "sts step_remaining+1, r24\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "reti\n\t"
      "1:\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "jmp __vector_step_slow\n\t" ::[tccr1a] "n"(_SFR_MEM_ADDR(TCCR1A)),
      [force_reg] "n"(_SFR_MEM_ADDR(HAL_FORCE_OC1A_REG)), [force] "n"(HAL_FORCE_OC1A_VALUE),
      [clear] "n"(hal::step_timer::kOc1aClear), [set] "n"(hal::step_timer::kOc1aSet));
}

// The general handler: one more period of a long interval, or a step of any
// axis. A timer-pulsed axis has had its whole pulse already (the match raised
// it, the vector above ended it). For the other axes everything before
// pulse_begin is the same on every step, so their edges trail the match by a
// constant number of cycles; their step lines stay high for the bookkeeping
// plus the board's pad, which together meet the drivers' minimum pulse width.
// (Named __vector_* so avr-gcc accepts the signal attribute: a full interrupt
// prologue and a RETI, entered by the jump above.)
extern "C" void __vector_step_slow() __attribute__((signal, used, externally_visible));
void __vector_step_slow() {
  using namespace engine;
  if (wraps_left) {
    if (--wraps_left == 0) {
      hal::step_timer::set_compare(compare);
      arm_if_step_period();
    }
    return;
  }
  board::Axes::pulse_begin(axes, dirs);
  if (--step_remaining != 0) {
    wraps_left = wraps;
    hal::step_timer::set_compare(wraps ? wrap_compare : compare);
    arm_if_step_period();
    __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
    board::Axes::pulse_end(axes);
    return;
  }
  __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
  board::Axes::pulse_end(axes);
  queue.pop();
  if (queue.empty()) {
    hal::step_timer::stop();
    step_fast = 0;
    step_armed = 0;
    running = false;
    return;
  }
  hal::step_timer::set_compare(load_front());
  arm_if_step_period();
}
