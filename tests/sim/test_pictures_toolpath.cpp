// The XY toolpath panel of real G-code runs (avrmotion-sim --plot): equal
// scale, titled axes in mm, 1-2-5 ticks, travel / feed / extrusion drawn
// apart with a legend, the path joined and ending where the decoder has X
// and Y; none unless X and Y both moved. The numbers behind it:
// test_toolpath.cpp.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "motion.h"
#include "picture_check.h"
#include "sim_fixture.h"
#include "toolpath.h"
#include "xml_check.h"

namespace {

using picturetest::check_picture;
using picturetest::draw;
using picturetest::linear_ticks;
using picturetest::Picture;
using picturetest::stretches;
using picturetest::Stretch;
using picturetest::texts;
using sim::MoveKind;

// --- the toolpath panel of real runs ----------------------------------------

std::vector<std::string> example_job(const std::string& file) {
  std::ifstream in(std::string(AVRMOTION_SOURCE_DIR) + "/examples/" + file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));  // as avrmotion-sim reads a job
    const size_t end = line.find_last_not_of(" \t\r");
    if (end != std::string::npos) lines.push_back(line.substr(0, end + 1));
  }
  return lines;
}

// A linear axis of a panel from its tick labels: value <-> pixel.
struct TickScale {
  double v0 = 0, p0 = 0, v1 = 1, p1 = 1;
  double mm_per_px() const { return std::fabs((v1 - v0) / (p1 - p0)); }
  double value(double px) const { return v0 + (px - p0) * (v1 - v0) / (p1 - p0); }
};

TickScale tick_scale(const xmlcheck::Element& panel, const std::string& dir, const std::string& where) {
  const auto labels = texts(panel, "tick", dir);
  linear_ticks(labels, where + " " + dir);  // 1-2-5, evenly spaced, at least three
  TickScale s;
  if (labels.size() < 2) return s;
  // An x label is centred on its tick; a y label's baseline is 4 px below it
  // (sim/plot.cpp).
  const auto pixel = [&](const xmlcheck::Element* t) {
    return dir == "x" ? std::strtod(t->attr_or("x").c_str(), nullptr)
                      : std::strtod(t->attr_or("y").c_str(), nullptr) - 4;
  };
  s.v0 = std::strtod(labels.front()->text.c_str(), nullptr);
  s.v1 = std::strtod(labels.back()->text.c_str(), nullptr);
  s.p0 = pixel(labels.front());
  s.p1 = pixel(labels.back());
  return s;
}

std::vector<std::pair<double, double>> polyline_points(const xmlcheck::Element& e) {
  std::vector<std::pair<double, double>> out;
  std::istringstream in(e.attr_or("points"));
  double x, y;
  char comma;
  while (in >> x >> comma >> y) out.push_back({x, y});
  return out;
}

struct ToolpathPicture {
  const xmlcheck::Element* panel = nullptr;
  std::vector<const xmlcheck::Element*> lines;  // the path's polylines, in order
  TickScale x, y;
};

