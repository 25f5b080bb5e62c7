#include "plot_thermal.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "svg_panel.h"
#include "ticks.h"

namespace sim {

using namespace svg;

namespace {

const char* const kSensor = "#d55e00", *const kBlock = "#e69f00", *const kSetpoint = "#000000",
                  *const kDuty = "#0072b2";

// One series of the log; points where `value` is NaN are left out.
template <typename F>
void series(const Panel& p, const std::vector<ThermalSample>& log, const char* kind, const char* colour,
            const char* dash, F value) {
  p.svg << "<polyline class='series' data-axis='T' data-kind='" << kind << "' fill='none' stroke='" << colour
        << "' stroke-width='1.4'" << (dash ? std::string(" stroke-dasharray='") + dash + "'" : std::string())
        << " points='";
  bool first = true;
  for (const ThermalSample& s : log) {
    const double v = value(s);
    if (std::isnan(v)) continue;
    p.svg << (first ? "" : " ") << num(p.px(s.t_s)) << "," << num(p.py(v));
    first = false;
  }
  p.svg << "'/>\n";
}

}  // namespace

void draw_thermal_row(std::ostream& svg, const ThermalPlant& plant, double x0, double y0, double cell_w,
                      double t_end) {
  const std::vector<ThermalSample>& log = plant.log();
  const Ticks time = nice_ticks(0, t_end, 6, false);
  double lo = plant.params().ambient_c, hi = lo + 1;
  for (const ThermalSample& s : log) {
    lo = std::min({lo, s.sensor_c, s.block_c});
    hi = std::max({hi, s.sensor_c, s.block_c, std::isnan(s.target_c) ? hi : s.target_c});
  }
  {
    const Ticks y = nice_ticks(lo, hi + 0.05 * (hi - lo));  // the setpoint's line off the frame
    Panel p{svg, x0, y0, cell_w, kThermalRowH, 0, t_end, y.lo, y.hi};
    open_panel(p, "T", "temperature", "hot end: thermistor (orange), heater block (yellow), setpoint (black, dashed)",
               kSensor, time.values, labels(time), y.values, labels(y), "time (s)", "temperature (\xc2\xb0""C)");
    series(p, log, "block", kBlock, nullptr, [](const ThermalSample& s) { return s.block_c; });
    series(p, log, "sensor", kSensor, nullptr, [](const ThermalSample& s) { return s.sensor_c; });
    series(p, log, "setpoint", kSetpoint, "5,3", [](const ThermalSample& s) { return s.target_c; });
    svg << "</g>\n";
  }
  {
    const Ticks y = nice_ticks(0, 1);
    Panel p{svg, x0 + cell_w, y0, cell_w, kThermalRowH, 0, t_end, y.lo, y.hi};
    open_panel(p, "T", "duty", "heater duty (100 ms means of the MOSFET pin)", kDuty, time.values, labels(time),
               y.values, labels(y), "time (s)", "duty");
    series(p, log, "duty", kDuty, nullptr, [](const ThermalSample& s) { return s.duty; });
    svg << "</g>\n";
  }
}

}  // namespace sim
