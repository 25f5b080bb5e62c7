// The electronic leadscrew: a stepper on the leadscrew that follows the
// spindle at an exact ratio, and positions the carriage between passes.
// The control API for the front ends (the UART's G33 here, the operator
// panel's keypad workflow). On a board with kServoLeadscrew (m16-servo) the
// same API drives the seed's DC servo instead (servo/leadscrew_servo.cpp:
// positions in motor encoder counts, a pass locked from its index under a
// PID, no catching state, moving while the motor coasts to rest; docs/
// lathe.md, "The m16-servo image").
//
// Contract
//   Positions are leadscrew steps, +Z away from the chuck, 0 at power-up.
//   init() once before sei(); poll() from the main loop as often as it runs
//   (the moves' and the engagement's speed control: one step of it per
//   millisecond, clock::due).
//
//   engage(ratio, reversed, length, start, starts): a thread or feed.
//     ratio and reversed are core/lathe's (gear_ratio(): GearRatio::ratio
//     and ::reversed), counted in the spindle encoder's counts (machine()).
//     The carriage stands where the pass begins (base). The state is armed
//     until the spindle index, seen at a spindle count, makes that count
//     the thread's zero s = 0; from then the thread's helix is
//         target(s) = base + floor(+-lambda (s - phi)),  phi = start/starts turn
//     (follower.h), exactly, however the spindle turns, so every pass that
//     starts from the same base re-enters the same helix and start k of n
//     lands k/n of a turn on. catching: the carriage, at rest, waits until
//     the target has passed it and then chases it at the board's
//     acceleration (kLeadscrewAccel), arriving at the target's speed; the
//     step that reaches the target locks it. locked: each spindle count's
//     steps are issued by the count's own interrupt, so the following error
//     is 0 and stays 0. The pass ends when the carriage is length steps from
//     base (0: until disengage() or stop_now()), at once, on that step
//     (last_stop() == Stop::length). A spindle reversal reverses the
//     leadscrew on the same helix (quadrature encoder only).
//     Refused (not idle, start >= starts, a ratio of kMaxStepsPerCount steps
//     or more per count, a phase the follower cannot hold, negative length,
//     limit switch hit) with the reason, and nothing moves.
//   move_to(steps, rate): a positioning move with the board's acceleration
//     to an absolute position, at most `rate` steps/s (and
//     kLeadscrewMaxRate); refused while busy or for rate 0.
//   disengage(): ends what runs in order: a locked pass stops at once (it
//     cannot leave the helix gradually), a catch-up or a move decelerates to
//     rest, an armed pass is dropped. stop_now(): everything stops on the
//     spot (emergency stop); so does the limit switch (PD7 low), checked at
//     every count, every paced step and every poll().
//   busy(): anything but idle. position(): where the carriage is.
//   following_error(): target - position while a pass is catching or
//   locked (0 when locked), else 0. spindle_rpm(): measured over the last
//   0.5 s, signed by direction.
//   set_encoder(quadrature, lines): the spindle encoder (single channel
//   counted on its falling edge, or quadrature x4); only while idle.
//   machine(): the gearing core's machine for the encoder in use.
#pragma once
#include <stdint.h>

#include "../../../core/lathe/ratio.h"

namespace am {
struct ServoGains;
}  // namespace am

namespace leadscrew {

enum class State : uint8_t { idle, moving, armed, catching, locked };
enum class Stop : uint8_t { none, done, length, limit, stopped, overspeed };
enum class Refusal : uint8_t { none, busy, bad_start, bad_length, too_steep, phase_range, limit, bad_rate };

void init();
void poll();

Refusal engage(const am::Ratio& ratio, bool reversed, int32_t length_steps /*0 = until stopped*/, uint8_t start,
               uint8_t starts);
Refusal move_to(int32_t steps, uint32_t rate);
void disengage();
void stop_now();

bool busy();
State state();
Stop last_stop();  // why the last pass or move ended
int32_t position();
int32_t following_error();
int16_t spindle_rpm();
int32_t spindle_count();  // net spindle counts since init()
uint16_t lost_counts();   // counts the decoder could not be sure of (spindle_encoder.h)

bool set_encoder(bool quadrature, uint16_t lines);

// The DC-servo leadscrew only (servo/leadscrew_servo.cpp, a board with
// kServoLeadscrew): reference() is where the last pass or move was meant to
// end (the base of the next pass, and the front end's "here"); last_slip()
// that end's target minus where the carriage is (final once idle: the
// motor has stopped). The stepper's carriage always ends where it was
// meant to. set_gains(): the position PID's gains (core/lathe/servo_pid.h),
// taken only while idle and within the PID's ranges (false otherwise, the
// gains in use kept); init() starts with the board's (kServoGains).
int32_t reference();
int32_t last_slip();
bool set_gains(const am::ServoGains& gains);
am::Machine machine();

}  // namespace leadscrew
