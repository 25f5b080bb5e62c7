// The leadscrew's interrupts and its speed control (contract: leadscrew.h).
//
// Who writes what: the spindle vectors (INT1, INT0: spindle_vectors.S, in
// assembly) decode each count, run the follower from the index on and,
// once locked, step; any other count goes to their C part here
// (__vector_spindle_unlocked: the index while armed); the pace vector (Timer1
// compare A, CTC at F_CPU / 8) steps moves and the catch-up at the period
// poll() sets; the main loop starts and ends passes and moves with
// interrupts off. Vectors do not nest, so each one sees the others' work
// whole. What the assembly reads and writes is lathe_vector and
// lathe_follower (spindle_vectors.h: the layout, checked).
//
// Speed over size for the counts' C path and the pace vector only (kFast:
// -O2); the rest of the file stays at the image's -Os.
#include "leadscrew.h"

#include <avr/interrupt.h>
#include <util/atomic.h>

#include "../../../core/lathe/rpm_meter.h"
#include "../../../core/math/isqrt.h"
#include "../../../hal/avr/step_timer.h"
#include "../../board.h"
#include "../../devices/spindle_encoder.h"
#include "../../engine/clock.h"
#include "spindle_vectors.h"

#define kFast __attribute__((optimize("O2")))
#define kInline __attribute__((always_inline)) inline

LatheVector lathe_vector;
am::Follower lathe_follower asm("lathe_follower");

static_assert(board::LeadStep::port == 'C' && board::LeadStep::mask == 1 << LV_STEP_BIT &&
                  board::LeadDir::port == 'C' && board::LeadDir::mask == 1 << LV_DIR_BIT &&
                  board::LimitSwitch::port == 'D' && board::LimitSwitch::mask == 1 << LV_LIMIT_BIT,
              "the pins spindle_vectors.S drives and reads");
static_assert(F_CPU == 16000000 && 3 * LV_HIGH_TURNS + 2 >= board::kStepHighCycles,
              "a burst's pulses in spindle_vectors.S");

namespace leadscrew {
namespace {

using Step = board::LeadStep;
using Dir = board::LeadDir;

LatheVector& lv = lathe_vector;
am::Follower& follower = lathe_follower;
volatile State& state_ = lv.state;
volatile Stop& stop_ = lv.stop;
int32_t& pos_ = lv.pos;   // the carriage, steps
int32_t base_;            // the pass's base: target = base_ + follower.position()
int32_t& end_ = lv.end;   // the pass ends here (lv.has_end)
bool& dir_up_ = lv.dir_up;  // the direction pin's level: true = +Z
bool index_was_high_;
uint16_t counts_per_turn_ = board::kSpindleLines;

// The pace: steps of the direction pace_dir_ (0: none) every pace_period_
// ticks of F_CPU / 8.
volatile int8_t pace_dir_;
volatile uint16_t pace_period_;
int32_t move_target_;
uint32_t move_rate_;

// The main loop's speed control.
int32_t velocity_;   // steps/s, signed: the pace's
uint32_t next_tick_;
constexpr uint8_t kTargetSamples = 8;
constexpr uint8_t kTargetEvery = 4;    // ms between samples
int32_t target_ring_[kTargetSamples];  // the target, every 4 ms (its speed over 32 ms)
am::RpmMeter rpm;                      // the spindle count, every 64 ms
int32_t target_speed_;                 // steps/s, from target_ring_
uint16_t tick_;                        // ms; 2^16 is a multiple of both samplings' cycles

constexpr uint32_t kPaceHz = F_CPU / 8;
constexpr uint32_t kMinPaceRate = kPaceHz / 65535 + 1;  // 31 steps/s at 16 MHz
constexpr uint32_t kAccelPerTick = board::kLeadscrewAccel / 1000;

inline void pace_off() {
  pace_dir_ = 0;
  hal::step_timer::stop();
}

// One step now, with the driver's timing: the direction set up first when
// it changes (kDirSetupCycles), the pulse's end left to the caller.
kInline void step_begin(bool up) {
  if (up != dir_up_) {
    Dir::set(up);
    dir_up_ = up;
    __builtin_avr_delay_cycles(board::kDirSetupCycles);
  }
  Step::high();
}

__attribute__((noinline)) void halt(Stop why) {
  state_ = State::idle;
  stop_ = why;
  pace_off();
}

}  // namespace
}  // namespace leadscrew

