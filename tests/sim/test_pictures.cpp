// The pictures avrmotion-sim draws (--plot): well-formed SVG with a panel per
// axis and quantity, each on its own scale, ticks on 1-2-5 values, titled
// axes with units, distinct colours; the XY toolpath of G-code runs (equal
// scale, travel / feed / extrusion drawn apart, each step given to the line
// that made it); and the numbers behind them (tick chooser, velocity /
// acceleration from step events, interval histogram, toolpath attribution).
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "motion.h"
#include "plot.h"
#include "sim_fixture.h"
#include "ticks.h"
#include "thermal_plant.h"
#include "toolpath.h"
#include "xml_check.h"

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Unique per process: several build trees may run their tests at once.
std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "avrmotion-" + std::to_string(getpid()) + "-" + name;
}

// True when v is 1, 2 or 5 times a power of ten.
bool is_125(double v) {
  if (!(v > 0)) return false;
  const double m = v / std::pow(10.0, std::floor(std::log10(v)));
  for (const double c : {1.0, 2.0, 5.0, 10.0}) {
    if (std::fabs(m - c) < 1e-6 * c) return true;
  }
  return false;
}

// --- the tick chooser, against an independent brute-force reference -------

// The contract of sim::nice_ticks, computed the slow way: walk the 1-2-5
// values upwards and take the first whose widened range has at most
// `max_intervals` steps. Values within 1e-9 of a step of a multiple count as
// on it.
double reference_step(double lo, double hi, int max_intervals) {
  if (lo == hi) {
    const double pad = std::max(1.0, 0.1 * std::fabs(lo));
    lo -= pad;
    hi += pad;
  }
  for (int e = -20; e <= 20; ++e) {
    for (const int m : {1, 2, 5}) {
      const double step = m * std::pow(10.0, e);
      const double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
      if (last - first <= max_intervals) return step;
    }
  }
  return NAN;
}

TEST(Ticks, HandPickedRanges) {
  struct Case {
    double lo, hi;
    double step, first, last;
  };
  // The ranges: a 9.32 s run, a 117.5 mm span, and the others.
  const Case cases[] = {
      {0, 9.32064, 2, 0, 10},
      {0, 117.5, 20, 0, 120},
      {-10, 0, 2, -10, 0},
      {0, 500, 100, 0, 500},
      {0, 0.5, 0.1, 0, 0.5},
      {-1000.3, 1000.3, 500, -1500, 1500},
      {0, 1, 0.2, 0, 1},
      {5, 5, 0.5, 4, 6},
      {-10, 20, 5, -10, 20},
      {0, 20.0063, 5, 0, 25},
      {0.0013, 0.0021, 0.0002, 0.0012, 0.0022},
      {-2.5e6, 1.2e6, 1e6, -3e6, 2e6},
      {0.3, 0.7, 0.1, 0.3, 0.7},  // 0.3 / 0.1 is 2.9999999999999996
  };
  for (const Case& c : cases) {
    const sim::Ticks t = sim::nice_ticks(c.lo, c.hi);
    EXPECT_NEAR(t.step, c.step, 1e-12 * c.step) << c.lo << ".." << c.hi;
    EXPECT_NEAR(t.lo, c.first, 1e-9 * c.step) << c.lo << ".." << c.hi;
    EXPECT_NEAR(t.hi, c.last, 1e-9 * c.step) << c.lo << ".." << c.hi;
  }
  const sim::Ticks time = sim::nice_ticks(0, 9.32064, 6, false);
  EXPECT_EQ(time.values, (std::vector<double>{0, 2, 4, 6, 8}));
  EXPECT_DOUBLE_EQ(time.hi, 9.32064);
  const sim::Ticks tenths = sim::nice_ticks(0, 0.5);
  std::vector<std::string> labels;
  for (const double v : tenths.values) labels.push_back(sim::tick_label(v, tenths.decimals));
  // One number of decimals for the whole axis.
  EXPECT_EQ(labels, (std::vector<std::string>{"0.0", "0.1", "0.2", "0.3", "0.4", "0.5"}));
  const sim::Ticks tiny = sim::nice_ticks(2.33016, 2.33017);
  EXPECT_NEAR(tiny.step, 2e-6, 1e-18);
  EXPECT_EQ(sim::tick_label(tiny.values.front(), tiny.decimals), "2.330160");
}

