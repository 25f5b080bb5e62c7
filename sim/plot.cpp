#include "plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

#include "../core/board/descriptor.h"
#include "motion.h"
#include "plot_thermal.h"
#include "plot_toolpath.h"
#include "report.h"
#include "svg_panel.h"
#include "ticks.h"
#include "toolpath.h"

namespace sim {

using namespace svg;

namespace {

// Okabe-Ito's colour-blind-safe set, its yellow (unreadable on white)
// replaced by a brown.
const char* const kPalette[kPaletteSize] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                            "#e69f00", "#56b4e9", "#000000", "#8c564b"};

constexpr double kHeader = 108;  // title, figures, legend, notes
constexpr double kCellW = 380;   // a time panel
constexpr double kHistW = 330;   // the histogram panel
constexpr double kCellH = 210;
constexpr size_t kSamples = 1200;  // velocity / acceleration points per panel (4 per pixel)

// A duration for a title: 31 ms, 2.5 s, 780 us.
std::string duration(double s) {
  char buf[32];
  if (s >= 1)
    std::snprintf(buf, sizeof buf, "%.3g s", s);
  else if (s >= 1e-3)
    std::snprintf(buf, sizeof buf, "%.3g ms", s * 1e3);
  else
    std::snprintf(buf, sizeof buf, "%.3g \xc2\xb5s", s * 1e6);
  return buf;
}

std::string kind_name(const am::AxisDescriptor& d) {
  switch (d.kind) {
    case am::AxisKind::step_dir:
      return "step/dir driver";
    case am::AxisKind::shield_latch:
      return "Motor Shield stepper " + std::to_string(d.option) + ", coils";
    case am::AxisKind::unipolar4:
      return "ULN2003, coils";
    default:
      return "?";
  }
}

// Labels for a log axis, thinned so that none overlaps another: the powers
// of ten first, then the 2s and 5s where they fit. `at` maps a value to its
// pixel along the axis, `room` is the room a label of n characters needs.
std::vector<std::string> log_labels(const std::vector<double>& v, const std::function<double(double)>& at,
                                    const std::function<double(size_t)>& room,
                                    const std::function<std::string(double)>& text) {
  std::vector<std::string> out(v.size());
  std::vector<std::pair<double, double>> taken;  // pixel intervals already labelled
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < v.size(); ++i) {
      const double mantissa = v[i] / std::pow(10.0, std::floor(std::log10(v[i]) + 1e-9));
      if ((pass == 0) != (std::fabs(mantissa - 1) < 1e-6)) continue;
      const std::string label = text(v[i]);
      const double c = at(v[i]), half = room(label.size()) / 2;
      bool free = true;
      for (const auto& t : taken) free = free && (c + half <= t.first || c - half >= t.second);
      if (!free) continue;
      taken.push_back({c - half, c + half});
      out[i] = label;
    }
  }
  return out;
}

// An interval in microseconds as a label with its own unit: 20 us, 5 ms, 1 s.
std::string interval_label(double us) {
  if (us >= 1e6 * (1 - 1e-9)) return log_tick_label(us / 1e6) + " s";
  if (us >= 1e3 * (1 - 1e-9)) return log_tick_label(us / 1e3) + " ms";
  return log_tick_label(us) + " \xc2\xb5s";
}

// The exact position (a point at every step), thinned to the first, lowest,
// highest and last point of each half-pixel column so that a long run stays
// small without losing a reversal.
void position_series(const Panel& p, const AxisTrace& a, double f, double t_end, const char* colour) {
  const double scale = mm_per_unit(a);
  std::vector<std::pair<double, double>> pts{{0, 0}};
  int64_t pos = 0;
  long column = -1;
  std::pair<double, double> first, lo, hi, last;
  const auto flush = [&] {
    if (column < 0) return;
    std::vector<std::pair<double, double>> c{first, lo, hi, last};
    std::sort(c.begin(), c.end());
    for (const auto& q : c) {
      if (pts.back() != q) pts.push_back(q);
    }
  };
  for (size_t i = 0; i < a.step_cycles.size(); ++i) {
    pos += a.step_deltas[i];
    const std::pair<double, double> q{double(a.step_cycles[i]) / f, double(pos) * scale};
    const long col = long(std::floor(p.px(q.first) * 2));
    if (col != column) {
      flush();
      column = col;
      first = lo = hi = last = q;
    } else {
      if (q.second < lo.second) lo = q;
      if (q.second > hi.second) hi = q;
      last = q;
    }
  }
  flush();
  pts.push_back({t_end, double(pos) * scale});
  p.svg << "<polyline class='series' data-axis='" << esc(std::string(1, a.name))
        << "' data-kind='position' fill='none' stroke='" << colour << "' stroke-width='1.6' points='";
  for (size_t i = 0; i < pts.size(); ++i)
    p.svg << (i ? " " : "") << num(p.px(pts[i].first)) << "," << num(p.py(pts[i].second));
  p.svg << "'/>\n";
}