// A spindle count while neither catching up nor locked (spindle_vectors.S
// hands it over with every register as the interrupt found it, the
// direction in lv.slow_dir): the spindle's count, the index while armed.
extern "C" void __vector_spindle_unlocked() __attribute__((signal, used, externally_visible)) kFast;
void __vector_spindle_unlocked() {
  using namespace leadscrew;
  const bool forward = lv.slow_dir != 0;
  lv.encoder.count = lv.encoder.count + (forward ? 1 : -1);
  if (state_ == State::armed) {
    const bool high = board::SpindleIndex::read();
    if (high && !index_was_high_) {
      // s = 0: from the next count on the assembly runs the follower
      // (spindle_vectors.h: the lead for this count's direction).
      const LatheVectorDir& e = lv.dir[forward];
      lv.ahead_dir = forward ? LV_FORWARD : 0;
      lv.lead = int32_t(am::FollowerVectorAccess::residual(follower) + e.neg_t);
      lv.ahead = int8_t(e.whole_a + (lv.lead >= 0 ? 1 : 0));
      state_ = State::catching;
    }
    index_was_high_ = high;
  }
}

// The pace: one step of a move or of the catch-up. Interrupts are on from
// its first instruction (ISR_NOBLOCK), so the spindle vectors, which run
// the follower while it catches up, wait for no more than its entry: what
// both touch (the carriage, the follower's position, the state) is read and
// changed with interrupts off, the lock included. Its own interrupt is
// masked while it runs: under spindle counts at 120000/s it can take
// longer than its period.
namespace leadscrew {
namespace {
kInline void pace_event() {
  OCR1A = pace_period_;
  const int8_t d = pace_dir_;
  if (d == 0) return;
  if (!board::LimitSwitch::read()) {
    ATOMIC_BLOCK(ATOMIC_FORCEON) { halt(Stop::limit); }
    return;
  }
  step_begin(d > 0);
  __builtin_avr_delay_cycles(board::kStepHighCycles);
  Step::low();
  ATOMIC_BLOCK(ATOMIC_FORCEON) {
    pos_ += d;
    if (state_ == State::catching) {
      if (pos_ == base_ + follower.position()) {
        // Locked: the spindle vectors step from the next count on, in the
        // direction of the last count (spindle_vectors.h: the lead and
        // ahead are that direction's); the direction pin is set for it
        // here, a count's vector or more before its step.
        const bool up = (lv.ahead_dir != 0) != (lv.reversed != 0);
        if (up != dir_up_) {
          Dir::set(up);
          dir_up_ = up;
        }
        state_ = State::locked;
        pace_off();
      } else if (lv.has_end && pos_ == end_) {
        halt(Stop::length);
      }
    } else if (pos_ == move_target_) {
      halt(stop_ == Stop::none ? Stop::done : stop_);  // a disengage() keeps its reason
    }
  }
}
}  // namespace
}  // namespace leadscrew

ISR(TIMER1_COMPA_vect, ISR_NOBLOCK) kFast;
ISR(TIMER1_COMPA_vect, ISR_NOBLOCK) {
  HAL_TIMER1_MASK &= uint8_t(~_BV(OCIE1A));
  leadscrew::pace_event();
  HAL_TIMER1_MASK |= _BV(OCIE1A);
}