// The toolpath panel: present once, titled axes in mm, 1-2-5 ticks, equal
// scale, and its path ending at the final decoded position.
ToolpathPicture check_toolpath_panel(const Picture& pic, const sim::Machine& m) {
  ToolpathPicture tp;
  for (const auto* p : pic.panels) {
    if (p->attr_or("data-kind") == "toolpath") {
      EXPECT_FALSE(tp.panel) << "two toolpath panels";
      tp.panel = p;
    }
  }
  if (!tp.panel) {
    ADD_FAILURE() << "no toolpath panel";
    return tp;
  }
  EXPECT_EQ(tp.panel->attr_or("data-axis"), "XY");
  const auto xt = texts(*tp.panel, "axis-title", "x"), yt = texts(*tp.panel, "axis-title", "y");
  EXPECT_EQ(xt.size(), 1u);
  EXPECT_EQ(yt.size(), 1u);
  if (xt.size() == 1 && yt.size() == 1) {
    EXPECT_EQ(xt[0]->text, "X (mm)");
    EXPECT_EQ(yt[0]->text, "Y (mm)");
  }
  tp.x = tick_scale(*tp.panel, "x", "toolpath");
  tp.y = tick_scale(*tp.panel, "y", "toolpath");
  EXPECT_NEAR(tp.x.mm_per_px() / tp.y.mm_per_px(), 1, 0.01) << "equal scale on both axes";
  tp.panel->find_all(
      [](const xmlcheck::Element& e) { return e.name == "polyline" && e.attr_or("data-kind") == "toolpath"; },
      tp.lines);
  EXPECT_FALSE(tp.lines.empty());
  if (tp.lines.empty()) return tp;
  // The path starts at the origin and ends where the decoder has X and Y.
  const auto first = polyline_points(*tp.lines.front()), last = polyline_points(*tp.lines.back());
  EXPECT_GE(first.size(), 2u);
  EXPECT_GE(last.size(), 2u);
  if (first.empty() || last.empty()) return tp;
  const double px_mm = tp.x.mm_per_px();
  EXPECT_NEAR(tp.x.value(first.front().first), 0, 1.0 * px_mm);
  EXPECT_NEAR(tp.y.value(first.front().second), 0, 1.0 * px_mm);
  const sim::AxisTrace &ax = *m.axis('X'), &ay = *m.axis('Y');
  const double end_x = double(ax.position) * sim::mm_per_unit(ax), end_y = double(ay.position) * sim::mm_per_unit(ay);
  EXPECT_NEAR(tp.x.value(last.back().first), end_x, 1.0 * px_mm);
  EXPECT_NEAR(tp.y.value(last.back().second), end_y, 1.0 * px_mm);
  // Consecutive polylines join: each starts where the one before ended.
  for (size_t i = 1; i < tp.lines.size(); ++i) {
    const auto a = polyline_points(*tp.lines[i - 1]), b = polyline_points(*tp.lines[i]);
    if (a.empty() || b.empty()) continue;
    EXPECT_EQ(a.back(), b.front()) << "polyline " << i;
  }
  return tp;
}

// The distinct style of a kind of move, as the polylines of that kind carry
// it (all alike) and as its legend entry shows it.
struct Style {
  std::string stroke, width, dash;
  bool operator==(const Style& o) const { return stroke == o.stroke && width == o.width && dash == o.dash; }
};

std::map<std::string, Style> styles(const Picture& pic, const ToolpathPicture& tp) {
  std::map<std::string, Style> out;
  for (const auto* l : tp.lines) {
    const std::string kind = l->attr_or("data-move");
    const Style s{l->attr_or("stroke"), l->attr_or("stroke-width"), l->attr_or("stroke-dasharray")};
    if (out.count(kind)) {
      EXPECT_TRUE(out[kind] == s) << kind << ": one style for all its polylines";
    }
    out[kind] = s;
  }
  // The legend: an entry per kind, drawn in that kind's style.
  std::vector<const xmlcheck::Element*> legend;
  pic.root->find_all([](const xmlcheck::Element& e) { return e.attr_or("class") == "move-legend"; }, legend);
  std::set<std::string> listed;
  for (const auto* g : legend) {
    const std::string kind = g->attr_or("data-move");
    for (const auto& c : g->children) {
      if (c->name != "line") continue;
      listed.insert(kind);
      if (out.count(kind)) {
        EXPECT_TRUE(out[kind] ==
                    (Style{c->attr_or("stroke"), c->attr_or("stroke-width"), c->attr_or("stroke-dasharray")}))
            << kind << ": the legend shows the path's style";
      }
    }
  }
  EXPECT_EQ(listed, (std::set<std::string>{"extrusion", "feed", "travel"}));
  return out;
}

