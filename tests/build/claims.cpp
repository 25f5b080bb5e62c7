// Compile-time claim checks (hal/avr/claims.h): built by tests/CMakeLists.txt
// once per CASE; every case but the valid ones must be refused with its
// message.
#include "hal/avr/claims.h"

#include "firmware/boards/common/m16_servo_claims.h"

using namespace hal::claim;

// The Uno's claims: Timer2's PWM (stepper 1) at no prescaler, Timer0's
// (stepper 2) at 8, the time base on Timer0's overflow at the same rate.
constexpr uint32_t uno_clock = timer0_ovf | timer0_pwm8 | timer0_div8;
// The m32's and m16's time base: Timer0 its own, prescaler 64.
constexpr uint32_t own_clock = timer0_ovf | timer0 | timer0_div64;

#if CASE == 0  // valid: the Uno's claims
using Claims = hal::ClaimSet<timer1, uno_clock, uart, oc1a, timer2_pwm8 | timer2_div1 | oc2a,
                             timer2_pwm8 | timer2_div1 | oc2b, timer0_pwm8 | timer0_div8 | oc0a,
                             timer0_pwm8 | timer0_div8 | oc0b>;
#elif CASE == 1  // two PWM users of one compare pin
using Claims = hal::ClaimSet<timer1, timer2_pwm8 | timer2_div1 | oc2a, timer2_pwm8 | timer2_div1 | oc2a>;
#elif CASE == 2  // a step clock and a servo PWM on Timer1
using Claims = hal::ClaimSet<timer1, timer1 | oc1a>;
#elif CASE == 3  // a time base on Timer2 beside the shield's PWM on it
using Claims = hal::ClaimSet<timer1, timer2_pwm8 | timer2_div1 | oc2b, timer2>;
#elif CASE == 4  // valid: the m32's claims, its time base on Timer0, Timer2 left to the heater
using Claims = hal::ClaimSet<timer1, own_clock, uart, timer2 | oc2a>;
#elif CASE == 5  // the shield's 62.5 kHz PWM on Timer0 beside a time base at prescaler 8
using Claims = hal::ClaimSet<timer1, uno_clock, timer0_pwm8 | timer0_div1 | oc0a>;
#elif CASE == 6  // two time bases on Timer0's overflow
using Claims = hal::ClaimSet<timer1, uno_clock, timer0_pwm8 | timer0_div8 | oc0a, uno_clock>;
#elif CASE == 7  // a part reprogramming Timer0 (another mode) while its overflow is the clock
using Claims = hal::ClaimSet<timer1, uno_clock, timer0 | oc0a>;
#elif CASE == 8  // a PWM channel on Timer0 while the time base owns it (normal mode)
using Claims = hal::ClaimSet<timer1, own_clock, timer0_pwm8 | timer0_div64 | oc0b>;
#elif CASE == 9  // a time base that does not say at what rate Timer0 runs
using Claims = hal::ClaimSet<timer1, timer0_ovf | timer0>;
#elif CASE == 10  // 8-bit PWM whose rate nobody names
using Claims = hal::ClaimSet<timer1, timer2_pwm8 | oc2a>;
#elif CASE == 11  // valid: the m16-servo's claims (firmware/boards/m16-servo.h)
using Claims = hal::ClaimSet<m16_servo_claims::kServo, m16_servo_claims::kSpindle, own_clock, uart>;
#elif CASE == 12  // the servo's PWM on Timer1 beside the stepper leadscrew's pace (Timer1, CTC)
using Claims = hal::ClaimSet<m16_servo_claims::kServo, m16_servo_claims::kSpindle, own_clock, uart, timer1>;
#elif CASE == 13  // the servo's encoder on INT0 beside a quadrature spindle's channel B
using Claims = hal::ClaimSet<m16_servo_claims::kServo, m16_servo_claims::kSpindle | int0, own_clock, uart>;
#endif

static_assert(sizeof(Claims) > 0, "instantiate");
int main() { return 0; }
