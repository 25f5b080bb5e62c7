#include "step_engine.h"

#include <stddef.h>

#include "../../hal/avr/step_timer.h"
#include "../board.h"
#include "step_vector.h"

static_assert(board::kStepClock == hal::claim::timer1, "the step engine runs on Timer1: the board must claim it");

namespace engine {
namespace {

constexpr uint8_t kTimerAxes = board::Axes::timer_mask;
using Queue = am::StepQueue<kQueueSize>;

// The facts the compare-A vector (step_vector.S) takes from step_vector.h.
static_assert(offsetof(am::StepSegment, count) == STEP_SEGMENT_COUNT, "segment layout");
static_assert(offsetof(am::StepSegment, compare) == STEP_SEGMENT_COMPARE, "segment layout");
static_assert(offsetof(am::StepSegment, chain) == STEP_SEGMENT_CHAIN, "segment layout");
static_assert(sizeof(am::StepSegment) == STEP_SEGMENT_SIZE, "segment layout");
static_assert(sizeof(am::StepSegment::count) == 2 && sizeof(am::StepSegment::compare) == 2, "segment layout");
static_assert(kQueueSize == STEP_QUEUE_SIZE, "queue size");
static_assert(Queue::slots_offset() == 0, "queue layout");
static_assert(STEP_QUEUE_SLOTS_BYTES == sizeof(am::StepSegment) * kQueueSize, "queue layout");
static_assert(Queue::head_offset() == STEP_QUEUE_HEAD, "queue layout");
static_assert(Queue::tail_offset() == STEP_QUEUE_TAIL, "queue layout");
static_assert(hal::step_timer::kOc1aClear == STEP_OC1A_CLEAR, "OC1A modes");
static_assert(hal::step_timer::kOc1aSet == STEP_OC1A_SET, "OC1A modes");
static_assert(kBlockRing == 4, "block_slot lists four slots");

}  // namespace
}  // namespace engine

// Shared with the compare-A vector (step_vector.S), hence assembler names.
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

// The direction lines driven inverted, the switch pins read inverted
// (set_polarities()).
uint8_t dir_invert, switch_invert;

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
  board::Axes::set_direction(s.axes, board::kPinPolarities ? uint8_t(s.dirs ^ dir_invert) : s.dirs);
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

void set_polarities(uint8_t dir_mask, uint8_t switch_pins) {
  if (!board::kPinPolarities) return;
  dir_invert = dir_mask;
  switch_invert = switch_pins;
  board::Endstops::init(switch_pins != 0);
}

uint8_t inverted_switches() { return switch_invert; }

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

// The C handlers. The compare-A vector itself is assembly, in
// firmware/engine/step_vector.S: the timer-pulsed axis's fast path, which
// jumps to one of these for everything else.
//
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
// it, the vector ended it). For the other axes everything before
// pulse_begin is the same on every step, so their edges trail the match by a
// constant number of cycles; their step lines stay high for the bookkeeping
// plus the board's pad, which together meet the drivers' minimum pulse width.
// A coordinated segment asks its block's interpolator which axes step; it
// has its own vector, so a one-axis step does not pay for the registers the
// interpolator needs. (Named __vector_* so avr-gcc accepts the signal
// attribute: a full interrupt prologue and a RETI, entered by the vector's
// jumps.)
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
  if (board::Endstops::closed(endstop_watch, endstop_latches, board::kPinPolarities ? switch_invert : 0)) {
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
