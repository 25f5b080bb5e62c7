// The numbers behind the pictures avrmotion-sim draws (--plot): the tick
// chooser against a brute-force reference, velocity / acceleration from step
// events, the interval histogram, and the XML checker the picture tests
// parse with. The pictures themselves: test_pictures.cpp.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "motion.h"
#include "picture_check.h"
#include "ticks.h"
#include "xml_check.h"

namespace {

using picturetest::is_125;


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

}  // namespace
