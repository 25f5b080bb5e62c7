// Board: the ATmega16 lathe controller (seed-004 section 4) as an electronic
// leadscrew with the seed's DC servo on the leadscrew (docs/lathe.md, "The
// m16-servo image"): the m16-lathe's board and front end, the stepper
// replaced by a brushed DC motor on an L298, its encoder and a position PID.
// avrmotion-board: mcu=atmega16 f_cpu=16000000 app=lathe
//
// Pin map (firmware/boards/common/m16_wiring.h, and the two moved pins):
//   PD5 (OC1A)  L298 ENABLE (both bridges in parallel): the 10-bit PWM while
//               a pass or move drives; stopped, OC1A is disconnected and PD5
//               is high (the brake with IN1 = IN2 = 0); low from reset until
//               the first drive (the bridge off).
//   PC0         L298 IN1 } high/low: +Z (away from the chuck), low/high: -Z,
//   PC1         L298 IN2 } low/low with ENABLE high: the brake (the motor's
//               terminals shorted), which every stop applies and holds
//               until the next drive (PD5 high as a port pin, OC1A
//               disconnected). The seed had them on PD0/PD1,
//               which are the UART here; PC0/PC1 are the stepper's step and
//               direction on the m16-lathe, unused with a servo.
//   PD2 (INT0)  motor encoder: the seed's 30-slot disc (H21A1) on the motor
//               shaft behind the 1:26 gearbox, one channel, counted on its
//               falling edge in the direction the bridge is driven (780
//               counts a leadscrew turn, 4.07 um of carriage each).
//   PD3 (INT1)  spindle encoder: the seed's 40-slot disc, one channel,
//               falling edge (no quadrature: INT0 is the motor's).
//   PD6         spindle index; PD7 limit switch (low = hit).
//   PORTA/PORTB the LCD and keypad (declared in the wiring, unused here);
//   PC7 (the stepper's enable) unused.
#pragma once
#include "../../core/lathe/ratio.h"
#include "../../core/lathe/servo_pid.h"
#include "../axes/axis_set.h"
#include "common/m16_servo_claims.h"
#include "common/m16_wiring.h"

namespace board {

using namespace m16_wiring;

constexpr bool kServoLeadscrew = true;
using ServoPwm = L298Enable;      // PD5, OC1A
using ServoIn1 = hal::Pin<'C', 0>;
using ServoIn2 = hal::Pin<'C', 1>;
using ServoEncoder = MotorEncoder;  // PD2, INT0
struct ServoPins {
  using Pwm = ServoPwm;
  using In1 = ServoIn1;
  using In2 = ServoIn2;
  using Encoder = ServoEncoder;
};

constexpr bool kSpindleEncoder = true;  // its pins in the descriptor, for the simulator
struct SpindlePins {
  using A = SpindleEncoder;
  // no B: one channel only (INT0 is the motor's; the simulator refuses quadrature)
  using Index = SpindleIndex;
  using Limit = LimitSwitch;
};

// No stepped axes: the leadscrew is the servo.
using Axes = AxisSet<>;

// The motor: the seed's 30-slot encoder disc behind its 1:26 gearbox, and
// the PID's gains for it (below); the operator panel's defaults
// (firmware/apps/lathe/operator.cpp) read them from here.
struct ServoMotor {
  static constexpr uint32_t kPulses = 30;
  static constexpr uint32_t kGearbox = 26;
  // The PID (core/lathe/servo_pid.h): the seed's tuning for this plant
  // (60 degrees phase margin, crossover about 132 rad/s).
  static constexpr am::ServoGains kGains = {72037, 82608, 672};
};

// The machine for the gearing core: 30 pulses x 26 = 780 counts per turn of
// the 3.175 mm leadscrew. Positive counts move +Z, so with the spindle
// forward a right-hand thread needs negative counts: leadscrew_reversed.
constexpr am::Pitch kLeadscrewPitch = am::pitch_tpi(8);
constexpr am::CountsPerTurn kLeadscrewCounts = am::servo_counts(ServoMotor::kPulses, ServoMotor::kGearbox);
constexpr bool kLeadscrewReversed = true;
constexpr uint16_t kSpindleLines = 40;
constexpr bool kSpindleQuadrature = false;

// The plant (seed digest section 3): G(s) = 2.0866 / (s / 74.29 + 1) from
// the duty count (0..1023) to the motor encoder's pulse rate, then an
// integrator: 2.0866 counts/s per duty count, 2134.6 counts/s (8.7 mm/s,
// 164 leadscrew rpm) at full duty, time constant 13.46 ms. The feedforward
// uses the gain: duty = speed / 2.0866.
constexpr uint32_t kServoGain_e4 = 20866;  // counts/s per duty count, x 10^4
constexpr uint32_t kServoTauUs = 13461;    // 1 / 74.29 s: a move stops its drive w tau before its end
// The PID is sampled every 16th Timer1 overflow: 16 x 1024 cycles, 1.024 ms
// at 16 MHz.
constexpr uint8_t kServoSampleOverflows = 16;
// Positioning moves (G0, the retract): at most 1800 counts/s (7.3 mm/s, 84 %
// of the motor's top speed, so the loop keeps headroom), 20000 counts/s^2;
// a pass whose ratio is kMaxStepsPerCount counts per spindle count or more
// is refused (4 TPI is 39).
// A pass whose carriage falls kServoMaxLag counts (260 um) behind its target
// stops (last=overspeed): the spindle turns too fast for the thread (the
// motor's 2134 counts/s are 521 rpm for 1 mm, 89 rpm for a 5.86 mm lead).
constexpr uint16_t kServoMaxLag = 64;
constexpr uint32_t kLeadscrewAccel = 20000;
constexpr uint32_t kLeadscrewMaxRate = 1800;
constexpr uint8_t kMaxStepsPerCount = 64;

// Hardware claims (hal/avr/claims.h, m16_servo_claims.h): Timer1 and OC1A
// (the PWM, and its overflow as the servo's sample clock), INT0 (the motor
// encoder), INT1 (the spindle), the UART, Timer0 (the time base).
using Claims = hal::ClaimSet<m16_servo_claims::kServo, m16_servo_claims::kSpindle, kClock, hal::claim::uart,
                             Axes::Claims::all>;

inline void init() {
  init_inputs();  // PD5 low (the bridge off), the inputs pulled up
  ServoIn1::low();
  ServoIn2::low();
  ServoIn1::output();
  ServoIn2::output();
}

}  // namespace board
