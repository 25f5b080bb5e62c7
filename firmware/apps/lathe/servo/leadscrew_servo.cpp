// The leadscrew as the seed's DC servo (contract: ../leadscrew.h; the board:
// firmware/boards/m16-servo.h; docs/lathe.md, "The m16-servo image").
//
// Who writes what: INT0 (the motor encoder) counts the carriage in the
// direction the bridge drives; INT1 (the spindle's one channel) counts the
// spindle, timestamps the count and runs the follower; Timer1's overflow
// (every 1024 cycles, the 10-bit PWM's period) reads the limit switch and,
// every kServoSampleOverflows-th time, runs the sample: the target, the PID,
// the duty, with interrupts on (below). The main loop starts and ends passes
// and moves with interrupts off, and measures the spindle's rpm. The other
// vectors do not nest.
//
// A pass: armed until the index (as the stepper's), then locked: every
// sample the target is the follower's floor(+-lambda (s - phi)) from the
// pass's base plus lambda times the fraction of the spindle count elapsed
// since the last one (the time since that count over the last count's
// period, at most 255/256), so the target moves smoothly between counts;
// the feedforward is the target's speed over the plant's gain. The error
// target - count drives the PID (core/lathe/servo_pid.h), which drives one
// way only: the pass's. The pass ends when the follower's target reaches the
// end: the drive stops at once and brakes (IN1 = IN2 = 0, ENABLE high), the
// motor runs down in the same direction and is counted, and the state stays `moving` until the
// encoder has been quiet for kQuietSamples; last_slip() is then the end's
// target minus where the carriage stopped.
// The base of every pass is the reference (reference()): where the
// previous pass or move was meant to end, not where the carriage stopped,
// so the slip of the last motion is carried into the next pass as its
// initial error and every pass from the same reference cuts the same helix.
#include <avr/interrupt.h>
#include <avr/io.h>
#include <util/atomic.h>

#include "../../../../core/lathe/rpm_meter.h"
#include "../../../../core/text/fixed_number.h"
#include "../../../../hal/avr/ext_int.h"
#include "../../../board.h"
#include "../../../engine/clock.h"
#include "../leadscrew.h"
#include "drive_figures.h"