TEST(Ticks, AgreeWithTheReferenceOverManyRanges) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(0, 1);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const double span = std::pow(10.0, -7 + 16 * u(rng));
    const double lo = (u(rng) * 20 - 10) * span;
    const double hi = lo + span * (i % 10 == 0 ? 1 : u(rng));
    const int max_intervals = 3 + i % 8;
    const sim::Ticks t = sim::nice_ticks(lo, hi, max_intervals);
    const double ref = reference_step(lo, hi, max_intervals);
    ASSERT_NEAR(t.step, ref, 1e-9 * ref) << lo << ".." << hi << " max " << max_intervals;
    ASSERT_TRUE(is_125(t.step)) << t.step;
    // The ticks: consecutive multiples of the step covering the data.
    ASSERT_GE(t.values.size(), 3u) << lo << ".." << hi;  // at least two intervals
    ASSERT_LE(int(t.values.size()) - 1, max_intervals);
    ASSERT_LE(t.lo, lo + 1e-9 * t.step);
    ASSERT_GE(t.hi, hi - 1e-9 * t.step);
    std::set<std::string> seen;
    for (size_t k = 0; k < t.values.size(); ++k) {
      const double v = t.values[k];
      ASSERT_NEAR(v / t.step, std::round(v / t.step), 1e-6);
      if (k) {
        ASSERT_NEAR(v - t.values[k - 1], t.step, 1e-6 * t.step);
      }
      // The label says the value, and no two labels are the same.
      const std::string label = sim::tick_label(v, t.decimals);
      ASSERT_NEAR(std::strtod(label.c_str(), nullptr), v, 1e-9 * t.step + 1e-300) << label;
      ASSERT_TRUE(seen.insert(label).second) << label;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 20000);
}

TEST(Ticks, ARangeThatEndsOnTicksIsNotWidened) {
  // Ends that are already multiples of the step (in decimal; in binary most
  // are not) stay where they are.
  for (int e = -6; e <= 6; ++e) {
    for (const int m : {1, 2, 5}) {
      for (int k1 = -7; k1 <= 3; ++k1) {
        const int k2 = k1 + 3 + (k1 & 3);  // 3 to 6 intervals
        const double step = e >= 0 ? m * std::pow(10.0, e) : m / std::pow(10.0, -e);
        const double lo = e >= 0 ? k1 * m * std::pow(10.0, e) : k1 * m / std::pow(10.0, -e);
        const double hi = e >= 0 ? k2 * m * std::pow(10.0, e) : k2 * m / std::pow(10.0, -e);
        const sim::Ticks t = sim::nice_ticks(lo, hi);
        // The step may be finer (3 intervals of 1 are also 6 of 0.5), never coarser.
        ASSERT_LE(t.step, step * (1 + 1e-12)) << lo << ".." << hi;
        ASSERT_EQ(t.lo, lo) << lo << ".." << hi;
        ASSERT_EQ(t.hi, hi) << lo << ".." << hi;
        ASSERT_EQ(double(t.values.size() - 1), std::round((hi - lo) / t.step)) << lo << ".." << hi;
      }
    }
  }
}

