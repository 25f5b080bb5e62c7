// The pictures avrmotion-sim draws (--plot): well-formed SVG with a panel per
// axis and quantity, each on its own scale, ticks on 1-2-5 values, titled
// axes with units, distinct colours; the XY toolpath of G-code runs (equal
// scale, travel / feed / extrusion drawn apart, each step given to the line
// that made it); and the numbers behind them (tick chooser, velocity /
// acceleration from step events, interval histogram, toolpath attribution).
//
// This file: the panels of real runs and a hot end's row. The toolpath
// panel: test_pictures_toolpath.cpp; the toolpath's and the plots' numbers:
// test_toolpath.cpp, test_plot_numbers.cpp; the shared checks:
// picture_check.h.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "picture_check.h"
#include "sim_fixture.h"
#include "thermal_plant.h"
#include "xml_check.h"

namespace {

using picturetest::check_picture;
using picturetest::draw;
using picturetest::panel_y_ticks;
using picturetest::Picture;
using picturetest::texts;

// --- the pictures of real runs ---------------------------------------------

TEST(Pictures, UnoRunHasAPanelPerAxisAndQuantityEachOnItsOwnScale) {
  auto m = simtest::run("uno", {"MOVE X100 F400 A800", "MOVE Y-50 F300 A600", "MOVE Z4000 F40000 A300000",
                                "MOVE E10"});
  const Picture pic = draw(*m, "uno-pictures.svg");
  check_picture(pic, *m);
  // Own scales: Y's -2 mm and X's 4 mm are each drawn over their panel.
  const std::vector<double> y = panel_y_ticks(pic, 'Y', "position"), x = panel_y_ticks(pic, 'X', "position");
  ASSERT_FALSE(y.empty());
  ASSERT_FALSE(x.empty());
  EXPECT_LE(y.front(), -2);
  EXPECT_GE(y.front(), -2.5);
  EXPECT_EQ(y.back(), 0);
  EXPECT_EQ(x.front(), 0);
  EXPECT_GE(x.back(), 100 / 25.0);
  EXPECT_LE(x.back(), 5);
  // Z cruises at 40000 steps/s = 100 mm/s and accelerates at 1000 mm/s^2.
  const std::vector<double> zv = panel_y_ticks(pic, 'Z', "velocity"), za = panel_y_ticks(pic, 'Z', "acceleration");
  ASSERT_FALSE(zv.empty());
  ASSERT_FALSE(za.empty());
  EXPECT_GE(zv.back(), 100);
  EXPECT_LE(zv.back(), 120);
  EXPECT_GE(za.back(), 900);
  EXPECT_LE(za.back(), 1500);
  EXPECT_LE(za.front(), -900);
}

TEST(Pictures, FourAxesOfTheM32KeepFourColours) {
  auto m = simtest::run("m32", {"G91", "G1 X0.2 F1200", "G1 Y-0.15 F1200", "G1 Z0.05 F120", "G1 E0.3 F300"});
  ASSERT_EQ(m->axes().size(), 4u);
  check_picture(draw(*m, "m32-pictures.svg"), *m);
}

TEST(Pictures, PaletteHasEightClearlyDifferentColours) {
  std::vector<std::array<int, 3>> rgb;
  for (int i = 0; i < sim::kPaletteSize; ++i) {
    unsigned v = 0;
    ASSERT_EQ(std::sscanf(sim::palette_colour(i), "#%6x", &v), 1);
    rgb.push_back({int(v >> 16), int((v >> 8) & 255), int(v & 255)});
  }
  ASSERT_EQ(rgb.size(), 8u);
  for (size_t i = 0; i < rgb.size(); ++i) {
    // Readable on white: not too light.
    EXPECT_LT(0.299 * rgb[i][0] + 0.587 * rgb[i][1] + 0.114 * rgb[i][2], 200) << sim::palette_colour(int(i));
    for (size_t j = 0; j < i; ++j) {
      const double d = std::sqrt(std::pow(rgb[i][0] - rgb[j][0], 2) + std::pow(rgb[i][1] - rgb[j][1], 2) +
                                 std::pow(rgb[i][2] - rgb[j][2], 2));
      EXPECT_GT(d, 60) << sim::palette_colour(int(i)) << " vs " << sim::palette_colour(int(j));
    }
  }
}

TEST(Pictures, AnAxisThatNeverMovedIsDrawnFlat) {
  auto m = simtest::run("m16", {"MOVE U20 F500 A1000"});
  const Picture pic = draw(*m, "m16-still.svg");
  ASSERT_TRUE(pic.root);
  EXPECT_EQ(pic.panels.size(), 8u);
  const std::vector<double> z = panel_y_ticks(pic, 'Z', "position");
  ASSERT_FALSE(z.empty());
  EXPECT_LT(z.front(), 0);  // an empty range is widened around 0
  EXPECT_GT(z.back(), 0);
}

// A panel's data values at the pixels of its polyline `kind`, mapped through
// the panel's y tick labels (each label sits 4 px below its tick's line:
// sim/svg_panel.cpp).
std::vector<double> series_values(const Picture& pic, const char* panel_kind, const char* kind) {
  const xmlcheck::Element* panel = nullptr;
  for (const auto* p : pic.panels)
    if (p->attr_or("data-axis") == "T" && p->attr_or("data-kind") == panel_kind) panel = p;
  const xmlcheck::Element* series = nullptr;
  for (const auto* e : pic.series)
    if (e->attr_or("data-axis") == "T" && e->attr_or("data-kind") == kind) series = e;
  EXPECT_TRUE(panel && series) << panel_kind << " " << kind;
  if (!panel || !series) return {};
  const auto ticks = texts(*panel, "tick", "y");
  EXPECT_GE(ticks.size(), 2u);
  if (ticks.size() < 2) return {};
  const double v0 = std::strtod(ticks.front()->text.c_str(), nullptr), v1 = std::strtod(ticks.back()->text.c_str(), nullptr);
  const double p0 = std::strtod(ticks.front()->attr_or("y").c_str(), nullptr) - 4;
  const double p1 = std::strtod(ticks.back()->attr_or("y").c_str(), nullptr) - 4;
  std::vector<double> out;
  std::istringstream pts(series->attr_or("points"));
  for (std::string xy; pts >> xy;) {
    const double py = std::strtod(xy.substr(xy.find(',') + 1).c_str(), nullptr);
    out.push_back(v0 + (py - p0) * (v1 - v0) / (p1 - p0));
  }
  return out;
}

}  // namespace