namespace leadscrew {
namespace {

// Speed to close a gap of e steps with the board's deceleration: sqrt(2 a |e|),
// at most kLeadscrewMaxRate.
uint32_t closing_speed(int32_t e) {
  const uint32_t gap = uint32_t(e < 0 ? -e : e);
  constexpr uint32_t kMaxGap = 0xFFFFFFFFul / (2 * board::kLeadscrewAccel);
  if (gap > kMaxGap) return board::kLeadscrewMaxRate;
  const uint32_t v = am::isqrt32(2 * board::kLeadscrewAccel * gap);
  return v < board::kLeadscrewMaxRate ? v : board::kLeadscrewMaxRate;
}

int32_t clamp(int32_t v, int32_t limit) { return v > limit ? limit : v < -limit ? -limit : v; }

// Moves the pace's speed towards `goal` by at most the acceleration of one
// millisecond and sets the pace from it.
void steer(int32_t goal) {
  velocity_ += clamp(goal - velocity_, int32_t(kAccelPerTick));
  const uint32_t speed = uint32_t(velocity_ < 0 ? -velocity_ : velocity_);
  if (speed < kMinPaceRate) {
    pace_dir_ = 0;
    return;
  }
  const uint16_t period = uint16_t(kPaceHz / speed - 1);
  const int8_t dir = velocity_ > 0 ? 1 : -1;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    pace_period_ = period;
    if (pace_dir_ == 0 && (state_ == State::moving || state_ == State::catching)) {
      pace_dir_ = dir;
      hal::step_timer::start_div8(period);
    }
    pace_dir_ = dir;
  }
}

int32_t target_now() {
  int32_t t;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { t = base_ + follower.position(); }
  return t;
}

// One millisecond of speed control.
// Decelerates a paced move or catch-up to rest as soon as the acceleration
// allows (v^2 / 2a further on), ending with `why`. Interrupts off.
void brake(Stop why) {
  const int32_t v = velocity_ < 0 ? -velocity_ : velocity_;
  const int32_t braking = int32_t(uint32_t(v) * uint32_t(v) / (2 * board::kLeadscrewAccel));
  move_target_ = pos_ + (velocity_ > 0 ? braking + 1 : -braking - 1);
  move_rate_ = uint32_t(v);
  state_ = State::moving;
  stop_ = why;
}

void control_tick() {
  const uint16_t tick = tick_++;
  const int32_t count = spindle_count();
  if (tick % am::RpmMeter::kSampleMs == 0) rpm.sample(count, counts_per_turn_);
  const State s = state_;
  if (s == State::catching) {
    const int32_t target = target_now();
    if (tick % kTargetEvery == 0) {
      const uint8_t at = uint8_t(tick / kTargetEvery) % kTargetSamples;
      target_speed_ = (target - target_ring_[at]) * 125 / 4;  // steps in 32 ms -> steps/s
      target_ring_[at] = target;
    }
    const int32_t target_speed = target_speed_;
    const int32_t e = target - position();
    if (target_speed > int32_t(board::kLeadscrewMaxRate) || target_speed < -int32_t(board::kLeadscrewMaxRate)) {
      // The carriage could never catch up: it stops, unlocked.
      ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
        if (state_ == State::catching) brake(Stop::overspeed);
      }
      return;
    }
    int32_t goal = 0;
    if (e != 0 && (target_speed == 0 || (e > 0) == (target_speed > 0))) {
      const int32_t closing = int32_t(closing_speed(e));
      goal = target_speed + (e > 0 ? closing : -closing);
    }
    steer(clamp(goal, board::kLeadscrewMaxRate));
  } else if (s == State::moving) {
    const int32_t e = move_target_ - position();
    const int32_t closing = int32_t(closing_speed(e));
    const int32_t limit = int32_t(move_rate_);
    steer(clamp(e > 0 ? closing : -closing, limit));
  } else {
    velocity_ = 0;
  }
}

// The spindle vectors' entries for both directions, from the follower's
// steps (spindle_vectors.h): rem, -T = rem - den, the conversion from the
// other direction, the whole steps. Idle: no vector reads them.
void prime_vectors() {
  const uint32_t den = am::FollowerVectorAccess::den(follower);
  for (uint8_t i = 0; i < 2; ++i) {
    LatheVectorDir& e = lv.dir[i];
    e.rem = am::FollowerVectorAccess::rem(follower, i);
    e.neg_t = e.rem - den;
    e.whole_a = e.whole_b = e.whole_c = int8_t(am::FollowerVectorAccess::whole(follower, i));
  }
  lv.dir[1].flip = lv.dir[1].neg_t - lv.dir[0].neg_t;
  lv.dir[0].flip = 0u - lv.dir[1].flip;
}

