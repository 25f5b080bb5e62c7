// The m32 image (or the m32-grbl) with the simulated 40 W hot end
// (sim/thermal_plant.h) that the heater tests drive (test_heater.cpp,
// test_heater_faults.cpp, test_heater_grbl.cpp): lines
// sent, simulated time run, and when the heater pin, the thermistor and the
// answers did what.
#pragma once
#include <algorithm>
#include <memory>
#include <regex>
#include <string>

#include "sim_fixture.h"
#include "thermal_plant.h"

namespace heatertest {

constexpr double kHz = 16e6;

struct HotEnd {
  std::unique_ptr<sim::Machine> m;
  std::unique_ptr<sim::ThermalPlant> plant;

  explicit HotEnd(double initial_c = 25, double heater_w = 40, const char* image = "m32")
      : m(new sim::Machine(simtest::image(image))) {
    sim::ThermalParams p;
    p.initial_c = initial_c;
    p.heater_w = heater_w;
    plant.reset(new sim::ThermalPlant(*m, p));
  }
  void send(const std::string& line) { m->serial().add_line(line); }
  void run_until(double t_s) {
    const uint64_t end = uint64_t(t_s * kHz);
    m->run([&] { return m->cycles() >= end; }, end - std::min(end, m->cycles()) + 1);
  }
  double now_s() const { return double(m->cycles()) / kHz; }
  // The first received line starting with `prefix`, and when it ended (s); -1 if none.
  double line_time(const std::string& prefix, std::string* line = nullptr) const {
    const auto& r = m->serial().received();
    for (size_t i = 0; i < r.size(); ++i) {
      if (r[i].rfind(prefix, 0) == 0) {
        if (line) *line = r[i];
        return double(m->serial().received_cycles()[i]) / kHz;
      }
    }
    return -1;
  }
  // The answer to the last script line equal to `script_line`.
  const sim::Response* answer_of(const std::string& script_line) const {
    const sim::Response* found = nullptr;
    for (const sim::Response& r : m->serial().responses())
      if (r.line == script_line) found = &r;
    return found;
  }
  // When the heater pin was last high (s): now if it is high, 0 if never.
  double last_high_s() const {
    const auto& e = plant->heater_pin();
    if (!e.empty() && e.back().level) return now_s();
    for (size_t i = e.size(); i-- > 1;)
      if (!e[i].level && e[i - 1].level) return double(e[i].cycle) / kHz;
    return 0;
  }
  // When the plant's thermistor first crossed `c` going up (or down), -1 if never.
  double crossed_s(double c, bool up) const {
    for (const sim::ThermalSample& s : plant->log())
      if (up ? s.sensor_c > c : s.sensor_c < c) return s.t_s;
    return -1;
  }
};

// A status line: "T:<sensor> /<target> @:<duty>".
inline const std::regex kStatus(R"(T:-?\d+\.\d\d /\d+\.\d\d @:\d+)");

}  // namespace heatertest
