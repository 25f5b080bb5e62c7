// The checks the picture tests share (test_pictures.cpp,
// test_pictures_toolpath.cpp, test_toolpath.cpp, test_plot_numbers.cpp): a
// run's picture parsed into its panels and series, the checks every picture
// must pass (a panel per axis and quantity, titled axes with units, 1-2-5
// ticks, one colour per axis), and a toolpath's points as runs of line and
// move kind.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "plot.h"
#include "sim_fixture.h"
#include "toolpath.h"
#include "xml_check.h"

namespace picturetest {

// True when v is 1, 2 or 5 times a power of ten.
inline bool is_125(double v) {
  if (!(v > 0)) return false;
  const double m = v / std::pow(10.0, std::floor(std::log10(v)));
  for (const double c : {1.0, 2.0, 5.0, 10.0}) {
    if (std::fabs(m - c) < 1e-6 * c) return true;
  }
  return false;
}


struct Picture {
  std::unique_ptr<xmlcheck::Element> root;
  std::vector<const xmlcheck::Element*> panels, series;
};

inline Picture draw(sim::Machine& m, const std::string& file) {
  const std::string path = simtest::temp_path(file);
  sim::write_run_plot(path, m, sim::PlotLabel{"job.txt", sim::RunEnd::done});
  const std::string doc = simtest::slurp(path);
  Picture pic;
  xmlcheck::Parser parser(doc);
  pic.root = parser.parse();
  EXPECT_TRUE(pic.root) << parser.error();
  if (!pic.root) return pic;
  pic.root->find_all([](const xmlcheck::Element& e) { return e.attr_or("class") == "panel"; }, pic.panels);
  pic.root->find_all([](const xmlcheck::Element& e) { return e.attr_or("class") == "series"; }, pic.series);
  std::remove(path.c_str());
  return pic;
}

inline std::vector<const xmlcheck::Element*> texts(const xmlcheck::Element& panel, const std::string& cls,
                                                   const std::string& dir) {
  std::vector<const xmlcheck::Element*> out;
  panel.find_all(
      [&](const xmlcheck::Element& e) {
        return e.name == "text" && e.attr_or("class") == cls && e.attr_or("data-dir") == dir;
      },
      out);
  return out;
}

// "20 µs", "5 ms", "1 s" -> microseconds.
inline double interval_label_us(const std::string& label) {
  char* end = nullptr;
  const double v = std::strtod(label.c_str(), &end);
  const std::string unit = end;
  if (unit == " s") return v * 1e6;
  if (unit == " ms") return v * 1e3;
  if (unit == " \xc2\xb5s") return v;
  ADD_FAILURE() << "interval label without a unit: " << label;
  return NAN;
}

// Checks a linear axis's labels: evenly spaced by a 1-2-5 step. Returns the
// values.
inline std::vector<double> linear_ticks(const std::vector<const xmlcheck::Element*>& labels, const std::string& where) {
  std::vector<double> v;
  for (const auto* t : labels) v.push_back(std::strtod(t->text.c_str(), nullptr));
  EXPECT_GE(v.size(), 3u) << where;
  if (v.size() < 2) return v;
  const double step = v[1] - v[0];
  EXPECT_TRUE(is_125(step)) << where << ": step " << step;
  for (size_t i = 1; i < v.size(); ++i) EXPECT_NEAR(v[i] - v[i - 1], step, 1e-6 * step) << where;
  return v;
}

inline void check_picture(const Picture& pic, const sim::Machine& m) {
  ASSERT_TRUE(pic.root);
  EXPECT_EQ(pic.root->name, "svg");
  EXPECT_EQ(pic.root->attr_or("xmlns"), "http://www.w3.org/2000/svg");
  const char* kinds[] = {"position", "velocity", "acceleration", "intervals"};
  // Four panels per axis, and the toolpath when X and Y both moved.
  const sim::AxisTrace *x = m.axis('X'), *y = m.axis('Y');
  const bool toolpath = x && y && !x->step_cycles.empty() && !y->step_cycles.empty();
  ASSERT_EQ(pic.panels.size(), 4 * m.axes().size() + (toolpath ? 1 : 0));
  size_t toolpath_panels = 0;
  for (const auto* p : pic.panels) toolpath_panels += p->attr_or("data-kind") == "toolpath";
  EXPECT_EQ(toolpath_panels, toolpath ? 1u : 0u);
  std::set<std::string> colours;
  for (const sim::AxisTrace& a : m.axes()) {
    const std::string axis(1, a.name);
    std::set<std::string> axis_colours;
    for (const char* kind : kinds) {
      const std::string where = axis + " " + kind;
      const xmlcheck::Element* panel = nullptr;
      for (const auto* p : pic.panels) {
        if (p->attr_or("data-axis") == axis && p->attr_or("data-kind") == kind) panel = p;
      }
      ASSERT_TRUE(panel) << "no panel " << where;
      const xmlcheck::Element* series = nullptr;
      for (const auto* s : pic.series) {
        if (s->attr_or("data-axis") == axis && s->attr_or("data-kind") == kind) series = s;
      }
      // An axis with fewer than two steps has no intervals to draw: its
      // panel says so instead.
      if (std::string(kind) == "intervals" && a.step_cycles.size() < 2 && !series) continue;
      ASSERT_TRUE(series) << "no series " << where;
      axis_colours.insert(series->attr_or("stroke", series->attr_or("fill")));
      // Titled axes with units in parentheses.
      const auto xt = texts(*panel, "axis-title", "x"), yt = texts(*panel, "axis-title", "y");
      ASSERT_EQ(xt.size(), 1u) << where;
      ASSERT_EQ(yt.size(), 1u) << where;
      if (std::string(kind) != "intervals") {
        EXPECT_EQ(xt[0]->text, "time (s)") << where;
        const std::string unit = std::string(kind) == "position"   ? "(mm)"
                                 : std::string(kind) == "velocity" ? "(mm/s)"
                                                                   : "(mm/s\xc2\xb2)";
        EXPECT_NE(yt[0]->text.find(unit), std::string::npos) << where << ": " << yt[0]->text;
        const std::vector<double> t = linear_ticks(texts(*panel, "tick", "x"), where + " time");
        if (!t.empty()) {
          EXPECT_EQ(t.front(), 0) << where;
        }
        linear_ticks(texts(*panel, "tick", "y"), where + " y");
      } else {
        EXPECT_NE(xt[0]->text.find("interval"), std::string::npos) << where;
        const auto xl = texts(*panel, "tick", "x");
        EXPECT_GE(xl.size(), 2u) << where;
        for (const auto* l : xl) EXPECT_TRUE(is_125(interval_label_us(l->text))) << where << ": " << l->text;
        for (const auto* l : texts(*panel, "tick", "y")) {
          EXPECT_TRUE(is_125(std::strtod(l->text.c_str(), nullptr))) << where << ": " << l->text;
        }
        // One bar per occupied bin; the bars count every interval.
        uint64_t total = 0;
        for (const auto& bar : series->children)
          total += std::strtoull(bar->attr_or("data-count").c_str(), nullptr, 10);
        EXPECT_EQ(total, a.step_cycles.size() - 1) << where;
      }
    }
    EXPECT_EQ(axis_colours.size(), 1u) << axis << ": one colour in all its panels";
    colours.insert(*axis_colours.begin());
  }
  EXPECT_EQ(colours.size(), m.axes().size()) << "every axis has its own colour";
}

// The y-axis tick values of one panel.
inline std::vector<double> panel_y_ticks(const Picture& pic, char axis, const char* kind) {
  for (const auto* p : pic.panels) {
    if (p->attr_or("data-axis") == std::string(1, axis) && p->attr_or("data-kind") == kind) {
      std::vector<double> v;
      for (const auto* t : texts(*p, "tick", "y")) v.push_back(std::strtod(t->text.c_str(), nullptr));
      return v;
    }
  }
  return {};
}

// The path's points as (response index, kind, number of points) runs.
struct Stretch {
  int line;
  sim::MoveKind kind;
  size_t points;
  bool operator==(const Stretch& o) const { return line == o.line && kind == o.kind && points == o.points; }
};
inline std::ostream& operator<<(std::ostream& os, const Stretch& s) {
  return os << "{line " << s.line << ", " << sim::move_kind_name(s.kind) << ", " << s.points << "}";
}

inline std::vector<Stretch> stretches(const sim::Toolpath& tp) {
  std::vector<Stretch> out;
  for (size_t i = 1; i < tp.points.size(); ++i) {
    const sim::ToolpathPoint& p = tp.points[i];
    if (out.empty() || out.back().line != p.line || out.back().kind != p.kind) out.push_back({p.line, p.kind, 0});
    ++out.back().points;
  }
  return out;
}

}  // namespace picturetest
