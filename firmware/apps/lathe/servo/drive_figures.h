// The servo leadscrew's figures (servo/leadscrew_servo.cpp), all derived at
// compile time from the board header (firmware/boards/m16-servo.h): the PWM's
// period and the sample time, the PID's coefficients, the feedforward's and
// the moves' scales, the coast, and when the motor counts as standing.
#pragma once
#include <avr/io.h>
#include <stdint.h>

#include "../../../../core/lathe/servo_pid.h"
#include "../../../board.h"

namespace leadscrew {
namespace servo {

// Timer1: fast PWM, 10 bits (mode 7: WGM12, WGM11, WGM10), no prescaler.
constexpr uint8_t kTccr1a = _BV(WGM11) | _BV(WGM10);
constexpr uint8_t kTccr1b = _BV(WGM12) | _BV(CS10);
constexpr uint32_t kPwmPeriod = 1024;  // cycles
constexpr uint32_t kSampleCycles = kPwmPeriod * board::kServoSampleOverflows;
constexpr uint32_t kSampleUs = kSampleCycles / (F_CPU / 1000000ul);
static_assert(kSampleCycles % (F_CPU / 1000000ul) == 0, "a whole number of microseconds a sample");
constexpr am::ServoCoefficients kPid = am::servo_coefficients(board::ServoMotor::kGains, kSampleUs);
static_assert(kPid.ok, "the board's servo gains are out of the PID's ranges");
static_assert(kSampleUs >= am::kServoMinSampleUs, "gains within the settings' ranges need samples of 1 ms or more");

// The feedforward: duty = speed / gain. In a pass speed = lambda F_CPU / P
// for a spindle count period of P cycles: duty = ff_k_ / P with ff_k_ =
// lambda x kFfCycles.
constexpr uint32_t kFfCycles = uint32_t(uint64_t(F_CPU) * 10000 / board::kServoGain_e4);
// A spindle count period this long (2^24 cycles, 1.05 s at 16 MHz) is a
// spindle at rest: no interpolation, no feedforward.
constexpr uint32_t kStalled = 1ul << 24;
// Moves: velocity in counts / 2^16 per sample, acceleration in counts /
// 2^16 per sample^2; the feedforward duty = velocity x kMoveFf_q8 >> 20
// (from velocity >> 4).
constexpr int32_t kMoveAccel =
    int32_t(uint64_t(board::kLeadscrewAccel) * kSampleCycles * kSampleCycles * 65536 / (uint64_t(F_CPU) * F_CPU));
constexpr uint32_t kMoveFf_q8 = uint32_t(uint64_t(F_CPU) * 10000 * 256 / (uint64_t(kSampleCycles) * board::kServoGain_e4));
constexpr uint32_t kVelPerRate = uint32_t(uint64_t(kSampleCycles) * 65536 / 1000);  // x rate / (F_CPU / 1000)
static_assert(uint64_t(board::kLeadscrewMaxRate) * kVelPerRate < (1ull << 32), "the top rate's velocity fits");
static_assert(kMoveAccel > 0, "an acceleration of at least one count / 2^16 per sample^2");
// A move's end: the drive stops where the motor, coasting, comes to rest on
// the destination: a first-order motor at w counts/s coasts w tau further,
// w = F_CPU / P for a motor count period of P cycles (the last one, or the
// time since it if longer): coast = kCoastCycles_q8 / P, counts x 256.
constexpr uint32_t kCoastCycles_q8 = board::kServoTauUs * (F_CPU / 1000000ul) * 256;
// The motor stands once the encoder has been quiet this many samples.
constexpr uint8_t kQuietSamples = 20;

}  // namespace servo
}  // namespace leadscrew