TEST(Ticks, LabelsPrintWhatIsMeant) {
  EXPECT_EQ(sim::tick_label(0.1 + 0.2, 1), "0.3");
  EXPECT_EQ(sim::tick_label(-0.0, 0), "0");
  EXPECT_EQ(sim::tick_label(-1e-12, 2), "0.00");
  EXPECT_EQ(sim::tick_label(-2.5, 1), "-2.5");
  EXPECT_EQ(sim::tick_label(117.5, 1), "117.5");
  EXPECT_EQ(sim::log_tick_label(0.5), "0.5");
  EXPECT_EQ(sim::log_tick_label(0.02), "0.02");
  EXPECT_EQ(sim::log_tick_label(2000), "2000");
}

TEST(Ticks, LogTicksAre125ValuesInsideTheRange) {
  EXPECT_EQ(sim::log_ticks(1, 1000), (std::vector<double>{1, 2, 5, 10, 20, 50, 100, 200, 500, 1000}));
  EXPECT_EQ(sim::log_ticks(1, 10000), (std::vector<double>{1, 10, 100, 1000, 10000}));  // > 3 decades: decades
  EXPECT_EQ(sim::log_ticks(0.3, 40), (std::vector<double>{0.5, 1, 2, 5, 10, 20}));
  EXPECT_EQ(sim::log_ticks(7.875, 5e6), (std::vector<double>{10, 100, 1000, 1e4, 1e5, 1e6}));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-6, 8);
  for (int i = 0; i < 2000; ++i) {
    double a = std::pow(10.0, u(rng)), b = std::pow(10.0, u(rng));
    if (a > b) std::swap(a, b);
    const std::vector<double> t = sim::log_ticks(a, b);
    for (size_t k = 0; k < t.size(); ++k) {
      ASSERT_TRUE(is_125(t[k])) << t[k];
      ASSERT_GE(t[k], a * (1 - 1e-9));
      ASSERT_LE(t[k], b * (1 + 1e-9));
      if (k) {
        ASSERT_GT(t[k], t[k - 1]);
      }
    }
  }
}

// --- velocity and acceleration from step events ----------------------------

sim::AxisTrace trace_at(const std::vector<double>& seconds, double f, double steps_per_mm, int delta = 1,
                        int units = 1) {
  sim::AxisTrace a;
  a.name = 'T';
  a.steps_per_mm = steps_per_mm;
  a.units_per_step = units;
  for (const double s : seconds) a.add_step(uint64_t(std::llround(s * f)), delta);
  return a;
}

TEST(Motion, SteadyRateReadsAsThatRateWithoutRipple) {
  const double f = 16e6;
  std::vector<double> t;
  for (int i = 1; i <= 2000; ++i) t.push_back(0.5 + i * 1e-3);  // 1 kHz from 0.5 s to 2.5 s
  const sim::AxisTrace a = trace_at(t, f, 10);                  // 10 steps per mm: 100 mm/s
  const sim::MotionProfile p = sim::derive_motion(a, f, 3.0, 1200);
  ASSERT_EQ(p.t.size(), 1200u);
  EXPECT_NEAR(p.sigma_min_s, 3.0 / 600, 1e-12);
  for (size_t k = 0; k < p.t.size(); ++k) {
    if (p.t[k] > 0.7 && p.t[k] < 2.3) {
      ASSERT_NEAR(p.vel[k], 100, 1e-6) << p.t[k];
      ASSERT_NEAR(p.acc[k], 0, 1e-3) << p.t[k];
    }
    if (p.t[k] < 0.4 || p.t[k] > 2.6) {
      ASSERT_EQ(p.vel[k], 0) << p.t[k];  // at rest, further than 6 sigma from any step
      ASSERT_EQ(p.acc[k], 0) << p.t[k];
    }
  }
  // The velocity integrates to the distance travelled: 2000 steps = 200 mm.
  double area = 0;
  for (size_t k = 1; k < p.t.size(); ++k) area += 0.5 * (p.vel[k] + p.vel[k - 1]) * (p.t[k] - p.t[k - 1]);
  EXPECT_NEAR(area, 200, 1e-3);
}