TEST(Pictures, PlotterJobDrawsItsToolpathWithTravelAndFeedApart) {
  auto m = simtest::run("uno", example_job("uno-plotter.gcode"), 60);
  // The numbers behind the panel: the pen (Z at 0) decides; each line's
  // steps go to that line, all on the straight line from its start to its
  // target (each diamond edge is answered before the one before it ends).
  const auto& responses = m->serial().responses();
  const sim::Toolpath tp = sim::trace_toolpath(m->axes(), responses);
  ASSERT_TRUE(tp.present);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::pen);
  EXPECT_EQ(tp.pen_down_mm, 0);
  const std::map<std::string, std::pair<double, double>> ends = {
      {"G0 X10 Y10", {10, 10}}, {"G1 X20 F300", {20, 10}},     {"G1 Y20", {20, 20}},     {"G1 X10", {10, 20}},
      {"G1 Y10", {10, 10}},     {"G1 X15 Y10 F300", {15, 10}}, {"G1 X20 Y15", {20, 15}}, {"G1 X15 Y20", {15, 20}},
      {"G1 X10 Y15", {10, 15}}, {"G1 X15 Y10", {15, 10}},      {"G0 X0 Y0", {0, 0}}};
  std::set<std::string> seen;
  for (size_t i = 1; i < tp.points.size();) {
    const int line = tp.points[i].line;
    ASSERT_GE(line, 0);
    std::string text = responses[size_t(line)].line;
    text = text.substr(0, text.find(';'));
    text = text.substr(0, text.find_last_not_of(' ') + 1);
    ASSERT_TRUE(ends.count(text)) << "XY steps attributed to \"" << text << "\"";
    seen.insert(text);
    const sim::ToolpathPoint start = tp.points[i - 1];
    const auto end = ends.at(text);
    size_t j = i;
    for (; j < tp.points.size() && tp.points[j].line == line; ++j) {
      // On the segment start-end, within a step (0.04 mm).
      const double dx = end.first - start.x, dy = end.second - start.y, len = std::hypot(dx, dy);
      const double off = std::fabs((tp.points[j].x - start.x) * dy - (tp.points[j].y - start.y) * dx) / len;
      ASSERT_LT(off, 0.041) << text << " point " << j;
      // Feed exactly where the pen is down: from the first G1 Z0 to the last G1 Z2.
      const bool drawing = text.rfind("G1", 0) == 0;
      ASSERT_EQ(tp.points[j].kind, drawing ? MoveKind::feed : MoveKind::travel) << text;
    }
    EXPECT_NEAR(tp.points[j - 1].x, end.first, 1e-9) << text;
    EXPECT_NEAR(tp.points[j - 1].y, end.second, 1e-9) << text;
    i = j;
  }
  EXPECT_EQ(seen.size(), ends.size());
  // The case the attribution exists for: lines answered before the line
  // before them had made its last step (the diamond's edges).
  int early = 0, previous = -1;
  uint64_t previous_end = 0;
  for (size_t i = 1; i < tp.points.size(); ++i) {
    const int line = tp.points[i].line;
    if (line != previous && previous >= 0 && responses[size_t(line)].answer_cycle < previous_end) ++early;
    previous = line;
    previous_end = tp.points[i].cycle;
  }
  EXPECT_GE(early, 3);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::travel)], std::hypot(10, 10) + std::hypot(15, 10), 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::feed)], 40 + 5 + 4 * std::hypot(5, 5), 1e-9);

  // The picture.
  const Picture pic = draw(*m, "uno-toolpath.svg");
  check_picture(pic, *m);
  const ToolpathPicture panel = check_toolpath_panel(pic, *m);
  const auto st = styles(pic, panel);
  ASSERT_TRUE(st.count("travel"));
  ASSERT_TRUE(st.count("feed"));
  EXPECT_FALSE(st.count("extrusion"));  // no E axis on the Uno
  EXPECT_FALSE(st.at("travel").dash.empty()) << "travel dashed";
  EXPECT_TRUE(st.at("feed").dash.empty()) << "feed solid";
  EXPECT_NE(st.at("travel").stroke, st.at("feed").stroke);
  // The drawing spans the square: ticks reach 0 and 20 mm on both axes.
  EXPECT_LE(panel.x.v0, 0);
  EXPECT_GE(panel.x.v1, 20);
  EXPECT_LE(panel.y.v0, 0);
  EXPECT_GE(panel.y.v1, 20);
}

