#include "step_engine.h"

#include <avr/interrupt.h>
#include <stddef.h>

#include "../../hal/avr/step_timer.h"
#include "../board.h"

static_assert(board::kStepClock == hal::claim::timer1, "the step engine runs on Timer1: the board must claim it");

namespace engine {
namespace {

constexpr uint8_t kTimerAxes = board::Axes::timer_mask;
using Queue = am::StepQueue<kQueueSize>;

// The timer-pulsed STEP ends at the FOC strobe below, 24 cycles after its
// match without padding (4 response + 3 JMP + 17 in the vector); the board
// asks for kTimerPulseCycles. Three cycles per turn of the padding loop. A
// segment's last step ends its pulse later, after the next segment's
// period is set (36 cycles after the match at the earliest, when nothing is
// chained; 51 when the next segment is): it needs no padding.
constexpr uint8_t kPulsePathCycles = 24;
constexpr uint8_t kPulsePadTurns =
    board::kTimerPulseCycles > kPulsePathCycles ? (board::kTimerPulseCycles - kPulsePathCycles + 2) / 3 : 0;
static_assert(board::kTimerPulseCycles <= 36, "the fast path's segment switch ends its pulse 36 cycles after the match");

// The layout facts the assembly below relies on.
static_assert(offsetof(am::StepSegment, count) == 0, "segment layout");
static_assert(offsetof(am::StepSegment, compare) == 2, "segment layout");
static_assert(offsetof(am::StepSegment, chain) == 9, "segment layout");
static_assert(sizeof(am::StepSegment) == 11, "segment layout");
static_assert(kBlockRing == 4, "block_slot lists four slots");
static_assert(Queue::slots_offset() == 0, "queue layout");

}  // namespace
}  // namespace engine

// Shared with the assembly fast path, hence assembler names.
engine::Queue step_queue asm("step_queue");
// Steps of the current segment after the one the next match makes.
volatile uint16_t step_remaining asm("step_remaining");
volatile uint8_t step_dirs asm("step_dirs");  // the current segment's direction bits
// Who takes the next match: 0 a C handler; 1 the fast path, a step with
// more to follow; 2 the fast path, the segment's last step.
volatile uint8_t step_fast asm("step_fast");
// Which C handler: the segment's axes step together as its block says.
volatile uint8_t step_coordinated asm("step_coordinated");
volatile uint8_t step_armed asm("step_armed");  // the next match raises the timer STEP
// The ring index after the current segment and its slot, kept ready so the
// fast path's segment switch reads no index arithmetic before its compare.
volatile uint8_t step_next_index asm("step_next_index");
const am::StepSegment* volatile step_next asm("step_next");