TEST(Motion, ConstantAccelerationReadsAsItself) {
  // Steps of a ramp from rest at 2000 steps/s^2: step n at sqrt(2n / A).
  const double f = 16e6, accel = 2000;
  std::vector<double> t;
  for (int n = 1; n <= 4000; ++n) t.push_back(0.1 + std::sqrt(2.0 * n / accel));
  const sim::AxisTrace a = trace_at(t, f, 25);  // 25 steps per mm: 80 mm/s^2
  const double t_end = t.back() + 0.2;
  const sim::MotionProfile p = sim::derive_motion(a, f, t_end, 1200);
  int inside = 0;
  for (size_t k = 0; k < p.t.size(); ++k) {
    const double since = p.t[k] - 0.1;
    if (since < 0.4 || p.t[k] > t.back() - 0.1) continue;
    ASSERT_NEAR(p.vel[k], accel * since / 25, 0.01 * accel * since / 25) << p.t[k];
    ASSERT_NEAR(p.acc[k], 80, 0.8) << p.t[k];
    ++inside;
  }
  EXPECT_GT(inside, 500);
}

TEST(Motion, CoilAxesCountHalfStepsAndSlowStepsAreSmoothedByTheirSpacing) {
  // A coil axis at 20 full steps/s (two half steps a time): far slower than
  // the run's length / 600, so each step's Gaussian is 1.5 intervals wide and
  // the rate still reads steady.
  const double f = 16e6;
  std::vector<double> t;
  for (int i = 0; i < 200; ++i) t.push_back(1 + i * 0.05);
  const sim::AxisTrace a = trace_at(t, f, 4.096, 2, 2);  // ULN2003 pulley: 4.096 steps per mm
  const std::vector<double> w = sim::smoothing_widths(a, f, 12);
  ASSERT_EQ(w.size(), 200u);
  EXPECT_NEAR(w[100], 0.075, 1e-9);
  const sim::MotionProfile p = sim::derive_motion(a, f, 12, 1200);
  for (size_t k = 0; k < p.t.size(); ++k) {
    if (p.t[k] > 2 && p.t[k] < 10) {
      ASSERT_NEAR(p.vel[k], 20 / 4.096, 1e-6) << p.t[k];
    }
  }
  EXPECT_NEAR(sim::mm_per_unit(a), 1 / (2 * 4.096), 1e-12);
}

TEST(Motion, IntervalHistogramCountsEveryIntervalInLogBins) {
  const double f = 1e6;  // one cycle = 1 us
  std::vector<double> t{0};
  for (int i = 0; i < 10; ++i) t.push_back(t.back() + 100e-6);  // ten of 100 us
  for (int i = 0; i < 5; ++i) t.push_back(t.back() + 1e-3);     // five of 1 ms
  t.push_back(t.back() + 0.35);                                 // one gap of 350 ms
  const sim::IntervalHistogram h = sim::interval_histogram(trace_at(t, f, 1), f);
  EXPECT_EQ(h.intervals, 16u);
  EXPECT_DOUBLE_EQ(h.min_us, 100);
  EXPECT_DOUBLE_EQ(h.max_us, 350000);
  ASSERT_EQ(h.edges_us.size(), h.counts.size() + 1);
  uint64_t total = 0;
  for (size_t j = 0; j < h.counts.size(); ++j) {
    total += h.counts[j];
    ASSERT_NEAR(std::log10(h.edges_us[j + 1] / h.edges_us[j]), 0.1, 1e-9);
  }
  EXPECT_EQ(total, 16u);
  const auto count_at = [&h](double us) {
    for (size_t j = 0; j < h.counts.size(); ++j) {
      if (us >= h.edges_us[j] * (1 - 1e-9) && us < h.edges_us[j + 1] * (1 - 1e-9)) return h.counts[j];
    }
    return uint64_t(999);
  };
  EXPECT_EQ(count_at(100), 10u);
  EXPECT_EQ(count_at(1000), 5u);
  EXPECT_EQ(count_at(350000), 1u);
}

