#include "plot.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

namespace sim {

namespace {

constexpr double kWidth = 800, kHeight = 400, kMargin = 60;
const char* const kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};

double axis_mm(const AxisTrace& a, int64_t units) {
  return a.steps_per_mm > 0 ? double(units) / a.units_per_step / a.steps_per_mm : 0;
}

}  // namespace

void write_position_plot(const std::string& path, const Machine& m) {
  std::ofstream svg(path);
  if (!svg) throw std::runtime_error("cannot write " + path);
  const double f = m.f_cpu();
  const double t_end = std::max(1e-9, double(m.cycles()) / f);
  double lo = 0, hi = 0;
  for (const AxisTrace& a : m.axes()) {
    int64_t p = 0;
    for (const int8_t d : a.step_deltas) {
      p += d;
      lo = std::min(lo, axis_mm(a, p));
      hi = std::max(hi, axis_mm(a, p));
    }
  }
  if (hi - lo < 1e-9) hi = lo + 1;
  const auto x = [&](double t) { return kMargin + t / t_end * (kWidth - 2 * kMargin); };
  const auto y = [&](double mm) { return kHeight - kMargin - (mm - lo) / (hi - lo) * (kHeight - 2 * kMargin); };

  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << kWidth << "' height='" << kHeight
      << "' font-family='sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << kMargin << "' y='20'>" << m.board().board << " (" << m.board().mcu
      << "): position against time</text>\n";
  // Five ticks on each axis, with light grid lines.
  for (int i = 0; i <= 4; ++i) {
    const double t = t_end * i / 4, mm = lo + (hi - lo) * i / 4;
    svg << "<line x1='" << x(t) << "' y1='" << y(lo) << "' x2='" << x(t) << "' y2='" << y(hi)
        << "' stroke='#e0e0e0'/>\n"
        << "<text x='" << x(t) << "' y='" << y(lo) + 16 << "' text-anchor='middle'>" << t << " s</text>\n"
        << "<line x1='" << x(0) << "' y1='" << y(mm) << "' x2='" << x(t_end) << "' y2='" << y(mm)
        << "' stroke='#e0e0e0'/>\n"
        << "<text x='" << kMargin - 5 << "' y='" << y(mm) + 4 << "' text-anchor='end'>" << mm << "</text>\n";
  }
  svg << "<text x='12' y='" << y(hi) - 10 << "'>mm</text>\n"
      << "<rect x='" << x(0) << "' y='" << y(hi) << "' width='" << x(t_end) - x(0) << "' height='"
      << y(lo) - y(hi) << "' fill='none' stroke='black'/>\n";
  size_t colour = 0;
  for (const AxisTrace& a : m.axes()) {
    const char* c = kColours[colour % 4];
    svg << "<polyline fill='none' stroke='" << c << "' stroke-width='1.5' points='" << x(0) << "," << y(0);
    int64_t p = 0;
    // Thin very long runs so the file stays small: at most ~4000 points.
    const size_t stride = std::max<size_t>(1, a.step_cycles.size() / 4000);
    for (size_t i = 0; i < a.step_cycles.size(); ++i) {
      p += a.step_deltas[i];
      if (i % stride == 0 || i + 1 == a.step_cycles.size()) {
        svg << " " << x(a.step_cycles[i] / f) << "," << y(axis_mm(a, p));
      }
    }
    svg << " " << x(t_end) << "," << y(axis_mm(a, p)) << "'/>\n";
    // Legend along the top.
    const double lx = kMargin + 260 + 70 * double(colour);
    svg << "<line x1='" << lx << "' y1='16' x2='" << lx + 20 << "' y2='16' stroke='" << c
        << "' stroke-width='3'/>\n"
        << "<text x='" << lx + 25 << "' y='20'>" << a.name << "</text>\n";
    ++colour;
  }
  svg << "</svg>\n";
}

}  // namespace sim
