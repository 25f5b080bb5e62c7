#include "step_engine.h"

#include <avr/interrupt.h>
#include <stddef.h>

#include "../../hal/avr/step_timer.h"
#include "../board.h"

namespace engine {
namespace {

constexpr uint8_t kTimerAxes = board::Axes::timer_mask;
using Queue = am::StepQueue<kQueueSize>;

// The timer-pulsed STEP ends at the FOC strobe below, 20 cycles after its
// match without padding (4 response + 3 JMP + 13 in the vector); the board
// asks for kTimerPulseCycles. Three cycles per turn of the padding loop.
constexpr uint8_t kPulsePathCycles = 20;
constexpr uint8_t kPulsePadTurns =
    board::kTimerPulseCycles > kPulsePathCycles ? (board::kTimerPulseCycles - kPulsePathCycles + 2) / 3 : 0;

// The layout facts the assembly below relies on.
static_assert(offsetof(am::StepSegment, count) == 0, "segment layout");
static_assert(offsetof(am::StepSegment, compare) == 2, "segment layout");
static_assert(offsetof(am::StepSegment, wraps) == 6, "segment layout");
static_assert(offsetof(am::StepSegment, axes) == 7, "segment layout");
static_assert(offsetof(am::StepSegment, dirs) == 8, "segment layout");
static_assert(sizeof(am::StepSegment) == 9, "segment layout: the fast path multiplies by 9");
static_assert(Queue::slots_offset() == 0, "queue layout");

}  // namespace
}  // namespace engine

// Shared with the assembly fast path, hence assembler names.
engine::Queue step_queue asm("step_queue");
volatile uint16_t step_remaining asm("step_remaining");  // steps left in the current segment
volatile uint16_t step_compare asm("step_compare");      // its (final-period) compare value
volatile uint8_t step_dirs asm("step_dirs");             // its direction bits
volatile uint8_t step_fast asm("step_fast");             // the fast path may take the next match
volatile uint8_t step_armed asm("step_armed");           // the next match raises the timer STEP

namespace engine {
namespace {

volatile bool running;

// The rest of the segment being executed, copied out of the queue so the
// C handler reads fixed addresses instead of indexing the ring.
uint16_t wrap_compare;
uint8_t wraps;
uint8_t wraps_left;
uint8_t axes;

// A segment the fast path can run and switch to by itself: the timer-pulsed
// axis alone, one timer period per step.
inline bool fast_eligible(const am::StepSegment& s) {
  return kTimerAxes != 0 && s.axes == kTimerAxes && s.wraps == 0;
}

// Programs the first timer period of a segment: the hardware pulse if that
// period ends in a step of the timer-pulsed axis, and its compare value.
// This comes before anything else at a segment change, because at 150 kHz
// the new period's match is barely 100 cycles away.
// Arms the hardware pulse for the period just programmed, or leaves OC1A to
// "clear" (rewritten only when that changes the state).
inline void set_armed(bool armed) {
  if (armed) hal::step_timer::arm_pulse();
  else if (step_armed) hal::step_timer::disarm_pulse();
  step_armed = armed;
}

inline uint16_t first_period(const am::StepSegment& s) {
  if (kTimerAxes) set_armed(s.wraps == 0 && (s.axes & kTimerAxes));
  return s.wraps ? s.wrap_compare : s.compare;
}

// Copies the queue's front segment into the fields the interrupt reads and
// sets its directions. Directions change only where a move starts from rest,
// whose first interval is long, so setting them after the period has been
// programmed still leaves the drivers their set-up time.
inline void load_front(const am::StepSegment& s) {
  step_remaining = s.count;
  step_compare = s.compare;
  wrap_compare = s.wrap_compare;
  wraps = s.wraps;
  wraps_left = wraps;
  axes = s.axes;
  step_dirs = s.dirs;
  step_fast = fast_eligible(s);
  board::Axes::set_direction(s.axes, s.dirs);
}

// The queue ran dry: stop the clock first (a pulse may be armed), then reset.
inline void stop_engine() {
  hal::step_timer::stop();
  if (kTimerAxes) hal::step_timer::disarm_pulse();
  step_fast = 0;
  step_armed = 0;
  running = false;
}

// The current segment is done: on to the next one, programming its first
// period before anything else, or stop if there is none.
inline void next_segment() {
  const am::StepSegment* s = step_queue.pop_and_front();
  if (!s) {
    stop_engine();
    return;
  }
  hal::step_timer::set_compare(first_period(*s));
  load_front(*s);
}

// Arms the hardware pulse when the period just programmed ends in a step of
// the timer-pulsed axis. Compiles to nothing on boards without one.
inline void arm_if_step_period() {
  if (kTimerAxes) set_armed(wraps_left == 0 && (axes & kTimerAxes));
}

}  // namespace

void init() { hal::step_timer::init(); }

bool queue_full() { return step_queue.full(); }

bool busy() { return running || !step_queue.empty(); }

bool push(const am::StepSegment& segment) {
  if (!step_queue.push(segment)) return false;
  // The interrupt clears `running` only after it found the queue empty, so if
  // it is still set here the interrupt will see this segment.
  if (!running) {
    running = true;
    const am::StepSegment& s = step_queue.front();
    const uint16_t first = first_period(s);
    load_front(s);
    hal::step_timer::start(first);
  }
  return true;
}

}  // namespace engine