// --- the XML checker itself -------------------------------------------------

TEST(XmlCheck, AcceptsWellFormedAndRejectsMalformedDocuments) {
  const char* good =
      "<?xml version='1.0' encoding='UTF-8'?>\n<!-- c -->\n<svg xmlns='x' a=\"1 &amp; 2\">"
      "<g><text>&lt;&#65;&#x42;</text></g><rect/></svg>\n";
  xmlcheck::Parser p(good);
  const auto root = p.parse();
  ASSERT_TRUE(root) << p.error();
  EXPECT_EQ(root->attr_or("a"), "1 & 2");
  EXPECT_EQ(root->children[0]->children[0]->text, "<AB");
  const char* bad[] = {
      "<a><b></a></b>",
      "<a>&foo;</a>",
      "<a x='1' x='2'/>",
      "<a>",
      "<a></a><b/>",
      "<a x=1/>",
      "<a>1 < 2</a>",
      "<a>fish & chips</a>",
      "<a x='<'/>",
      "<!-- a -- b --><a/>",
      "text<a/>",
      "<1a/>",
      "",
  };
  for (const char* doc : bad) {
    xmlcheck::Parser q(doc);
    EXPECT_FALSE(q.parse()) << "accepted: " << doc;
  }
}

// --- the pictures of real runs ---------------------------------------------

struct Picture {
  std::unique_ptr<xmlcheck::Element> root;
  std::vector<const xmlcheck::Element*> panels, series;
};