TEST(Pictures, PrinterJobShowsExtrusionFeedAndTravel) {
  // The m32 as a printer (X Y Z E at 1000 steps per mm): a perimeter with E,
  // retraction, travel, and a wipe of the same axes as the travel before it
  // (queued behind it: answered while the travel still runs).
  const std::vector<std::string> job = {
      "G21 G90",       "M83",           "G0 X2 Y2",       "G1 E0.4 F1800", "G1 X6 Y2 E0.2 F600", "G1 X6 Y6 E0.2",
      "G1 X2 Y6 E0.2", "G1 X2 Y2 E0.2", "G1 E-0.4 F1800", "G0 X5 Y1",      "G1 X1 Y1.5 F600",    "G0 X3.5 Y0.5"};
  auto m = simtest::run("m32", job, 60);
  EXPECT_TRUE(m->serial().errors().empty());
  const auto& responses = m->serial().responses();
  ASSERT_EQ(responses.size(), job.size());
  const sim::Toolpath tp = sim::trace_toolpath(m->axes(), responses);
  ASSERT_TRUE(tp.present);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::extrusion);
  EXPECT_EQ(stretches(tp), (std::vector<Stretch>{{2, MoveKind::travel, 2000},
                                                 {4, MoveKind::extrusion, 4000},
                                                 {5, MoveKind::extrusion, 4000},
                                                 {6, MoveKind::extrusion, 4000},
                                                 {7, MoveKind::extrusion, 4000},
                                                 {9, MoveKind::travel, 3000},
                                                 {10, MoveKind::feed, 4000},
                                                 {11, MoveKind::travel, 2500}}));
  // The case the attribution exists for: the wipe was answered before the
  // travel's last step, so "the last line answered" would have been wrong.
  uint64_t travel_end = 0;
  for (const sim::ToolpathPoint& p : tp.points) {
    if (p.line == 9) travel_end = p.cycle;
  }
  EXPECT_LT(responses[10].answer_cycle, travel_end);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::extrusion)], 16, 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::feed)], std::hypot(4, 0.5), 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::travel)], std::hypot(2, 2) + std::hypot(3, 1) + std::hypot(2.5, 1), 1e-9);

  const Picture pic = draw(*m, "m32-toolpath.svg");
  check_picture(pic, *m);
  const ToolpathPicture panel = check_toolpath_panel(pic, *m);
  const auto st = styles(pic, panel);
  ASSERT_EQ(st.size(), 3u);
  EXPECT_EQ(st.at("extrusion").stroke, st.at("feed").stroke) << "extrusion in the feed colour";
  EXPECT_GT(std::strtod(st.at("extrusion").width.c_str(), nullptr),
            1.5 * std::strtod(st.at("feed").width.c_str(), nullptr))
      << "extrusion thicker";
  EXPECT_TRUE(st.at("extrusion").dash.empty());
  EXPECT_TRUE(st.at("feed").dash.empty());
  EXPECT_FALSE(st.at("travel").dash.empty());
  EXPECT_NE(st.at("travel").stroke, st.at("feed").stroke);
  // The end is away from the origin here: (3.5, 0.5).
  EXPECT_NEAR(double(m->axis('X')->position), 3500, 0);
  EXPECT_NEAR(double(m->axis('Y')->position), 500, 0);
}

TEST(Pictures, NoToolpathUnlessXAndYBothMoved) {
  // The m16 (Z and U): no X or Y; its picture keeps its size.
  auto lathe = simtest::run("m16", {"MOVE Z500 F5000 A20000"});
  const Picture a = draw(*lathe, "m16-no-toolpath.svg");
  check_picture(a, *lathe);
  ASSERT_TRUE(a.root);
  EXPECT_EQ(a.root->attr_or("height"), "548.0");  // 2 x 10 + 108 + 2 x 210, as before the toolpath
  // The Uno moving X alone.
  auto uno = simtest::run("uno", {"G1 X5 F600"});
  const Picture b = draw(*uno, "uno-x-only.svg");
  check_picture(b, *uno);
  std::vector<const xmlcheck::Element*> legend;
  ASSERT_TRUE(b.root);
  b.root->find_all([](const xmlcheck::Element& e) { return e.attr_or("class") == "move-legend"; }, legend);
  EXPECT_TRUE(legend.empty());
}

}  // namespace