TEST(Pictures, AHotEndRowShowsItsTemperaturesSetpointAndDuty) {
  // The m32 heats toward 200 C for 20 s: the picture gains a row of two
  // panels; the setpoint line sits at 0 until M104 (after 1 s), then at 200; the
  // thermistor climbs; the duty is full on while it is far below.
  sim::Machine m(simtest::image("m32"));
  sim::ThermalPlant plant(m);
  for (const char* l : {"G4 S1", "M400", "M104 S200", "G4 S20"}) m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(30) * m.f_cpu()), sim::RunEnd::done);
  const std::string path = simtest::temp_path("hot-end.svg");
  sim::write_run_plot(path, m, sim::PlotLabel{"hot end", sim::RunEnd::done, &plant});
  Picture pic;
  const std::string doc = simtest::slurp(path);
  std::remove(path.c_str());
  xmlcheck::Parser parser(doc);
  pic.root = parser.parse();
  ASSERT_TRUE(pic.root) << parser.error();
  pic.root->find_all([](const xmlcheck::Element& e) { return e.attr_or("class") == "panel"; }, pic.panels);
  pic.root->find_all([](const xmlcheck::Element& e) { return e.attr_or("class") == "series"; }, pic.series);
  EXPECT_EQ(pic.panels.size(), 4 * m.axes().size() + 2);
  const std::vector<double> setpoint = series_values(pic, "temperature", "setpoint");
  const std::vector<double> sensor = series_values(pic, "temperature", "sensor");
  const std::vector<double> duty = series_values(pic, "duty", "duty");
  ASSERT_GT(setpoint.size(), 100u);
  EXPECT_NEAR(setpoint.front(), 0, 1);
  EXPECT_NEAR(setpoint.back(), 200, 1);
  ASSERT_EQ(sensor.size(), plant.log().size());
  EXPECT_NEAR(sensor.front(), 25, 1);
  EXPECT_NEAR(sensor.back(), plant.sensor_c(), 1);
  EXPECT_GT(sensor.back(), 50);
  ASSERT_EQ(duty.size(), plant.log().size());
  EXPECT_NEAR(*std::max_element(duty.begin(), duty.end()), 1, 0.02);
  EXPECT_NEAR(duty.front(), 0, 0.02);
}