void curve_series(const Panel& p, char axis, const char* kind, const std::vector<double>& t,
                  const std::vector<double>& v, const char* colour) {
  p.svg << "<polyline class='series' data-axis='" << esc(std::string(1, axis)) << "' data-kind='" << kind
        << "' fill='none' stroke='" << colour << "' stroke-width='1.4' stroke-linejoin='round' points='";
  for (size_t i = 0; i < t.size(); ++i) p.svg << (i ? " " : "") << num(p.px(t[i])) << "," << num(p.py(v[i]));
  p.svg << "'/>\n";
}

void range_of(const std::vector<double>& v, double& lo, double& hi) {
  lo = 0;
  hi = 0;
  for (const double x : v) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
}

}  // namespace

const char* palette_colour(int series) { return kPalette[((series % kPaletteSize) + kPaletteSize) % kPaletteSize]; }

void write_run_plot(const std::string& path, Machine& m, const PlotLabel& label) {
  std::ostringstream svg;
  const am::BoardDescriptor& b = m.board();
  const double f = m.f_cpu();
  const double t_end = std::max(1e-6, double(m.cycles()) / f);
  const auto& axes = m.axes();
  const size_t rows = std::max<size_t>(1, axes.size());
  // The XY toolpath: a row below the axes' rows when X and Y both moved.
  const Toolpath tp = trace_toolpath(axes, m.serial().responses());
  const PathLayout layout = tp.present ? path_layout(tp) : PathLayout();
  const double width =
      std::max(2 * kPad + 3 * kCellW + kHistW, tp.present ? 2 * kPad + layout.cell_w + 24 + kPathLegendW : 0);
  const double thermal = label.plant ? kThermalRowH : 0;  // the hot end's row, below the axes'
  const double height =
      2 * kPad + kHeader + double(rows) * kCellH + thermal + (tp.present ? path_row_height(layout) : 0);

  svg << "<?xml version='1.0' encoding='UTF-8'?>\n"
      << "<svg xmlns='http://www.w3.org/2000/svg' width='" << num(width) << "' height='" << num(height)
      << "' viewBox='0 0 " << num(width) << " " << num(height) << "' font-family='sans-serif' font-size='11'>\n";
  char mhz[32];
  std::snprintf(mhz, sizeof mhz, "%g MHz", f / 1e6);
  std::string run = std::string(b.board) + " (" + b.mcu + ", " + mhz + ")";
  if (!label.input.empty()) run += ": " + label.input;
  svg << "<title>" << esc("avrmotion-sim: " + run) << "</title>\n"
      << "<desc>One row per axis: position, velocity and acceleration against time, and a histogram of the "
         "axis's step intervals. Velocity and acceleration are the step events convolved with a Gaussian "
         "and its derivative (docs/simulator-report.md says how). On a board with a simulated hot end, a row "
         "with its temperatures and setpoint and the heater's duty against time. When X and Y both moved, a "
         "last row with the XY toolpath: travel, feed and extrusion drawn apart.</desc>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";

  const SerialHost& serial = m.serial();
  size_t answered = 0;
  for (const Response& r : serial.responses()) answered += !r.answer.empty();
  const size_t errors = answered - serial.lines_ok();
  char figures[256];
  std::snprintf(figures, sizeof figures, "%.6g s simulated, end: %s; %zu lines sent, %zu ok, %zu error%s", t_end,
                end_name(label.end),
                serial.lines_sent(), serial.lines_ok(), errors, errors == 1 ? "" : "s");
  const double y0 = kPad;
  svg << "<text x='" << num(kPad) << "' y='" << num(y0 + 16) << "' font-size='16' font-weight='bold'>" << esc(run)
      << "</text>\n"
      << "<text x='" << num(kPad) << "' y='" << num(y0 + 36) << "' font-size='12'>" << esc(figures) << "</text>\n";
  // Legend: each axis's colour, name and driver.
  double lx = kPad;
  for (size_t i = 0; i < axes.size(); ++i) {
    const std::string text = std::string(1, axes[i].name) + ": " + kind_name(b.axes[i]);
    svg << "<g class='legend' data-axis='" << esc(std::string(1, axes[i].name)) << "'>"
        << "<rect x='" << num(lx) << "' y='" << num(y0 + 46) << "' width='14' height='10' fill='"
        << palette_colour(int(i)) << "'/>"
        << "<text x='" << num(lx + 19) << "' y='" << num(y0 + 55) << "' font-size='12'>" << esc(text)
        << "</text></g>\n";
    lx += 40 + 6.6 * double(text.size());
  }
  svg << "<text x='" << num(kPad) << "' y='" << num(y0 + 76) << "' fill='#505050'>"
      << esc("Velocity and acceleration: every step event spread into a Gaussian (and its derivative) of width "
             "\xcf\x83 = max(the run's length / 600 = " +
             duration(t_end / 600) +
             ", 1.5 \xc3\x97 the step's shorter neighbouring interval); at most the run's length / 60.")
      << "</text>\n"
      << "<text x='" << num(kPad) << "' y='" << num(y0 + 91) << "' fill='#505050'>"
      << esc("Step intervals: the time between consecutive step events (coil-state changes on coil-driven axes), "
             "10 logarithmic bins per decade, counts on a log scale. How it is all derived: "
             "docs/simulator-report.md.")
      << "</text>\n";

  const Ticks time = nice_ticks(0, t_end, 6, false);
  const std::vector<std::string> time_labels = labels(time);
  for (size_t row = 0; row < axes.size(); ++row) {
    const AxisTrace& a = axes[row];
    const char* colour = palette_colour(int(row));
    const double top = kPad + kHeader + double(row) * kCellH;
    const std::string name(1, a.name);
    const bool mm = a.steps_per_mm > 0;
    const std::string unit = mm ? "mm" : "steps";

    // Position.
    {
      double lo = 0, hi = 0;
      int64_t pos = 0;
      for (const int8_t d : a.step_deltas) {
        pos += d;
        lo = std::min(lo, double(pos) * mm_per_unit(a));
        hi = std::max(hi, double(pos) * mm_per_unit(a));
      }
      const Ticks y = nice_ticks(lo, hi);
      Panel p{svg, kPad, top, kCellW, kCellH, 0, t_end, y.lo, y.hi};
      open_panel(p, name, "position", name + " position", colour, time.values, time_labels, y.values, labels(y),
                 "time (s)", "position (" + unit + ")");
      position_series(p, a, f, t_end, colour);
      svg << "</g>\n";
    }
    // Velocity and acceleration.
    const MotionProfile prof = derive_motion(a, f, t_end, kSamples);
    {
      double lo, hi;
      range_of(prof.vel, lo, hi);
      const Ticks y = nice_ticks(lo, hi);
      Panel p{svg, kPad + kCellW, top, kCellW, kCellH, 0, t_end, y.lo, y.hi};
      open_panel(p, name, "velocity", name + " velocity", colour, time.values, time_labels, y.values, labels(y),
                 "time (s)", "velocity (" + unit + "/s)");
      curve_series(p, a.name, "velocity", prof.t, prof.vel, colour);
      svg << "</g>\n";
    }
    {
      double lo, hi;
      range_of(prof.acc, lo, hi);
      const Ticks y = nice_ticks(lo, hi);
      Panel p{svg, kPad + 2 * kCellW, top, kCellW, kCellH, 0, t_end, y.lo, y.hi};
      open_panel(p, name, "acceleration", name + " acceleration", colour, time.values, time_labels, y.values,
                 labels(y), "time (s)", "acceleration (" + unit + "/s\xc2\xb2)");
      curve_series(p, a.name, "acceleration", prof.t, prof.acc, colour);
      svg << "</g>\n";
    }
    // Step-interval histogram.
    {
      const IntervalHistogram h = interval_histogram(a, f);
      const double x0 = kPad + 3 * kCellW;
      const std::string title = name + " step intervals";
      const std::string xtitle = "step interval (log scale)", ytitle = "intervals (log scale)";
      if (h.counts.empty()) {
        // Fewer than two steps: an empty frame that says so.
        Panel p{svg, x0, top, kHistW, kCellH, 1, 10, 1, 10, true, true};
        open_panel(p, name, "intervals", title, colour, {}, {}, {}, {}, xtitle, ytitle);
        svg << "<text x='" << num((p.left() + p.right()) / 2) << "' y='" << num((p.top() + p.bottom()) / 2)
            << "' text-anchor='middle' fill='#707070'>fewer than two step events</text>\n</g>\n";
        continue;
      }
      const double xlo = std::pow(10.0, std::floor(std::log10(h.edges_us.front()) + 1e-9));
      const double xhi = std::pow(10.0, std::ceil(std::log10(h.edges_us.back()) - 1e-9));
      const uint64_t most = *std::max_element(h.counts.begin(), h.counts.end());
      const double yhi = std::pow(10.0, std::ceil(std::log10(double(most) * 1.05)));
      const double ylo = 0.5;
      const std::vector<double> xt = log_ticks(xlo, xhi), yt = log_ticks(1, yhi);
      Panel p{svg, x0, top, kHistW, kCellH, xlo, xhi, ylo, yhi, true, true};
      const auto xl = log_labels(
          xt, [&p](double v) { return p.px(v); }, [](size_t n) { return 6.4 * double(n) + 8; }, interval_label);
      const auto yl = log_labels(
          yt, [&p](double v) { return p.py(v); }, [](size_t) { return 13.0; },
          [](double v) { return log_tick_label(v); });
      open_panel(p, name, "intervals", title, colour, xt, xl, yt, yl, xtitle, ytitle);
      svg << "<g class='series' data-axis='" << esc(name) << "' data-kind='intervals' fill='" << colour
          << "' fill-opacity='0.85'>\n";
      for (size_t j = 0; j < h.counts.size(); ++j) {
        if (!h.counts[j]) continue;
        const double xa = p.px(h.edges_us[j]), xb = p.px(h.edges_us[j + 1]), yc = p.py(double(h.counts[j]));
        svg << "<rect x='" << num(xa) << "' y='" << num(yc) << "' width='" << num(std::max(0.8, xb - xa - 0.6))
            << "' height='" << num(p.bottom() - yc) << "' data-count='" << h.counts[j] << "'/>\n";
      }
      svg << "</g>\n";
      char note[128];
      std::snprintf(note, sizeof note, "n = %llu, shortest %.4g \xc2\xb5s",
                    static_cast<unsigned long long>(h.intervals), h.min_us);
      // The count and the shortest interval, top right inside the frame, on a
      // light backing in case a bar reaches up there.
      const double nw = 5.6 * double(std::strlen(note)) + 8;
      svg << "<rect x='" << num(p.right() - nw - 2) << "' y='" << num(p.top() + 2) << "' width='" << num(nw)
          << "' height='14' fill='white' fill-opacity='0.8'/>\n"
          << "<text x='" << num(p.right() - 6) << "' y='" << num(p.top() + 13)
          << "' text-anchor='end' font-size='10' fill='#404040'>" << esc(note) << "</text>\n</g>\n";
    }
  }
  if (label.plant)
    draw_thermal_row(svg, *label.plant, kPad, kPad + kHeader + double(rows) * kCellH, (3 * kCellW + kHistW) / 2, t_end);
  if (tp.present) toolpath_row(svg, tp, layout, kPad + kHeader + double(rows) * kCellH + thermal);
  if (axes.empty()) {
    svg << "<text x='" << num(kPad) << "' y='" << num(kPad + kHeader + 20) << "'>no axes on this board</text>\n";
  }
  svg << "</svg>\n";

  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << svg.str();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace sim