namespace leadscrew {
namespace {

using In1 = board::ServoIn1;
using In2 = board::ServoIn2;

using namespace servo;

am::Follower follower;
am::ServoPid pid;
volatile State state_;
volatile Stop stop_;
volatile int32_t pos_;  // the carriage, motor encoder counts, +Z up
int8_t dir_ = 1;        // the bridge's direction (and the count's), +1 or -1
bool driving_;          // the bridge is driven (the PID runs); else off, coasting or idle
uint8_t quiet_;         // samples since the last encoder count
uint8_t sample_div_ = board::kServoSampleOverflows;
bool in_sample_;
uint32_t overflows_;    // Timer1 overflows: the fine time's upper part

int32_t reference_;     // where the last pass or move was meant to end
int32_t base_, end_;    // the pass: target = base_ + follower.position(); it ends at end_
bool has_end_;
bool index_was_high_;
int32_t lam_q8_;        // lambda x 256, rounded
uint32_t ff_k_;         // lambda x kFfCycles
int32_t slip_target_;   // the last motion's end target (last_slip())

// The spindle: one channel, counted on its falling edge.
volatile int32_t count_;
uint32_t last_count_time_;  // fine time of the last count
uint32_t count_period_;     // cycles between the last two counts
uint16_t counts_per_turn_ = board::kSpindleLines;

// Moves.
int32_t move_dest_;
int32_t traj_q8_;       // the trajectory's point, counts x 256
int32_t vel_q16_;       // its speed, counts / 2^16 per sample
int32_t max_vel_q16_;
bool traj_done_;
uint32_t motor_time_;    // fine time of the last motor count
uint32_t motor_period_;  // cycles between the last two

// The main loop's rpm.
am::RpmMeter rpm;
uint32_t next_tick_;

// Cycles since power-up (mod 2^32): Timer1's count below its overflows.
// Interrupts off.
inline uint32_t fine_now() {
  const uint16_t t = TCNT1;
  uint32_t o = overflows_;
  if ((TIFR & _BV(TOV1)) && t < kPwmPeriod / 2) ++o;
  return (o << 10) | t;
}

// The bridge: while a pass or move drives it, OC1A is connected in the
// inverting fast PWM (COM1A1:0 = 11: set on the compare match, cleared at
// BOTTOM) with OCR1A = TOP - duty, so ENABLE is high for `duty` of the 1024
// cycles of a period, and duty 0 is OCR1A = TOP: a constant low (the
// datasheet's "OCR1x equal to TOP: constant output"; non-inverting PWM at
// OCR1A = 0 would still pulse once a period). OCR1A is double-buffered, so
// a duty takes effect from the next period whole. Stopped, OC1A is
// disconnected: PD5 is its PORT bit, high, at once (the brake, below).
constexpr uint16_t kTop = 1023;
constexpr uint8_t kConnected = kTccr1a | _BV(COM1A1) | _BV(COM1A0);
inline void set_duty(uint16_t duty) { OCR1A = kTop - duty; }

inline void bridge_direction(int8_t d) {
  if (d > 0) {
    In2::low();
    In1::high();
  } else {
    In1::low();
    In2::high();
  }
}

// The drive stops at once and brakes: IN1 = IN2 = 0 first, then ENABLE high
// (PD5's PORT bit, OC1A disconnected): the L298's fast motor stop, held to
// the next drive. The motor is still counted in dir_ until it stands
// (quiet), then the state is idle. The reference becomes `target`.
void drive_off(Stop why, int32_t target) {
  In1::low();
  In2::low();
  board::ServoPwm::high();
  TCCR1A = kTccr1a;
  OCR1A = kTop;
  driving_ = false;
  quiet_ = 0;
  stop_ = why;
  reference_ = target;
  slip_target_ = target;
  state_ = State::moving;
}

inline int32_t pass_target() { return base_ + follower.position(); }

// v in the direction of the motion: +v for +Z, -v for -Z.
inline int32_t along(int32_t v) { return dir_ > 0 ? v : -v; }

// The current target of what runs, for a stop.
int32_t target_now() {
  if (state_ == State::locked) return pass_target();
  if (state_ == State::moving && driving_) return (traj_q8_ + 128) >> 8;
  return reference_;
}

void halt(Stop why) {
  if (state_ == State::idle) return;
  if (!driving_ && state_ == State::moving) return;  // already stopped, the motor still turning
  drive_off(why, state_ == State::armed ? reference_ : target_now());
}

// The sample runs with interrupts on (it takes up to about 2300 cycles,
// more than two PWM periods: the overflow, the encoders and the UART must
// not wait for it). What the vectors write is read in one go with
// interrupts off, and the duty is applied only if nothing stopped the drive
// meanwhile (the limit switch, read by the overflow vector nesting in it).
// Only this function and the main loop (which cannot run during it) touch
// the PID and the move's trajectory.

// Sets the duty unless the drive was stopped meanwhile. Interrupts on.
void apply(uint16_t duty) {
  cli();
  if (driving_) set_duty(duty);
  sei();
}

// Stops the drive at the end of a pass or move unless it was already.
void finish(Stop why, int32_t target) {
  cli();
  if (driving_) drive_off(why, target);
  sei();
}

__attribute__((noinline)) void pass_sample() {
  cli();
  const int32_t target = pass_target();
  const int32_t here = pos_;
  const uint32_t period = count_period_;
  const uint32_t elapsed = fine_now() - last_count_time_;
  sei();
  if (has_end_ && (dir_ > 0 ? target >= end_ : target <= end_)) return finish(Stop::length, end_);
  uint8_t frac = 0;
  uint16_t ff = 0;
  if (period != 0 && period < kStalled) {
    frac = elapsed < period ? uint8_t((elapsed << 8) / period) : 255;
    const uint32_t f = ff_k_ / (elapsed > period ? elapsed : period);
    ff = uint16_t(f > am::ServoPid::kMaxDuty ? am::ServoPid::kMaxDuty : f);
  }
  // In the pass's direction: e = dir (target + dir lambda frac - pos).
  const int32_t ahead = int32_t((uint32_t(lam_q8_) * frac) >> 8);
  const int32_t e = along((target - here) * 256) + ahead;
  // A target the motor cannot keep up with (too fast a spindle for the
  // thread): the pass stops rather than cut off the helix.
  if (e > int32_t(board::kServoMaxLag) * 256) return finish(Stop::overspeed, target);
  apply(pid.update(e, ff));
}

__attribute__((noinline)) void move_sample() {
  cli();
  const int32_t here = pos_;
  uint32_t period = motor_period_;
  const uint32_t since = fine_now() - motor_time_;
  sei();
  if (since > period) period = since;
  const int32_t coast = period < kStalled ? int32_t(kCoastCycles_q8 / period) : 0;
  const Stop why = stop_ == Stop::none ? Stop::done : stop_;  // a disengage() keeps its reason
  if (along((move_dest_ - here) * 256) <= coast) return finish(why, move_dest_);  // it coasts onto the end
  if (!traj_done_) {
    const int32_t remaining = along(move_dest_ * 256 - traj_q8_);  // counts x 256, >= 0
    const int32_t v8 = vel_q16_ >> 8;
    const int32_t stopping = v8 * v8 * 128 / kMoveAccel;  // counts x 256
    if (remaining <= stopping) {
      vel_q16_ -= kMoveAccel;
      if (vel_q16_ < kMoveAccel) vel_q16_ = kMoveAccel;  // creeps to the end
    } else if (vel_q16_ < max_vel_q16_) {
      vel_q16_ += kMoveAccel;
      if (vel_q16_ > max_vel_q16_) vel_q16_ = max_vel_q16_;
    }
    const int32_t step = (vel_q16_ + 128) >> 8;
    if (step >= remaining) {
      traj_q8_ = move_dest_ * 256;
      traj_done_ = true;
      vel_q16_ = 0;
    } else {
      traj_q8_ += along(step);
    }
  }
  const uint16_t ff = uint16_t((uint32_t(vel_q16_ >> 4) * kMoveFf_q8) >> 20);
  const int32_t e = along(traj_q8_ - here * 256);
  apply(pid.update(e, ff > am::ServoPid::kMaxDuty ? am::ServoPid::kMaxDuty : ff));
}

// Interrupts on.
void sample() {
  const State s = state_;
  if (s == State::locked) {
    pass_sample();
  } else if (s == State::moving) {
    if (driving_) {
      move_sample();
    } else if (++quiet_ >= kQuietSamples) {
      cli();
      if (!driving_ && quiet_ >= kQuietSamples) state_ = State::idle;  // the motor stands
      sei();
    }
  }
}

void start_drive(int8_t d) {
  board::ServoPwm::low();  // the brake off, before OC1A takes the pin
  OCR1A = kTop;
  TCCR1A = kConnected;  // constant low until the first sample's duty
  dir_ = d;
  bridge_direction(d);
  pid.reset();
  driving_ = true;
  stop_ = Stop::none;
}

}  // namespace
}  // namespace leadscrew