void start_pace_clock() {
  velocity_ = 0;
  pace_dir_ = 0;
  pace_period_ = 0xFFFF;
  hal::step_timer::start_div8(0xFFFF);
}

}  // namespace

void init() {
  hal::step_timer::init();
  set_encoder(board::kSpindleQuadrature, board::kSpindleLines);
  dir_up_ = false;
  next_tick_ = clock::now();
}

void poll() {
  if (!board::LimitSwitch::read() && state_ != State::idle) {
    ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
      if (state_ != State::idle) halt(Stop::limit);
    }
  }
  while (clock::due(next_tick_, clock::ms(1))) control_tick();
}

Refusal engage(const am::Ratio& ratio, bool reversed, int32_t length_steps, uint8_t start, uint8_t starts) {
  if (state_ != State::idle) return Refusal::busy;
  if (starts == 0 || start >= starts) return Refusal::bad_start;
  if (length_steps < 0) return Refusal::bad_length;
  if (ratio.den == 0 || ratio.num / ratio.den >= board::kMaxStepsPerCount) return Refusal::too_steep;
  if (!board::LimitSwitch::read()) return Refusal::limit;
  if (!follower.reset(ratio, reversed, am::start_phase(start, starts, counts_per_turn_))) return Refusal::phase_range;
  prime_vectors();
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    base_ = pos_;
    lv.reversed = reversed ? LV_FORWARD : 0;
    end_ = reversed ? pos_ - length_steps : pos_ + length_steps;
    lv.has_end = length_steps != 0;
    index_was_high_ = true;  // the index must be seen low at a count, then high
    stop_ = Stop::none;
    const int32_t t = base_ + follower.position();
    for (uint8_t i = 0; i < kTargetSamples; ++i) target_ring_[i] = t;
    target_speed_ = 0;
    start_pace_clock();
    state_ = State::armed;
  }
  return Refusal::none;
}

Refusal move_to(int32_t steps, uint32_t rate) {
  if (state_ != State::idle) return Refusal::busy;
  if (rate == 0) return Refusal::bad_rate;
  if (!board::LimitSwitch::read()) return Refusal::limit;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    stop_ = Stop::none;
    if (steps == pos_) {
      stop_ = Stop::done;
      return Refusal::none;
    }
    move_target_ = steps;
    move_rate_ = rate < board::kLeadscrewMaxRate ? rate : board::kLeadscrewMaxRate;
    start_pace_clock();
    state_ = State::moving;
  }
  return Refusal::none;
}

void disengage() {
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    const State s = state_;
    if (s == State::locked || s == State::armed || velocity_ == 0) {
      if (s != State::idle) halt(Stop::stopped);
    } else {
      brake(Stop::stopped);
    }
  }
}

void stop_now() {
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { halt(Stop::stopped); }
}

bool busy() { return state_ != State::idle; }
State state() { return state_; }
Stop last_stop() { return stop_; }

int32_t position() {
  int32_t p;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { p = pos_; }
  return p;
}

int32_t following_error() {
  const State s = state_;
  if (s != State::catching && s != State::locked) return 0;
  int32_t e;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { e = base_ + follower.position() - pos_; }
  return e;
}

int16_t spindle_rpm() { return rpm.rpm(); }

int32_t spindle_count() {
  int32_t c;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { c = lv.encoder.count; }
  return c;
}

uint16_t lost_counts() {
  uint16_t n;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { n = lv.encoder.lost; }
  return n;
}

bool set_encoder(bool quadrature, uint16_t lines) {
  if (state_ != State::idle || lines == 0) return false;
  const spindle_encoder::Mode m = quadrature ? spindle_encoder::Mode::quadrature : spindle_encoder::Mode::single;
  const uint32_t counts = uint32_t(lines) * spindle_encoder::counts_per_line(m);
  if (counts > 0xFFFF) return false;
  counts_per_turn_ = uint16_t(counts);
  spindle_encoder::init(m, lv.encoder);
  rpm.reset(spindle_count());
  return true;
}

am::Machine machine() {
  return am::Machine{board::kLeadscrewPitch, board::kLeadscrewCounts, counts_per_turn_, board::kLeadscrewReversed};
}

}  // namespace leadscrew