// The compare-A vector. Steady cruise of the timer-pulsed axis is the hot
// path and is written in assembly: ending the pulse (after the board's pulse
// width), re-arming it and counting take 54 cycles plus the padding,
// including the interrupt response and RETI, where a C
// handler would spend more than that saving and restoring the 17 registers
// its calls may clobber. At a segment's last step it reads the next segment
// straight from the ring and, if that one continues the same axis in the
// same direction with no long interval, switches to it in about 40 more
// cycles (at 150 kHz the next match is only 107 cycles away). Every other
// case restores the registers it used and jumps to a C handler, which then
// runs exactly as if it were the vector.
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
      ".if %[pad]\n\t"
      "ldi r24, %[pad]\n\t"
      "9: dec r24\n\t"
      "brne 9b\n\t"
      ".endif\n\t"
      "ldi r24, %[force]\n\t"
      "sts %[force_reg], r24\n\t"
      "3:\n\t"
      "lds r24, step_fast\n\t"
      "tst r24\n\t"
      "brne 8f\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "jmp __vector_step_slow\n\t"
      "8:\n\t"
      "lds r24, step_remaining\n\t"
      "cpi r24, 1\n\t"
      "brne 2f\n\t"
      "lds r24, step_remaining+1\n\t"
      "tst r24\n\t"
      "breq 4f\n\t"
      // Another step of this segment: re-arm and count.
      "2:\n\t"
      "ldi r24, %[set]\n\t"
      "sts %[tccr1a], r24\n\t"
      "lds r24, step_remaining\n\t"
      "subi r24, 1\n\t"
      "sts step_remaining, r24\n\t"
      "lds r24, step_remaining+1\n\t"
      "sbci r24, 0\n\t"
      "sts step_remaining+1, r24\n\t"
      "5:\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "reti\n\t"
      // The segment's last step. Arm the next pulse at once: a fast segment
      // is followed by more steps of the same axis (moves end at rest, with
      // long intervals), and the C handler disarms in the rare other case
      // long before a slow interval ends.
      "4:\n\t"
      "ldi r24, %[set]\n\t"
      "sts %[tccr1a], r24\n\t"
      "push r23\n\t"
      "push r25\n\t"
      "push r30\n\t"
      "push r31\n\t"
      "lds r24, step_queue+%[tail]\n\t"
      "subi r24, 0xFF\n\t"  // r24 = index of the next segment
      "lds r25, step_queue+%[head]\n\t"
      "cp r24, r25\n\t"
      "breq 7f\n\t"
      "mov r30, r24\n\t"
      "andi r30, %[mask]\n\t"
      "mov r25, r30\n\t"
      "lsl r30\n\t"
      "lsl r30\n\t"
      "lsl r30\n\t"
      "add r30, r25\n\t"  // slot * 9 (<= 135)
      "ldi r31, 0\n\t"
      "subi r30, lo8(-(step_queue))\n\t"
      "sbci r31, hi8(-(step_queue))\n\t"
      "ldd r25, Z+6\n\t"  // wraps == 0
      "tst r25\n\t"
      "brne 7f\n\t"
      "ldd r25, Z+7\n\t"  // axes == the timer-pulsed axis alone
      "cpi r25, %[timer_axes]\n\t"
      "brne 7f\n\t"
      "ldd r25, Z+8\n\t"  // same direction
      "lds r23, step_dirs\n\t"
      "cp r25, r23\n\t"
      "brne 7f\n\t"
      "ldd r25, Z+3\n\t"
      "sts %[ocr1ah], r25\n\t"
      "sts step_compare+1, r25\n\t"
      "ldd r25, Z+2\n\t"
      "sts %[ocr1al], r25\n\t"
      "sts step_compare, r25\n\t"
      "ldd r25, Z+0\n\t"
      "sts step_remaining, r25\n\t"
      "ldd r25, Z+1\n\t"
      "sts step_remaining+1, r25\n\t"
      "sts step_queue+%[tail], r24\n\t"  // pop the finished segment
      "pop r31\n\t"
      "pop r30\n\t"
      "pop r25\n\t"
      "pop r23\n\t"
      "rjmp 5b\n\t"
      "7:\n\t"
      "pop r31\n\t"
      "pop r30\n\t"
      "pop r25\n\t"
      "pop r23\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "jmp __vector_step_switch\n\t" ::[tccr1a] "n"(_SFR_MEM_ADDR(TCCR1A)),
      [ocr1ah] "n"(_SFR_MEM_ADDR(OCR1AH)), [ocr1al] "n"(_SFR_MEM_ADDR(OCR1AL)),
      [force_reg] "n"(_SFR_MEM_ADDR(HAL_FORCE_OC1A_REG)), [force] "n"(HAL_FORCE_OC1A_VALUE),
      [clear] "n"(hal::step_timer::kOc1aClear), [set] "n"(hal::step_timer::kOc1aSet),
      [head] "n"(engine::Queue::head_offset()), [tail] "n"(engine::Queue::tail_offset()),
      [mask] "n"(engine::kQueueSize - 1), [timer_axes] "n"(engine::kTimerAxes),
      [pad] "n"(engine::kPulsePadTurns));
}

// The end of a timer-only segment that the vector could not continue: the
// queue holds nothing more (a stop, or the planner fell behind) or the next
// segment is of another kind. The next pulse is already armed, so one thing
// is urgent: the stop, or the new compare value, must land before the old
// compare matches again, about 100 cycles away at 150 kHz. No software pulses
// and no calls here, so the prologue saves few registers.
extern "C" void __vector_step_switch() __attribute__((signal, used, externally_visible));
void __vector_step_switch() { engine::next_segment(); }

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
      hal::step_timer::set_compare(step_compare);
      arm_if_step_period();
    }
    return;
  }
  board::Axes::pulse_begin(axes, step_dirs);
  if (--step_remaining != 0) {
    wraps_left = wraps;
    hal::step_timer::set_compare(wraps ? wrap_compare : step_compare);
    arm_if_step_period();
    __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
    board::Axes::pulse_end(axes);
    return;
  }
  __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
  board::Axes::pulse_end(axes);
  next_segment();
}
