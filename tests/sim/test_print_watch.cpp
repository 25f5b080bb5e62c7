// The report's print measurements (sim/print_watch.h) tell a print that
// ended right from one that did not, on the m32 image with its hot end and
// switches: a cold extrusion is seen cold, a hot one hot; the drivers are
// enabled while the print runs and off after M84; the heater pin has high
// time while a target is set and none once M104 S0 has been in force for
// the plant's last 100 ms step; each G28 closes its switch twice.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "endstops.h"
#include "machine.h"
#include "print_watch.h"
#include "sim_fixture.h"
#include "thermal_plant.h"

namespace {

struct Rig {
  sim::Machine m{simtest::image("m32")};
  sim::ThermalPlant plant{m};
  sim::Endstops switches{m};
  sim::PrintWatch watch{m, &plant, &switches};
  void run(const std::vector<std::string>& lines) {
    for (const std::string& l : lines) m.serial().add_line(l);
    ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 120), sim::RunEnd::done);
    for (const sim::Response& r : m.serial().responses()) ASSERT_TRUE(sim::SerialHost::is_ok(r.answer)) << r.line;
  }
};

}  // namespace

TEST(PrintWatch, AColdExtrusionIsSeenCold) {
  Rig r;
  r.run({"G92 E0", "G1 E-1 F600", "G1 E0", "M104 S60"});
  EXPECT_FALSE(r.watch.extruded());  // back to where E was: no new filament
  r.run({"G1 E0.5"});
  ASSERT_TRUE(r.watch.extruded());
  EXPECT_LT(r.watch.sensor_c_at_first_extrusion(), 30);
  EXPECT_EQ(r.watch.switch_closes('X'), 1u);  // closed at the start (on its switch), never homed
}

TEST(PrintWatch, AHeatedPrintIsSeenHotAndItsEndSeenOff) {
  Rig r;
  r.run({"M104 S60", "G28", "M109 S60", "G92 E0", "G1 X20 Y20 E1 F1800"});
  ASSERT_TRUE(r.watch.extruded());
  EXPECT_GE(r.watch.sensor_c_at_first_extrusion(), 59);  // M109's window: 1 C
  EXPECT_EQ(r.watch.enabled_now(), "XYZE");
  EXPECT_GT(r.watch.heater_duty_last(), 0);
  EXPECT_EQ(r.watch.target_c_last(), 60);
  for (const char a : {'X', 'Y', 'Z'}) EXPECT_EQ(r.watch.switch_closes(a), 2u) << a;
  r.run({"M104 S0", "M84", "G4 P200"});  // the plant's 100 ms log step all after M104 S0
  EXPECT_EQ(r.watch.enabled_now(), "");
  EXPECT_FALSE(r.watch.heater_pin_now());
  EXPECT_EQ(r.watch.heater_duty_last(), 0);
  EXPECT_EQ(r.watch.target_c_last(), 0);
  r.run({"G28 X0"});
  EXPECT_EQ(r.watch.switch_closes('X'), 4u);
  EXPECT_EQ(r.watch.switch_closes('Y'), 2u);
}
