// The hot end's row of a run picture (sim/plot.cpp), for a board with a
// heater and its simulated plant (sim/thermal_plant.h): temperature against
// time (the thermistor's reading, the heater block's, and the firmware's
// setpoint as it changed) | the heater's duty against time, each a 100 ms
// mean of the MOSFET pin (the plant's log, one point every 100 ms).
//
// Tagged as the other rows: <g class="panel" data-axis="T"
// data-kind="temperature|duty">, its series class="series" data-axis="T"
// data-kind="sensor|block|setpoint|duty".
#pragma once
#include <ostream>

#include "thermal_plant.h"

namespace sim {

constexpr double kThermalRowH = 210;

void draw_thermal_row(std::ostream& svg, const ThermalPlant& plant, double x0, double y0, double cell_w,
                      double t_end);

}  // namespace sim