namespace engine {
namespace {

volatile bool running;
// The step interrupt stopped at an endstop (hard limit, homing): the queue
// stays as it was until clear_trip().
volatile bool tripped;
// The pins and edge latches of the endstops the current segment runs
// toward (board::Endstops::watch): each step event of it first checks them.
uint8_t endstop_watch, endstop_latches;

// The rest of the segment being executed, copied out of the queue so the
// C handler reads fixed addresses instead of indexing the ring.
uint16_t step_compare;
uint16_t wrap_compare;
uint8_t wraps;
uint8_t wraps_left;
uint8_t axes;
Dda* dda;  // the interpolator of a coordinated segment (step_coordinated)

// Block serials: the last one handed out, the one the interrupt is in.
Dda blocks[kBlockRing];
Dda* const block_slot[kBlockRing] = {&blocks[0], &blocks[1], &blocks[2], &blocks[3]};
uint8_t block_serial;
volatile uint8_t running_block;

// The last segment pushed (main loop only), for the chain mark.
uint8_t pushed_axes;
uint8_t pushed_dirs;

// A segment the fast path can run: the timer-pulsed axis alone, one timer
// period per step.
inline bool fast_eligible(const am::StepSegment& s) {
  return kTimerAxes != 0 && s.axes == kTimerAxes && s.wraps == 0;
}

// Arms the hardware pulse for the period just programmed, or leaves OC1A to
// "clear" (rewritten only when that changes the state).
inline void set_armed(bool armed) {
  if (armed) hal::step_timer::arm_pulse();
  else if (step_armed) hal::step_timer::disarm_pulse();
  step_armed = armed;
}

// Programs the first timer period of a segment: the hardware pulse if that
// period ends in a step of the timer-pulsed axis, and its compare value.
inline uint16_t first_period(const am::StepSegment& s) {
  if (kTimerAxes) set_armed(s.wraps == 0 && (s.axes & kTimerAxes));
  return s.wraps ? s.wrap_compare : s.compare;
}

// Points the fast path's look-ahead at the segment after the front `s`
// (no index arithmetic: a multiplication here would cost the C handlers
// registers on every step).
inline void track_next(const am::StepSegment& s) {
  step_next_index = uint8_t(step_queue.tail() + 1);
  const am::StepSegment* next = &s + 1;
  step_next = next == step_queue.slot(0) + kQueueSize ? step_queue.slot(0) : next;
}

// Copies the queue's front segment into the fields the interrupt reads and
// sets its directions. Directions change only where a move starts from rest,
// whose first interval is long, so setting them after the period has been
// programmed still leaves the drivers their set-up time.
__attribute__((noinline)) void load_front(const am::StepSegment& s) {
  step_coordinated = (s.axes & (s.axes - 1)) != 0;
  if (step_coordinated) {
    running_block = s.block;
    dda = block_slot[s.block & (kBlockRing - 1)];
  }
  step_remaining = uint16_t(s.count - 1);
  step_compare = s.compare;
  wrap_compare = s.wrap_compare;
  wraps = s.wraps;
  wraps_left = wraps;
  axes = s.axes;
  step_dirs = s.dirs;
  step_fast = fast_eligible(s) ? (s.count == 1 ? 2 : 1) : 0;
  board::Axes::set_direction(s.axes, s.dirs);
  if (board::Endstops::count) {
    endstop_watch = board::Endstops::watch(s.axes, s.dirs);
    endstop_latches = board::Endstops::watch_latches(s.axes, s.dirs);
  }
  track_next(s);
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
__attribute__((noinline)) void next_segment() {
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

uint8_t queued() { return step_queue.size(); }

bool block_available() {
  // In use: the running block and every later one already handed out.
  return !busy() || uint8_t(block_serial + 1 - running_block) < kBlockRing;
}

Dda* begin_block(uint8_t& serial) {
  const uint8_t next = uint8_t(block_serial + 1);
  block_serial = next;
  serial = next;
  return &blocks[next & (kBlockRing - 1)];
}

bool busy() { return running || !step_queue.empty(); }

bool stopped_at_endstop() { return tripped; }

void clear_trip() {
  while (!step_queue.empty()) step_queue.pop();
  tripped = false;
}

__attribute__((optimize("Os"))) Progress progress() {
  // No lock: the Uno's 160 kHz fast path has no cycles to spare for one.
  // Read again when a segment ended or step_remaining changed meanwhile.
  for (;;) {
    const uint8_t tail = step_queue.tail();
    const bool run = running;
    const uint16_t remaining = step_remaining;
    if (tail != step_queue.tail() || remaining != step_remaining) continue;
    return Progress{tail, run ? uint16_t(step_queue.slot(tail)->count - 1u - remaining) : uint16_t(0)};
  }
}

uint8_t head() { return step_queue.head(); }

const am::StepSegment& segment(uint8_t index) { return *step_queue.slot(index); }

const Dda& block(uint8_t serial) { return blocks[serial & (kBlockRing - 1)]; }

// Main-loop functions: built for size in this -O2 file.
__attribute__((optimize("Os"))) bool push(am::StepSegment segment) {
  if (step_queue.full()) return false;
  // The fast path switches to a segment by itself only where it continues
  // the one before it: same (timer-pulsed) axis, same direction.
  segment.chain = fast_eligible(segment) && segment.axes == pushed_axes && segment.dirs == pushed_dirs;
  pushed_axes = segment.axes;
  pushed_dirs = segment.dirs;
  step_queue.push(segment);
  return true;
}

__attribute__((optimize("Os"))) void start() {
  // The interrupt clears `running` only after it found the queue empty, so if
  // it is still set here the interrupt will see every segment pushed.
  if (running || tripped || step_queue.empty()) return;
  running = true;
  const am::StepSegment& s = step_queue.front();
  const uint16_t first = first_period(s);
  load_front(s);
  hal::step_timer::start(first);
}

}  // namespace engine

// The compare-A vector. Cycle counts are from the match: 4 of interrupt
// response and 3 of the vector table's JMP come first. Steady cruise of the
// timer-pulsed axis is the hot path and is written in assembly: ending the
// pulse (after the board's pulse width), re-arming it and counting, where a
// C handler would spend more than that saving and restoring the 17 registers
// its calls may clobber. At a segment's last step it takes the next segment
// straight from the ring if that one is marked `chain` (it continues the same
// axis in the same direction with no long interval): the new compare lands
// 45 cycles after the match, 60 before the next match at 160 kHz, and only
// then does the step's pulse end (51 cycles: no padding), so the whole
// switch takes about 96 cycles. The trapezoid's parts can be one step long
// (two of them back to back at a run's end), and a switch that took longer
// than the interval would start the next one late until a compare is
// missed: a step the pins never make. Every other case ends the pulse,
// restores the registers it used and jumps to a C handler, which then runs
// exactly as if it were the vector.
ISR(TIMER1_COMPA_vect, ISR_NAKED) {
  asm volatile(
      "push r24\n\t"                    // 2   9
      "in r24, __SREG__\n\t"            // 1  10
      "push r24\n\t"                    // 2  12
      ".if %[timer_axis]\n\t"            //    (a board without one has no fast path)
      "lds r24, step_fast\n\t"          // 2  14
      "cpi r24, 2\n\t"                  // 1  15
      "breq 4f\n\t"                     // 1 / 2 taken (17): the segment's last step
      ".endif\n\t"
      // A match that raised STEP: end the pulse now, whatever comes next.
      "lds r24, step_armed\n\t"         // 2  18
      "tst r24\n\t"                     // 1  19
      "breq 3f\n\t"                     // 1  20
      "ldi r24, %[clear]\n\t"           // 1  21
      "sts %[tccr1a], r24\n\t"          // 2  23
      ".if %[pad]\n\t"
      "ldi r24, %[pad]\n\t"             // 1
      "9: dec r24\n\t"                  // 1
      "brne 9b\n\t"                     // 2, 1 on the last turn: 3 per turn
      ".endif\n\t"
      "ldi r24, %[force]\n\t"           // 1
      "sts %[force_reg], r24\n\t"       // 2  26 + 3 pad: the pulse ends (38 on the Uno)
      "3:\n\t"
      "lds r24, step_fast\n\t"          // 2
      "cpi r24, 1\n\t"                  // 1
      "breq 2f\n\t"                     // 1 / 2 taken: a step with more to follow
      "lds r24, step_coordinated\n\t"
      "tst r24\n\t"
      "brne 6f\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "jmp __vector_step_slow\n\t"
      "6:\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "jmp __vector_step_coordinated\n\t"
      // Another step of this segment follows: re-arm and count.
      "2:\n\t"
      "ldi r24, %[set]\n\t"             // 1
      "sts %[tccr1a], r24\n\t"          // 2
      "lds r24, step_remaining\n\t"     // 2
      "subi r24, 1\n\t"                 // 1
      "sts step_remaining, r24\n\t"     // 2
      "lds r24, step_remaining+1\n\t"   // 2
      "sbci r24, 0\n\t"                 // 1  Z: the 16-bit result is 0
      "sts step_remaining+1, r24\n\t"   // 2
      "brne 5f\n\t"                     // 1 / 2
      "ldi r24, 2\n\t"                  // 1  the next match is the last step
      "sts step_fast, r24\n\t"          // 2
      "5:\n\t"
      "pop r24\n\t"                     // 2
      "out __SREG__, r24\n\t"           // 1
      "pop r24\n\t"                     // 2
      "reti\n\t"                        // 4
      // The segment's last step; its pulse is high.
      "4:\n\t"
      "push r25\n\t"                    // 2  19
      "push r30\n\t"                    // 2  21
      "push r31\n\t"                    // 2  23
      "lds r24, step_next_index\n\t"    // 2  25
      "lds r25, step_queue+%[head]\n\t" // 2  27
      "cp r24, r25\n\t"                 // 1  28
      "breq 7f\n\t"                     // 1  29  nothing queued (2, 30)
      "lds r30, step_next\n\t"          // 2  31
      "lds r31, step_next+1\n\t"        // 2  33
      "ldd r25, Z+9\n\t"                // 2  35  chain
      "tst r25\n\t"                     // 1  36
      "breq 7f\n\t"                     // 1  37  (2, 38)
      "ldd r25, Z+3\n\t"                // 2  39
      "sts %[ocr1ah], r25\n\t"          // 2  41
      "ldd r25, Z+2\n\t"                // 2  43
      "sts %[ocr1al], r25\n\t"          // 2  45  the new period is set
      "ldi r25, %[clear]\n\t"           // 1  46
      "sts %[tccr1a], r25\n\t"          // 2  48
      "ldi r25, %[force]\n\t"           // 1  49
      "sts %[force_reg], r25\n\t"       // 2  51  the pulse ends
      "ldi r25, %[set]\n\t"             // 1
      "sts %[tccr1a], r25\n\t"          // 2  the next one is armed
      "sts step_queue+%[tail], r24\n\t" // 2  pop the finished segment
      "subi r24, 0xFF\n\t"              // 1
      "sts step_next_index, r24\n\t"    // 2
      "ldd r24, Z+0\n\t"                // 2
      "ldd r25, Z+1\n\t"                // 2
      "sbiw r24, 1\n\t"                 // 2  count - 1, Z: a one-step segment
      "sts step_remaining, r24\n\t"     // 2
      "sts step_remaining+1, r25\n\t"   // 2
      "ldi r24, 1\n\t"                  // 1
      "brne 6f\n\t"                     // 1 / 2
      "ldi r24, 2\n\t"                  // 1
      "6:\n\t"
      "sts step_fast, r24\n\t"          // 2
      "adiw r30, %[slot]\n\t"           // 2  the slot after the new segment
      "cpi r30, lo8(step_queue+%[ring])\n\t"  // 1
      "ldi r25, hi8(step_queue+%[ring])\n\t"  // 1
      "cpc r31, r25\n\t"                // 1
      "brne 1f\n\t"                     // 1 / 2
      "ldi r30, lo8(step_queue)\n\t"    // 1
      "ldi r31, hi8(step_queue)\n\t"    // 1
      "1:\n\t"
      "sts step_next, r30\n\t"          // 2
      "sts step_next+1, r31\n\t"        // 2
      "pop r31\n\t"                     // 2
      "pop r30\n\t"                     // 2
      "pop r25\n\t"                     // 2
      "rjmp 5b\n\t"                     // 2  about 96 to the end of RETI
      // Nothing to chain: end the pulse (36 cycles at the earliest), then
      // the C handler takes the queue.
      "7:\n\t"
      "ldi r25, %[clear]\n\t"           // 1  31
      "sts %[tccr1a], r25\n\t"          // 2  33
      "ldi r25, %[force]\n\t"           // 1  34
      "sts %[force_reg], r25\n\t"       // 2  36  the pulse ends
      "pop r31\n\t"
      "pop r30\n\t"
      "pop r25\n\t"
      "pop r24\n\t"
      "out __SREG__, r24\n\t"
      "pop r24\n\t"
      "jmp __vector_step_switch\n\t" ::[tccr1a] "n"(_SFR_MEM_ADDR(TCCR1A)),
      [ocr1ah] "n"(_SFR_MEM_ADDR(OCR1AH)), [ocr1al] "n"(_SFR_MEM_ADDR(OCR1AL)),
      [force_reg] "n"(_SFR_MEM_ADDR(HAL_FORCE_OC1A_REG)), [force] "n"(HAL_FORCE_OC1A_VALUE),
      [clear] "n"(hal::step_timer::kOc1aClear), [set] "n"(hal::step_timer::kOc1aSet),
      [head] "n"(engine::Queue::head_offset()), [tail] "n"(engine::Queue::tail_offset()),
      [slot] "n"(sizeof(am::StepSegment)), [ring] "n"(sizeof(am::StepSegment) * engine::kQueueSize),
      [pad] "n"(engine::kPulsePadTurns), [timer_axis] "n"(engine::kTimerAxes != 0));
}

// The end of a timer-only segment that the vector could not continue: the
// queue holds nothing more (a stop) or the next segment is not marked
// `chain` (another move, which starts from rest). The pulse is not armed;
// the stop, or the new compare value, must land before the old compare
// matches again: the last interval of a deceleration, thousands of cycles
// within the board's acceleration limit. No software pulses and no calls
// here, so the prologue saves few registers.
extern "C" void __vector_step_switch() __attribute__((signal, used, externally_visible));
void __vector_step_switch() { engine::next_segment(); }

// The general handlers: one more period of a long interval, or a step of any
// axis. A timer-pulsed axis has had its whole pulse already (the match raised
// it, the vector above ended it). For the other axes everything before
// pulse_begin is the same on every step, so their edges trail the match by a
// constant number of cycles; their step lines stay high for the bookkeeping
// plus the board's pad, which together meet the drivers' minimum pulse width.
// A coordinated segment asks its block's interpolator which axes step; it
// has its own vector, so a one-axis step does not pay for the registers the
// interpolator needs. (Named __vector_* so avr-gcc accepts the signal
// attribute: a full interrupt prologue and a RETI, entered by the jumps
// above.)
namespace engine {
namespace {

template <bool Coordinated>
inline void step_event() {
  if (wraps_left) {
    if (--wraps_left == 0) {
      hal::step_timer::set_compare(step_compare);
      arm_if_step_period();
    }
    return;
  }
  // A switch the segment runs toward has closed: this step is not made, and
  // nothing moves until the main loop has seen it (clear_trip()).
  if (board::Endstops::closed(endstop_watch, endstop_latches)) {
    stop_engine();
    tripped = true;
    return;
  }
  const uint8_t stepping = Coordinated ? dda->next().axes : axes;
  board::Axes::pulse_begin(stepping, step_dirs);
  if (step_remaining != 0) {
    step_remaining = uint16_t(step_remaining - 1);
    wraps_left = wraps;
    hal::step_timer::set_compare(wraps ? wrap_compare : step_compare);
    arm_if_step_period();
    __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
    board::Axes::pulse_end(stepping);
    return;
  }
  __builtin_avr_delay_cycles(board::kStepPulsePadCycles);
  board::Axes::pulse_end(stepping);
  next_segment();
}

}  // namespace
}  // namespace engine

extern "C" void __vector_step_slow() __attribute__((signal, used, externally_visible));
void __vector_step_slow() { engine::step_event<false>(); }

extern "C" void __vector_step_coordinated() __attribute__((signal, used, externally_visible));
void __vector_step_coordinated() { engine::step_event<true>(); }
