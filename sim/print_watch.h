// What a print's checks need, measured by the simulator from the pins and
// the plant, not from anything the firmware says: the report's "print"
// object (docs/simulator-report.md).
//
// Contract
//   Attach before the run, to a board with an extruder axis ('E', step/dir);
//   the hot end (a ThermalPlant) and the switches (Endstops) when the board
//   has them (nullptr otherwise). From then on:
//   - the first extrusion: the first E step edge that moves E forward (its
//     decoded position above every position it had before); its cycle and
//     the plant's thermistor and block temperatures at that moment;
//   - the switches: how many times each axis's contact closed
//     (Endstops::contact_changes(), the closing ones), the axes at the
//     start included (a switch closed at reset counts once);
//   - at the end (read when asked): each step/dir axis's driver enabled or
//     not, from its enable pin: an output at the active level (the
//     descriptor's option bit 0: active low) is enabled, a pin that is not
//     an output counts as disabled; the heater pin's level and its high
//     fraction over the plant's last 100 ms log step; the firmware's
//     setpoint as the plant logs it (its RAM, for information).
//   And two things the firmware says, read from its lines (free functions
//   below), each from the line the firmware printed just before the first
//   `ok` after a code's line went out (one line in flight) (so an M117 whose text is `Progress: 5%` is no M73;
//   a line a host numbered, `N<n> M117 ...*<sum>`, counts as well):
//   last_progress(), the percent of the last M73's `echo:Progress: <P>%`
//   (an M73 without P, whose echo has no percent, is passed over; -1: no
//   such line); last_message(), the text of the last M117's `echo:<text>`,
//   false when no M117 was answered so.
#pragma once
#include <cstdint>
#include <string>

#include "endstops.h"
#include "machine.h"
#include "thermal_plant.h"

namespace sim {

int last_progress(const SerialHost& serial);
bool last_message(const SerialHost& serial, std::string& text);

class PrintWatch {
 public:
  PrintWatch(Machine& m, const ThermalPlant* plant, const Endstops* switches);
  PrintWatch(const PrintWatch&) = delete;
  PrintWatch& operator=(const PrintWatch&) = delete;

  bool extruded() const { return first_extrusion_ != 0; }
  uint64_t first_extrusion_cycle() const { return first_extrusion_; }
  double sensor_c_at_first_extrusion() const { return sensor_c_; }
  double block_c_at_first_extrusion() const { return block_c_; }

  // Axis letters whose driver is enabled now, in the descriptor's order.
  std::string enabled_now() const;
  // Switch closings of axis `name` so far (0 for an axis without a switch).
  unsigned switch_closes(char name) const;
  // The heater pin now, its duty over the last log step, the setpoint
  // (-1 with no plant or no setpoint in the image).
  bool heater_pin_now() const;
  double heater_duty_last() const;
  double target_c_last() const;

  const ThermalPlant* plant() const { return plant_; }
  const Endstops* switches() const { return switches_; }
  Machine& machine() const { return m_; }

 private:
  Machine& m_;
  const ThermalPlant* plant_;
  const Endstops* switches_;
  double most_e_ = 0;
  uint64_t first_extrusion_ = 0;
  double sensor_c_ = -1, block_c_ = -1;
};

}  // namespace sim
