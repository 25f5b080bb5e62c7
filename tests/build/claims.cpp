// Compile-time claim checks (hal/avr/claims.h): built by tests/CMakeLists.txt
// once per CASE; every case but `valid` must be refused with its message.
#include "hal/avr/claims.h"

using namespace hal::claim;

#if CASE == 0  // valid: the Uno's claims
using Claims = hal::ClaimSet<timer1, uart, oc1a, timer2_pwm8 | oc2a, timer2_pwm8 | oc2b, timer0_pwm8 | oc0a,
                             timer0_pwm8 | oc0b>;
#elif CASE == 1  // two PWM users of one compare pin
using Claims = hal::ClaimSet<timer1, timer2_pwm8 | oc2a, timer2_pwm8 | oc2a>;
#elif CASE == 2  // a step clock and a servo PWM on Timer1
using Claims = hal::ClaimSet<timer1, timer1 | oc1a>;
#elif CASE == 3  // a time base on Timer2 beside the shield's PWM on it
using Claims = hal::ClaimSet<timer1, timer2_pwm8 | oc2b, timer2>;
#endif

static_assert(sizeof(Claims) > 0, "instantiate");
int main() { return 0; }