// The motor encoder: a count in the bridge's direction.
ISR(INT0_vect) {
  using namespace leadscrew;
  pos_ = pos_ + dir_;
  quiet_ = 0;
  const uint32_t t = fine_now();
  motor_period_ = t - motor_time_;
  motor_time_ = t;
}

// The spindle: one channel, every falling edge a forward count.
ISR(INT1_vect) {
  using namespace leadscrew;
  const uint32_t t = fine_now();
  count_period_ = t - last_count_time_;
  last_count_time_ = t;
  count_ = count_ + 1;
  const State s = state_;
  if (s == State::locked) {
    follower.edge(true);
  } else if (s == State::armed) {
    const bool high = board::SpindleIndex::read();
    if (high && !index_was_high_) state_ = State::locked;  // this count is s = 0 (the PID is fresh from engage())
    index_was_high_ = high;
  }
}

// The PWM's period: the limit switch every time, the sample every
// kServoSampleOverflows-th.
ISR(TIMER1_OVF_vect) {
  using namespace leadscrew;
  overflows_ = overflows_ + 1;
  if (!board::LimitSwitch::read() && driving_) halt(Stop::limit);
  if (--sample_div_ == 0) {
    sample_div_ = board::kServoSampleOverflows;
    if (!in_sample_) {  // never false unless a sample took 16 periods
      in_sample_ = true;
      sei();
      sample();
      cli();
      in_sample_ = false;
    }
  }
}