Picture draw(sim::Machine& m, const std::string& file) {
  const std::string path = temp_path(file);
  sim::write_run_plot(path, m, sim::PlotLabel{"job.txt", sim::RunEnd::done});
  const std::string doc = slurp(path);
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

std::vector<const xmlcheck::Element*> texts(const xmlcheck::Element& panel, const std::string& cls,
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
double interval_label_us(const std::string& label) {
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
std::vector<double> linear_ticks(const std::vector<const xmlcheck::Element*>& labels, const std::string& where) {
  std::vector<double> v;
  for (const auto* t : labels) v.push_back(std::strtod(t->text.c_str(), nullptr));
  EXPECT_GE(v.size(), 3u) << where;
  if (v.size() < 2) return v;
  const double step = v[1] - v[0];
  EXPECT_TRUE(is_125(step)) << where << ": step " << step;
  for (size_t i = 1; i < v.size(); ++i) EXPECT_NEAR(v[i] - v[i - 1], step, 1e-6 * step) << where;
  return v;
}

void check_picture(const Picture& pic, const sim::Machine& m) {
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
std::vector<double> panel_y_ticks(const Picture& pic, char axis, const char* kind) {
  for (const auto* p : pic.panels) {
    if (p->attr_or("data-axis") == std::string(1, axis) && p->attr_or("data-kind") == kind) {
      std::vector<double> v;
      for (const auto* t : texts(*p, "tick", "y")) v.push_back(std::strtod(t->text.c_str(), nullptr));
      return v;
    }
  }
  return {};
}

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

// --- the XY toolpath: which line moved the tool, and what kind of move -----

sim::AxisTrace step_axis(char name, double steps_per_mm) {
  sim::AxisTrace a;
  a.name = name;
  a.kind = 1;  // am::AxisKind::step_dir
  a.steps_per_mm = steps_per_mm;
  return a;
}

sim::Response ok_line(const std::string& line, uint64_t sent) { return {line, "ok", "", sent, sent + 50}; }

// The path's points as (response index, kind, number of points) runs.
struct Stretch {
  int line;
  sim::MoveKind kind;
  size_t points;
  bool operator==(const Stretch& o) const { return line == o.line && kind == o.kind && points == o.points; }
};
std::ostream& operator<<(std::ostream& os, const Stretch& s) {
  return os << "{line " << s.line << ", " << sim::move_kind_name(s.kind) << ", " << s.points << "}";
}

std::vector<Stretch> stretches(const sim::Toolpath& tp) {
  std::vector<Stretch> out;
  for (size_t i = 1; i < tp.points.size(); ++i) {
    const sim::ToolpathPoint& p = tp.points[i];
    if (out.empty() || out.back().line != p.line || out.back().kind != p.kind) out.push_back({p.line, p.kind, 0});
    ++out.back().points;
  }
  return out;
}

using sim::MoveKind;

TEST(Toolpath, AStepBelongsToTheLineWhoseTargetItApproachesNotToTheLastLineAnswered) {
  // 10 steps per mm. The G1 is sent (and answered) while the G0 before it is
  // still running, as the firmware does with moves of the same axes; so is
  // the last G0. Their steps still go to their own lines.
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10);
  uint64_t c = 1000;
  for (int k = 0; k < 10; ++k, c += 1000) {  // G0 X1 Y1: diagonal events
    x.add_step(c, 1);
    y.add_step(c + 5, 1);
  }
  c += 20000;
  for (int k = 0; k < 10; ++k, c += 1000) {  // G1 X2 Y1.5: Y on every other event
    x.add_step(c, 1);
    if (k % 2) y.add_step(c + 5, 1);
  }
  c += 20000;
  for (int k = 0; k < 20; ++k, c += 1000) {  // G0 X0 Y0: Y on 15 of 20 events
    x.add_step(c, -1);
    if ((k + 1) * 15 / 20 > k * 15 / 20) y.add_step(c + 5, -1);
  }
  const std::vector<sim::Response> r = {ok_line("G21 G90", 0), ok_line("G0 X1 Y1", 100),
                                        ok_line("G1 X2 Y1.5 F600", 500), ok_line("G0 X0 Y0", 25000)};
  const sim::Toolpath tp = sim::trace_toolpath({x, y}, r);
  ASSERT_TRUE(tp.present);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::gcode);
  EXPECT_EQ(tp.motion_lines, 3u);
  ASSERT_EQ(tp.points.size(), 41u);  // the origin and one point per event
  EXPECT_EQ(stretches(tp),
            (std::vector<Stretch>{{1, MoveKind::travel, 10}, {2, MoveKind::feed, 10}, {3, MoveKind::travel, 20}}));
  EXPECT_NEAR(tp.points[10].x, 1, 1e-12);
  EXPECT_NEAR(tp.points[10].y, 1, 1e-12);
  EXPECT_NEAR(tp.points[20].x, 2, 1e-12);
  EXPECT_NEAR(tp.points[20].y, 1.5, 1e-12);
  EXPECT_NEAR(tp.points.back().x, 0, 1e-12);
  EXPECT_NEAR(tp.points.back().y, 0, 1e-12);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::travel)], std::sqrt(2.0) + std::sqrt(4 + 2.25), 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::feed)], std::sqrt(1 + 0.25), 1e-9);
  EXPECT_EQ(tp.length_mm[int(MoveKind::extrusion)], 0);
}

