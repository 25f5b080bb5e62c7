// A hot end for the simulated board: the heater's MOSFET pin in, the
// thermistor's ADC input out, with faults to inject.
//
// Model (ThermalParams, defaults a typical 40 W hot end, the same plant the
// heater core's host tests use: docs/heater.md)
//   heater power  P = heater_w while the PWM pin is high (its high time in
//                 each 1 ms step, from the pin's edges), arriving delay_s
//                 later at the block (heater cartridge to block);
//   block         C dT/dt = P - (loss + fan * fan_w_per_k) (T - ambient),
//                 C = capacity_j_per_k; with the defaults full power settles
//                 at 305 C and takes 82 s from 25 C to 200 C, and 200 C needs
//                 25 W (62.5 %, 8.75 W more with the fan at 100 %);
//   thermistor    first-order lag behind the block, sensor_tau_s;
//   divider       NTC (r0 at t0, beta) from the ADC input to ground, pullup_ohm
//                 to the 5 V reference: Vin = Vref R / (R + R_pullup), plus
//                 Gaussian noise of noise_mv (a fixed seed: every run is the
//                 same), fresh for every conversion (simavr's ADC trigger).
//                 simavr converts Vin * 1023 / Vref; the input is scaled by
//                 1024 / 1023 so the codes are the datasheet's 1024 Vin / Vref.
//   Euler steps of 1 ms (a simavr cycle timer), far below every time
//   constant (3 s and more).
// Faults (inject() from that moment on, inject_at() at a time)
//   sensor_open: Vin = Vref (the NTC's wire broken: the pull-up alone);
//   sensor_shorted: Vin = 0; heater_disconnected: no power whatever the pin
//   says; heater_stuck_on: full power whatever the pin says (a shorted
//   MOSFET). fan(fraction) changes the extra loss at once.
// Log: every 100 ms the time, block and thermistor temperatures and the
// pin's duty over those 100 ms; peak and final thermistor temperature.
#pragma once
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "board_info.h"
#include "machine.h"

namespace sim {

struct ThermalParams {
  double ambient_c = 25;
  double initial_c = 25;        // block and thermistor at reset
  double heater_w = 40;
  double capacity_j_per_k = 12;
  double loss_w_per_k = 1.0 / 7;  // to still air
  double fan_w_per_k = 0.05;      // more, with the part fan at 100 %
  double sensor_tau_s = 3;
  double delay_s = 1;
  double r0_ohm = 100000, t0_c = 25, beta = 3950, pullup_ohm = 4700;
  double vref_mv = 5000;
  double noise_mv = 3;
};

// The divider's ADC input for a thermistor at `c`, without noise, scaled for
// simavr's converter (see above).
uint32_t thermistor_input_mv(const ThermalParams& p, double c);

enum class ThermalFault { none, sensor_open, sensor_shorted, heater_disconnected, heater_stuck_on };

// "open", "shorted", "disconnected", "stuck_on" -> the fault; false if none.
bool parse_thermal_fault(const std::string& name, ThermalFault& fault);
const char* thermal_fault_name(ThermalFault f);

struct ThermalSample {
  double t_s;
  double block_c, sensor_c;
  double duty;      // the pin's high fraction over the 100 ms before t_s
  double target_c;  // the firmware's setpoint then (its heater::target_), NaN if the image has none
};

class ThermalPlant {
 public:
  // Attaches to the heater the image's descriptor names (board().heater_pin,
  // heater_adc); throws if the board has none.
  ThermalPlant(Machine& m, const ThermalParams& p = ThermalParams());
  ThermalPlant(const ThermalPlant&) = delete;
  ThermalPlant& operator=(const ThermalPlant&) = delete;

  void inject(ThermalFault f) { fault_ = f; }
  void fan(double fraction) { fan_ = fraction; }
  // The same, at a simulated time (seconds from reset).
  void inject_at(double t_s, ThermalFault f) { events_.push_back({uint64_t(t_s * m_.f_cpu()), f, -1}); }
  void fan_at(double t_s, double fraction) { events_.push_back({uint64_t(t_s * m_.f_cpu()), fault_, fraction}); }
  ThermalFault fault() const { return fault_; }

  double block_c() const { return block_; }
  double sensor_c() const { return sensor_; }
  double peak_sensor_c() const { return peak_; }
  const std::vector<ThermalSample>& log() const { return log_; }
  const std::vector<PinEdge>& heater_pin() const { return *edges_; }  // the MOSFET pin's edges
  const ThermalParams& params() const { return p_; }

 private:
  static uint64_t on_step(avr_t* avr, uint64_t when, void* param);
  static void on_adc_trigger(avr_irq_t* irq, uint32_t value, void* param);
  void step(uint64_t now);
  uint32_t input_mv();

  Machine& m_;
  ThermalParams p_;
  uint8_t adc_channel_;
  uint64_t step_cycles_;
  const std::vector<PinEdge>* edges_;
  size_t next_edge_ = 0;
  bool level_ = false;
  uint64_t last_cycle_ = 0;
  std::vector<double> pipe_;  // delayed power fractions, one per step
  size_t pipe_at_ = 0;
  double block_, sensor_, peak_;
  double fan_ = 0;
  ThermalFault fault_ = ThermalFault::none;
  double high_cycles_ = 0;  // pin high time in the log interval
  ElfSymbol target_;        // firmware/services/heater.cpp's setpoint (0.01 C)
  unsigned steps_in_log_ = 0;
  std::vector<ThermalSample> log_;
  struct Event {
    uint64_t cycle;
    ThermalFault fault;
    double fan;  // < 0: a fault event
  };
  std::vector<Event> events_;
  std::mt19937 rng_{20261201};
  std::normal_distribution<double> noise_{0.0, 1.0};
};

}  // namespace sim
