// The seed's DC-servo leadscrew for the simulated board: an L298 bridge, a
// brushed motor behind a 1:26 gearbox and its 30-slot encoder, on the pins
// the image's descriptor names (servo_pins: the bridge's enable = the PWM,
// IN1, IN2, the encoder's channel).
//
// Model (ServoParams)
//   The plant the seed identified (digest section 3, open-loop step response):
//       G(s) = 2.0866 / (s / 74.29 + 1)
//   from the PWM's duty count to the motor encoder's pulse rate, then an
//   integrator to position. Units, as the seed derived them: the input is
//   the duty count of its 10-bit PWM (OCR1A, 0..1023 of TOP 1023), the
//   output pulses of the motor encoder per second, one pulse = one slot of
//   the 30-slot disc = 1/780 of a leadscrew turn; so the gain is 2.0866
//   pulses/s per duty count, 2134.6 pulses/s at full duty (2.74 leadscrew
//   turns/s, 164 rpm, 8.7 mm/s of carriage), and the time constant 1/74.29
//   s = 13.46 ms. (The gain per unit of duty fraction would be 2.0866 x 1023
//   = 2134.6 pulses/s.)
//   The model does not average the PWM: the bridge's output is the
//   instantaneous input, +full scale while ENABLE is high with IN1 high and
//   IN2 low, -full scale with IN2 high and IN1 low, 0 otherwise (ENABLE high
//   with IN1 = IN2: the brake, the motor's terminals shorted; ENABLE low:
//   free running), and
//       tau dw/dt = gain x full_scale x v(t) - w,   dx/dt = w
//   is integrated exactly between the input's changes (piecewise constant
//   input: exponentials). tau is 1 / pole while ENABLE is high (driven or
//   braking: the identified plant), 1 / coast_pole while it is low (free
//   running: the seed identified no figure for it, so coast_pole defaults
//   to pole; a smaller one is a motor that runs on longer unbraked, and
//   slows the PWM's low phases too). The 15.6 kHz PWM (64 us) is well inside the
//   plant's 13.46 ms, so its duty is what moves the motor, and a spike or a
//   stray period on ENABLE moves it too.
//   Encoder: one channel, low for the first half of each pulse and high for
//   the second (x in pulses, pin high when frac(x) >= 0.5), so a falling
//   edge comes at every whole pulse forward and every half pulse backward:
//   a single-channel disc has no direction. The pin changes at the first
//   tick (every tick_cycles, and at every input change) after the position
//   crossed the edge: up to tick_cycles late (4 us at the default 64).
// Log: the position every log_every ticks (cycle, pulses, pulses/s) for the
// tests and the picture; the encoder's falling edges.
#pragma once
#include <cstdint>
#include <vector>

#include "machine.h"

namespace sim {

struct ServoParams {
  double gain = 2.0866;       // pulses/s per duty count
  double pole = 74.29;        // rad/s: 1 / the time constant
  double coast_pole = 0;      // rad/s while ENABLE is low (0: pole)
  double full_scale = 1023;   // duty counts at 100 % (the 10-bit PWM's TOP)
  double start_position = 0;  // pulses (0: mid-way between edges, + 0.25)
  uint32_t tick_cycles = 64;
  uint32_t log_every = 16;    // ticks between log entries (1024 cycles)
};

struct ServoSample {
  uint64_t cycle;
  double position;  // pulses, + = IN1's direction
  double speed;     // pulses/s
};

class DcServo {
 public:
  // Throws when the image's descriptor names no servo.
  DcServo(Machine& m, const ServoParams& p = ServoParams());
  DcServo(const DcServo&) = delete;
  DcServo& operator=(const DcServo&) = delete;

  // Brings the model up to the present and returns where the motor is.
  double position();
  double speed();
  const std::vector<ServoSample>& log() const { return log_; }
  const std::vector<uint64_t>& falling_edges() const { return falls_; }
  // The position at a cycle from the log (linear between entries).
  double position_at(uint64_t cycle) const;
  // Cycles the bridge drove the motor (ENABLE high, IN1 != IN2) and braked
  // it (ENABLE high, IN1 = IN2), since the start.
  uint64_t driven_cycles() const { return driven_cycles_; }
  uint64_t brake_cycles() const { return brake_cycles_; }

 private:
  static uint64_t on_tick(avr_t* avr, uint64_t when, void* param);
  void advance(uint64_t cycle);
  double drive() const;  // -1, 0, +1

  Machine& m_;
  ServoParams p_;
  uint8_t pin_en_, pin_in1_, pin_in2_, pin_enc_;
  bool en_ = false, in1_ = false, in2_ = false, enc_level_ = false;
  uint64_t at_ = 0;  // the model's time, cycles
  double x_, w_ = 0;
  uint32_t ticks_ = 0;
  uint64_t driven_cycles_ = 0, brake_cycles_ = 0;
  std::vector<ServoSample> log_;
  std::vector<uint64_t> falls_;
};

}  // namespace sim