TEST(Toolpath, ATargetHalfAStepAwayEndsWhereTheFirmwareRoundedIt) {
  // Motor Shield axes at 10 full steps per mm in a full-step mode: the
  // interpreter keeps X0.05 as half a step (32 of the 64 units of a full
  // step), the firmware rounds the move to whole steps, away from the start:
  // one step (two half steps as decoded) to 0.1. Both that step and the next
  // line's first step leave the tool 0.05 from the target: the step in the
  // line's own direction is the line's. All lines are sent before anything
  // moves.
  const auto coil_axis = [](char name) {
    sim::AxisTrace a = step_axis(name, 10);
    a.kind = 2;  // am::AxisKind::shield_latch
    a.units_per_step = 2;
    return a;
  };
  for (const bool back : {false, true}) {
    sim::AxisTrace x = coil_axis('X'), y = coil_axis('Y');
    x.add_step(1000, 2);
    x.add_step(5000, back ? -2 : 2);
    if (!back) x.add_step(6000, 2);
    for (int k = 0; k < 3; ++k) y.add_step(9000 + 1000 * uint64_t(k), 2);
    const std::vector<sim::Response> r = {ok_line("G1 X0.05 F600", 100), ok_line(back ? "G0 X0" : "G0 X0.3", 200),
                                          ok_line("G1 Y0.3", 300)};
    const sim::Toolpath tp = sim::trace_toolpath({x, y}, r);
    EXPECT_EQ(
        stretches(tp),
        (std::vector<Stretch>{{0, MoveKind::feed, 1}, {1, MoveKind::travel, back ? 1u : 2u}, {2, MoveKind::feed, 3}}))
        << (back ? "back" : "on");
    ASSERT_EQ(tp.points.size(), back ? 6u : 7u);
    EXPECT_NEAR(tp.points[1].x, 0.1, 1e-12);
  }
}

TEST(Toolpath, ExtrusionIsWhereEAdvancedDuringTheMove) {
  // 100 steps per mm; E steps 13 cycles after X or Y in the same event.
  sim::AxisTrace x = step_axis('X', 100), y = step_axis('Y', 100), e = step_axis('E', 100);
  std::vector<sim::Response> r = {ok_line("M83", 0)};
  uint64_t c = 1000;
  const auto line = [&](const std::string& text) { r.push_back(ok_line(text, c - 500)); };
  line("G0 X1 Y0");
  for (int k = 0; k < 100; ++k, c += 500) x.add_step(c, 1);
  c += 10000;
  line("G1 E0.5 F1800");  // prime: E alone
  for (int k = 0; k < 50; ++k, c += 500) e.add_step(c, 1);
  c += 10000;
  line("G1 X1 Y1 E0.2 F600");
  for (int k = 0; k < 100; ++k, c += 500) {
    y.add_step(c, 1);
    if (k % 5 == 4) e.add_step(c + 13, 1);
  }
  c += 10000;
  line("G1 E-0.5 F1800");  // retract
  for (int k = 0; k < 50; ++k, c += 500) e.add_step(c, -1);
  c += 10000;
  line("G0 X0 Y0");
  for (int k = 0; k < 100; ++k, c += 500) {
    x.add_step(c, -1);
    y.add_step(c + 5, -1);
  }
  c += 10000;
  line("G1 E0.5 F1800");  // a prime just before a move without E: not that move's extrusion
  for (int k = 0; k < 50; ++k, c += 500) e.add_step(c, 1);
  c += 10000;
  line("G1 X0 Y-1 F600");
  for (int k = 0; k < 100; ++k, c += 500) y.add_step(c, -1);
  c += 10000;
  line("G0 X1 Y-1 E0.1");  // E advancing on a G0 is extrusion all the same
  for (int k = 0; k < 100; ++k, c += 500) {
    x.add_step(c, 1);
    if (k % 10 == 9) e.add_step(c + 13, 1);
  }
  const sim::Toolpath tp = sim::trace_toolpath({x, y, step_axis('Z', 100), e}, r);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::extrusion);
  EXPECT_EQ(stretches(tp), (std::vector<Stretch>{{1, MoveKind::travel, 100},
                                                 {3, MoveKind::extrusion, 100},
                                                 {5, MoveKind::travel, 100},
                                                 {7, MoveKind::feed, 100},
                                                 {8, MoveKind::extrusion, 100}}));
  EXPECT_NEAR(tp.length_mm[int(MoveKind::extrusion)], 2, 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::travel)], 1 + std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(tp.length_mm[int(MoveKind::feed)], 1, 1e-9);
}