namespace leadscrew {

void init() {
  pid.set(kPid);
  OCR1A = kTop;  // written directly: the timer is still in normal mode
  TCNT1 = 0;
  TCCR1A = kTccr1a;
  TCCR1B = kTccr1b;
  TIFR = _BV(TOV1);
  TIMSK |= _BV(TOIE1);
  hal::ext_int::enable_int0(hal::ext_int::Sense::falling);
  hal::ext_int::enable_int1(hal::ext_int::Sense::falling);
  next_tick_ = clock::now();
}

void poll() {
  while (clock::due(next_tick_, clock::ms(am::RpmMeter::kSampleMs))) rpm.sample(spindle_count(), counts_per_turn_);
}

Refusal engage(const am::Ratio& ratio, bool reversed, int32_t length_steps, uint8_t start, uint8_t starts) {
  if (state_ != State::idle) return Refusal::busy;
  if (starts == 0 || start >= starts) return Refusal::bad_start;
  if (length_steps < 0) return Refusal::bad_length;
  if (ratio.den == 0 || ratio.num / ratio.den >= board::kMaxStepsPerCount) return Refusal::too_steep;
  int32_t lam = 0, ffk = 0;
  if (!am::scale_round(256, ratio.num, ratio.den, lam) || !am::scale_round(int32_t(kFfCycles), ratio.num, ratio.den, ffk))
    return Refusal::too_steep;
  if (!board::LimitSwitch::read()) return Refusal::limit;
  if (!follower.reset(ratio, reversed, am::start_phase(start, starts, counts_per_turn_))) return Refusal::phase_range;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    lam_q8_ = lam;
    ff_k_ = uint32_t(ffk);
    base_ = reference_;
    const int8_t d = reversed ? -1 : 1;
    end_ = base_ + d * length_steps;
    has_end_ = length_steps != 0;
    index_was_high_ = true;  // the index must be seen low at a count, then high
    start_drive(d);
    state_ = State::armed;
  }
  return Refusal::none;
}

Refusal move_to(int32_t steps, uint32_t rate) {
  if (state_ != State::idle) return Refusal::busy;
  if (rate == 0) return Refusal::bad_rate;
  if (!board::LimitSwitch::read()) return Refusal::limit;
  if (rate > board::kLeadscrewMaxRate) rate = board::kLeadscrewMaxRate;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    const int32_t here = pos_;
    if (steps == here) {
      reference_ = steps;
      slip_target_ = steps;
      stop_ = Stop::done;
      return Refusal::none;
    }
    move_dest_ = steps;
    traj_q8_ = here * 256;
    vel_q16_ = 0;
    // counts/s -> counts / 2^16 per sample
    max_vel_q16_ = int32_t(rate * kVelPerRate / uint32_t(F_CPU / 1000));
    traj_done_ = false;
    motor_period_ = kStalled;  // at rest
    start_drive(steps > here ? 1 : -1);
    state_ = State::moving;
  }
  return Refusal::none;
}

void disengage() {
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    if (state_ == State::moving && driving_ && !traj_done_) {
      // Decelerate: the move's end where the speed comes to 0.
      const int32_t v8 = vel_q16_ >> 8;
      const int32_t stopping = v8 * v8 * 128 / kMoveAccel;
      move_dest_ = ((traj_q8_ + along(stopping)) >> 8) + dir_;
      stop_ = Stop::stopped;
    } else {
      halt(Stop::stopped);
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

int32_t reference() {
  int32_t r;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { r = reference_; }
  return r;
}

int32_t last_slip() {
  int32_t s;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { s = slip_target_ - pos_; }
  return s;
}

int32_t following_error() {
  int32_t e = 0;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) {
    if (state_ == State::locked) e = pass_target() - pos_;
  }
  return e;
}

int16_t spindle_rpm() { return rpm.rpm(); }

int32_t spindle_count() {
  int32_t c;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { c = count_; }
  return c;
}

uint16_t lost_counts() { return 0; }  // one channel: nothing to check a count against

bool set_gains(const am::ServoGains& gains) {
  if (state_ != State::idle) return false;
  const am::ServoCoefficients c = am::servo_coefficients(gains, kSampleUs);
  bool taken;
  ATOMIC_BLOCK(ATOMIC_RESTORESTATE) { taken = pid.set(c); }
  return taken;
}

bool set_encoder(bool quadrature, uint16_t lines) {
  if (state_ != State::idle || lines == 0 || quadrature) return false;
  counts_per_turn_ = lines;
  rpm.reset(spindle_count());
  return true;
}

am::Machine machine() {
  return am::Machine{board::kLeadscrewPitch, board::kLeadscrewCounts, counts_per_turn_, board::kLeadscrewReversed};
}

}  // namespace leadscrew