TEST(Toolpath, OnAPlotterThePenDecidesWhateverTheLineSaid) {
  // No E axis, Z moves: Z at its lowest level (0 here) is the pen down.
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10), z = step_axis('Z', 10);
  std::vector<sim::Response> r;
  uint64_t c = 1000;
  r.push_back(ok_line("G1 Z2 F600", c - 500));
  for (int k = 0; k < 20; ++k, c += 500) z.add_step(c, 1);
  r.push_back(ok_line("G1 X1 Y1", c));  // pen up: travel, though G1
  c += 1000;
  for (int k = 0; k < 10; ++k, c += 500) {
    x.add_step(c, 1);
    y.add_step(c, 1);
  }
  r.push_back(ok_line("G1 Z0", c));
  c += 1000;
  for (int k = 0; k < 20; ++k, c += 500) z.add_step(c, -1);
  r.push_back(ok_line("G0 X2", c));  // pen down: drawing, though G0
  c += 1000;
  for (int k = 0; k < 10; ++k, c += 500) x.add_step(c, 1);
  const sim::Toolpath tp = sim::trace_toolpath({x, y, z}, r);
  EXPECT_EQ(tp.rule, sim::ToolpathRule::pen);
  EXPECT_EQ(tp.pen_down_mm, 0);
  EXPECT_EQ(stretches(tp), (std::vector<Stretch>{{1, MoveKind::travel, 10}, {3, MoveKind::feed, 10}}));
  // Without the pen's Z moving, the lines decide.
  const sim::Toolpath flat = sim::trace_toolpath({x, y, step_axis('Z', 10)}, r);
  EXPECT_EQ(flat.rule, sim::ToolpathRule::gcode);
  EXPECT_EQ(stretches(flat), (std::vector<Stretch>{{1, MoveKind::feed, 10}, {3, MoveKind::travel, 10}}));
}

TEST(Toolpath, AMoveLineTakesWhatHappenedBeforeTheNextMotionLine) {
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10);
  for (int k = 0; k < 10; ++k) {
    x.add_step(1000 + 500 * uint64_t(k), 1);
    y.add_step(1000 + 500 * uint64_t(k), 1);
  }
  for (int k = 0; k < 10; ++k) x.add_step(20000 + 500 * uint64_t(k), -1);
  const std::vector<sim::Response> r = {ok_line("MOVE X10 Y10 F100", 100), ok_line("POS", 9000),
                                        ok_line("G0 X0 Y1", 15000)};
  const sim::Toolpath tp = sim::trace_toolpath({x, y}, r);
  EXPECT_EQ(tp.motion_lines, 2u);
  EXPECT_EQ(stretches(tp), (std::vector<Stretch>{{0, MoveKind::feed, 10}, {2, MoveKind::travel, 10}}));
}

TEST(Toolpath, OnlyWhenXAndYBothMoved) {
  sim::AxisTrace x = step_axis('X', 10), y = step_axis('Y', 10);
  x.add_step(1000, 1);
  EXPECT_FALSE(sim::trace_toolpath({x, y}, {}).present);
  EXPECT_FALSE(sim::trace_toolpath({x, step_axis('Z', 10)}, {}).present);
  y.add_step(2000, 1);
  EXPECT_TRUE(sim::trace_toolpath({x, y}, {}).present);
  EXPECT_TRUE(sim::is_gcode_line("G1 X1"));
  EXPECT_TRUE(sim::is_gcode_line(" m 114"));
  EXPECT_TRUE(sim::is_gcode_line("; a comment"));
  EXPECT_FALSE(sim::is_gcode_line("MOVE X1"));
  EXPECT_FALSE(sim::is_gcode_line("NOP"));
}

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

namespace {

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
  for (const char* l : {"G4 P1", "M400", "M104 S200", "G4 P20"}) m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(30) * m.f_cpu()), sim::RunEnd::done);
  const std::string path = temp_path("hot-end.svg");
  sim::write_run_plot(path, m, sim::PlotLabel{"hot end", sim::RunEnd::done, &plant});
  Picture pic;
  const std::string doc = slurp(path);
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
