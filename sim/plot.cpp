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
#include "ticks.h"
#include "toolpath.h"

namespace sim {

namespace {

// Okabe-Ito's colour-blind-safe set, its yellow (unreadable on white)
// replaced by a brown.
const char* const kPalette[kPaletteSize] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7",
                                            "#e69f00", "#56b4e9", "#000000", "#8c564b"};

constexpr double kPad = 10;      // around the whole picture
constexpr double kHeader = 108;  // title, figures, legend, notes
constexpr double kCellW = 380;   // a time panel
constexpr double kHistW = 330;   // the histogram panel
constexpr double kCellH = 210;
constexpr double kLeft = 66, kRight = 14, kTop = 26, kBottom = 40;  // inside a panel
constexpr size_t kSamples = 1200;  // velocity / acceleration points per panel (4 per pixel)

std::string esc(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        if (static_cast<unsigned char>(c) >= 0x20 || c == '\t' || c == '\n') out += c;
    }
  }
  return out;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

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

// One panel: a frame, ticks and titles, and a mapping from data to pixels.
struct Panel {
  std::ostream& svg;
  double x0, y0, w, h;        // the cell, in picture coordinates
  double xlo, xhi, ylo, yhi;  // data limits
  bool xlog = false, ylog = false;

  double left() const { return x0 + kLeft; }
  double right() const { return x0 + w - kRight; }
  double top() const { return y0 + kTop; }
  double bottom() const { return y0 + h - kBottom; }
  double px(double v) const {
    const double f = xlog ? std::log10(v / xlo) / std::log10(xhi / xlo) : (v - xlo) / (xhi - xlo);
    return left() + f * (right() - left());
  }
  double py(double v) const {
    const double f = ylog ? std::log10(v / ylo) / std::log10(yhi / ylo) : (v - ylo) / (yhi - ylo);
    return bottom() - f * (bottom() - top());
  }
};

void open_panel(Panel& p, const std::string& axis, const char* kind, const std::string& title, const char* colour,
                const std::vector<double>& xticks, const std::vector<std::string>& xlabels,
                const std::vector<double>& yticks, const std::vector<std::string>& ylabels, const std::string& xtitle,
                const std::string& ytitle) {
  std::ostream& s = p.svg;
  s << "<g class='panel' data-axis='" << esc(axis) << "' data-kind='" << kind << "'>\n";
  s << "<text class='panel-title' x='" << num(p.left()) << "' y='" << num(p.y0 + 16) << "' font-weight='bold' fill='"
    << colour << "'>" << esc(title) << "</text>\n";
  s << "<rect x='" << num(p.left()) << "' y='" << num(p.top()) << "' width='" << num(p.right() - p.left())
    << "' height='" << num(p.bottom() - p.top()) << "' fill='#fbfbfb' stroke='none'/>\n";
  for (size_t i = 0; i < xticks.size(); ++i) {
    const double x = p.px(xticks[i]);
    s << "<line x1='" << num(x) << "' y1='" << num(p.top()) << "' x2='" << num(x) << "' y2='" << num(p.bottom() + 4)
      << "' stroke='#e4e4e4'/>\n";
    if (!xlabels[i].empty()) {
      s << "<text class='tick' data-dir='x' x='" << num(x) << "' y='" << num(p.bottom() + 16)
        << "' text-anchor='middle'>" << esc(xlabels[i]) << "</text>\n";
    }
  }
  for (size_t i = 0; i < yticks.size(); ++i) {
    const double y = p.py(yticks[i]);
    const bool zero = !p.ylog && yticks[i] == 0;
    s << "<line x1='" << num(p.left() - 4) << "' y1='" << num(y) << "' x2='" << num(p.right()) << "' y2='" << num(y)
      << "' stroke='" << (zero ? "#9a9a9a" : "#e4e4e4") << "'/>\n";
    if (!ylabels[i].empty()) {
      s << "<text class='tick' data-dir='y' x='" << num(p.left() - 7) << "' y='" << num(y + 4) << "' text-anchor='end'>"
        << esc(ylabels[i]) << "</text>\n";
    }
  }
  s << "<rect x='" << num(p.left()) << "' y='" << num(p.top()) << "' width='" << num(p.right() - p.left())
    << "' height='" << num(p.bottom() - p.top()) << "' fill='none' stroke='#606060'/>\n";
  s << "<text class='axis-title' data-dir='x' x='" << num((p.left() + p.right()) / 2) << "' y='" << num(p.bottom() + 32)
    << "' text-anchor='middle'>" << esc(xtitle) << "</text>\n";
  const double yx = p.x0 + 14, yy = (p.top() + p.bottom()) / 2;
  s << "<text class='axis-title' data-dir='y' x='" << num(yx) << "' y='" << num(yy)
    << "' text-anchor='middle' transform='rotate(-90 " << num(yx) << " " << num(yy) << ")'>" << esc(ytitle)
    << "</text>\n";
}

std::vector<std::string> labels(const Ticks& t) {
  std::vector<std::string> out;
  for (const double v : t.values) out.push_back(tick_label(v, t.decimals));
  return out;
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

// --- the XY toolpath (sim/toolpath.h) --------------------------------------

constexpr double kPathW = 680, kPathH = 470;  // the toolpath's plot area at most, px
constexpr double kPathLegendW = 520;          // room right of the toolpath panel
const char* const kFeedColour = "#1d3557";    // feed and extrusion (not an axis colour)
const char* const kTravelColour = "#9aa0a6";

// Ticks at every multiple of `step` (1, 2 or 5 times a power of ten) that
// covers [lo, hi], at least `min_intervals` of them (added above).
Ticks ticks_with_step(double lo, double hi, double step, int min_intervals) {
  const int e = int(std::floor(std::log10(step) + 1e-9));
  const double m = std::round(step / std::pow(10.0, e));
  const auto at = [&](double k) { return e >= 0 ? k * m * std::pow(10.0, e) : k * m / std::pow(10.0, -e); };
  double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
  while (last - first < min_intervals) last += 1;
  Ticks t;
  t.step = step;
  t.decimals = std::max(0, -e);
  for (double k = first; k <= last; ++k) t.values.push_back(at(k));
  t.lo = at(first);
  t.hi = at(last);
  return t;
}

// The toolpath panel's scales: one tick step on both axes (the grid is
// square), one mm per pixel on both.
struct PathLayout {
  Ticks x, y;
  double margin = 0;  // mm beyond the outermost ticks
  double mm_per_px = 1;
  double cell_w = 0, cell_h = 0;  // the panel's cell, px
};

PathLayout path_layout(const Toolpath& tp) {
  double xlo = 0, xhi = 0, ylo = 0, yhi = 0;
  for (const ToolpathPoint& q : tp.points) {
    xlo = std::min(xlo, q.x);
    xhi = std::max(xhi, q.x);
    ylo = std::min(ylo, q.y);
    yhi = std::max(yhi, q.y);
  }
  // The step of the wider axis at the room it has; the other axis takes it.
  const bool wide = (xhi - xlo) / kPathW >= (yhi - ylo) / kPathH;
  const double step = wide ? nice_ticks(xlo, xhi, 6).step : nice_ticks(ylo, yhi, 5).step;
  PathLayout l;
  l.x = ticks_with_step(xlo, xhi, step, 2);
  l.y = ticks_with_step(ylo, yhi, step, 2);
  // A margin of 3 % of the wider span around the ticks on all sides, so a
  // path along the outermost tick is not hidden under the frame.
  l.margin = 0.03 * std::max(l.x.hi - l.x.lo, l.y.hi - l.y.lo);
  const double w = l.x.hi - l.x.lo + 2 * l.margin, h = l.y.hi - l.y.lo + 2 * l.margin;
  l.mm_per_px = std::max(w / kPathW, h / kPathH);
  l.cell_w = w / l.mm_per_px + kLeft + kRight;
  l.cell_h = h / l.mm_per_px + kTop + kBottom;
  return l;
}

double path_row_height(const PathLayout& l) { return std::max(l.cell_h, 200.0); }

void move_style(std::ostream& s, MoveKind k) {
  switch (k) {
    case MoveKind::extrusion:
      s << "stroke='" << kFeedColour << "' stroke-width='2.8'";
      break;
    case MoveKind::feed:
      s << "stroke='" << kFeedColour << "' stroke-width='1.1'";
      break;
    case MoveKind::travel:
      s << "stroke='" << kTravelColour << "' stroke-width='1' stroke-dasharray='5 3'";
      break;
  }
}

std::string mm_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  std::string t = buf;
  if (t == "-0.000") t = "0.000";
  return t;
}

// Douglas-Peucker: the fewest of `pts` (first and last always) that keep the
// polyline within `tol` pixels of every point dropped. Straight moves are
// left with their ends, curves keep what a pixel can show.
std::vector<std::pair<double, double>> simplify(const std::vector<std::pair<double, double>>& pts, double tol) {
  if (pts.size() < 3) return pts;
  std::vector<char> keep(pts.size(), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<size_t, size_t>> todo{{0, pts.size() - 1}};
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    const double ax = pts[a].first, ay = pts[a].second;
    const double dx = pts[b].first - ax, dy = pts[b].second - ay, len2 = dx * dx + dy * dy;
    double worst = -1;
    size_t at = a;
    for (size_t i = a + 1; i < b; ++i) {
      const double px = pts[i].first - ax, py = pts[i].second - ay;
      // Distance to the segment a-b (to a itself when a and b coincide).
      const double t = len2 > 0 ? std::min(1.0, std::max(0.0, (px * dx + py * dy) / len2)) : 0;
      const double ex = px - t * dx, ey = py - t * dy, d = ex * ex + ey * ey;
      if (d > worst) {
        worst = d;
        at = i;
      }
    }
    if (worst > tol * tol) {
      keep[at] = 1;
      todo.push_back({a, at});
      todo.push_back({at, b});
    }
  }
  std::vector<std::pair<double, double>> out;
  for (size_t i = 0; i < pts.size(); ++i) {
    if (keep[i]) out.push_back(pts[i]);
  }
  return out;
}

// The panel, then its legend and the rule it used, to its right.
void toolpath_row(std::ostream& svg, const Toolpath& tp, const PathLayout& l, double top) {
  Panel p{
      svg, kPad, top, l.cell_w, l.cell_h, l.x.lo - l.margin, l.x.hi + l.margin, l.y.lo - l.margin, l.y.hi + l.margin};
  open_panel(p, "XY", "toolpath", "XY toolpath (equal scale on both axes)", "#000000", l.x.values, labels(l.x),
             l.y.values, labels(l.y), "X (mm)", "Y (mm)");
  // One polyline per run of one kind, each starting where the previous one
  // ended: every step's point, less those within half a pixel of the last
  // one kept (a run's last point is always kept), then simplified to within
  // 0.3 pixel.
  size_t i = 1;
  const size_t n = tp.points.size();
  while (i < n) {
    const MoveKind kind = tp.points[i].kind;
    size_t j = i;
    while (j + 1 < n && tp.points[j + 1].kind == kind) ++j;
    std::vector<std::pair<double, double>> pts{{p.px(tp.points[i - 1].x), p.py(tp.points[i - 1].y)}};
    for (size_t q = i; q <= j; ++q) {
      const double x = p.px(tp.points[q].x), y = p.py(tp.points[q].y);
      const double dx = x - pts.back().first, dy = y - pts.back().second;
      if (q == j || dx * dx + dy * dy >= 0.25) pts.push_back({x, y});
    }
    pts = simplify(pts, 0.3);
    svg << "<polyline class='series' data-axis='XY' data-kind='toolpath' data-move='" << move_kind_name(kind)
        << "' fill='none' ";
    move_style(svg, kind);
    svg << " stroke-linejoin='round' stroke-linecap='round' points='";
    for (size_t q = 0; q < pts.size(); ++q) svg << (q ? " " : "") << num(pts[q].first) << "," << num(pts[q].second);
    svg << "'/>\n";
    i = j + 1;
  }
  const ToolpathPoint& first = tp.points.front();
  const ToolpathPoint& last = tp.points.back();
  svg << "<circle class='marker' data-kind='start' cx='" << num(p.px(first.x)) << "' cy='" << num(p.py(first.y))
      << "' r='5' fill='none' stroke='" << kFeedColour << "' stroke-width='1.4'/>\n"
      << "<circle class='marker' data-kind='end' cx='" << num(p.px(last.x)) << "' cy='" << num(p.py(last.y))
      << "' r='2.8' fill='" << kFeedColour << "'/>\n</g>\n";

  // Legend: the three kinds with their length, then the rule.
  const double lx = kPad + l.cell_w + 24;
  double ly = top + kTop + 8;
  svg << "<text x='" << num(lx) << "' y='" << num(ly) << "' font-weight='bold'>Toolpath: kinds of motion</text>\n";
  ly += 22;
  const MoveKind kinds[] = {MoveKind::extrusion, MoveKind::feed, MoveKind::travel};
  const char* const what[] = {"extrusion: E advanced during the move", "feed: G1 (or MOVE), no extrusion",
                              "travel: G0, no extrusion"};
  const char* const pen_what[] = {"extrusion: none (no E axis on this board)", "feed: pen down (drawing)",
                                  "travel: pen up"};
  for (int k = 0; k < 3; ++k) {
    char len[48];
    std::snprintf(len, sizeof len, " (%.1f mm)", tp.length_mm[int(kinds[k])]);
    svg << "<g class='move-legend' data-move='" << move_kind_name(kinds[k]) << "'><line x1='" << num(lx) << "' y1='"
        << num(ly - 4) << "' x2='" << num(lx + 34) << "' y2='" << num(ly - 4) << "' ";
    move_style(svg, kinds[k]);
    svg << "/><text x='" << num(lx + 42) << "' y='" << num(ly) << "'>"
        << esc(std::string(tp.rule == ToolpathRule::pen ? pen_what[k] : what[k]) + len) << "</text></g>\n";
    ly += 18;
  }
  svg << "<g class='move-legend' data-move='markers'><circle cx='" << num(lx + 8) << "' cy='" << num(ly - 4)
      << "' r='5' fill='none' stroke='" << kFeedColour << "' stroke-width='1.4'/><text x='" << num(lx + 42) << "' y='"
      << num(ly) << "'>" << esc("start (" + mm_text(first.x) + ", " + mm_text(first.y) + ")") << "</text><circle cx='"
      << num(lx + 208) << "' cy='" << num(ly - 4) << "' r='2.8' fill='" << kFeedColour << "'/><text x='"
      << num(lx + 220) << "' y='" << num(ly) << "'>" << esc("end (" + mm_text(last.x) + ", " + mm_text(last.y) + ") mm")
      << "</text></g>\n";
  ly += 28;
  std::vector<std::string> notes;
  switch (tp.rule) {
    case ToolpathRule::extrusion:
      notes = {"Rule (board with an E axis): a line's XY motion is extrusion when the E axis",
               "advanced during it (net E steps forward); otherwise G0 is travel and G1 or", "MOVE is feed."};
      break;
    case ToolpathRule::pen: {
      notes = {"Rule (no E axis, Z moved: a pen plotter, the pen on Z): an XY step is feed",
               "(drawing) when Z is at its lowest level of the run, " + mm_text(tp.pen_down_mm) +
                   " mm (pen down), and travel",
               "otherwise (pen up), whatever the G-code line said."};
      break;
    }
    case ToolpathRule::gcode:
      notes = {"Rule (no E axis, Z did not move): G0 is travel, G1 or MOVE is feed."};
      break;
  }
  notes.push_back("");
  notes.push_back("Which line moved the tool: the G-code lines the firmware accepted are run");
  notes.push_back("through its own interpreter for their targets; in order, each G0/G1 takes the");
  notes.push_back("XY steps that bring the tool closer to its target, a MOVE what happened before");
  notes.push_back("the next motion line was sent (docs/simulator-report.md). Points: every step.");
  char counts[96];
  std::snprintf(counts, sizeof counts, "%zu XY step events, %zu motion lines.", tp.points.size() - 1, tp.motion_lines);
  notes.push_back(counts);
  for (const std::string& t : notes) {
    if (!t.empty()) svg << "<text x='" << num(lx) << "' y='" << num(ly) << "' fill='#505050'>" << esc(t) << "</text>\n";
    ly += 15;
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
  const double height = 2 * kPad + kHeader + double(rows) * kCellH + (tp.present ? path_row_height(layout) : 0);

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
         "and its derivative (docs/simulator-report.md says how). When X and Y both moved, a last row with "
         "the XY toolpath: travel, feed and extrusion drawn apart.</desc>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";

  const SerialHost& serial = m.serial();
  size_t answered = 0;
  for (const Response& r : serial.responses()) answered += !r.answer.empty();
  const size_t errors = answered - serial.lines_ok();
  char figures[256];
  std::snprintf(figures, sizeof figures, "%.6g s simulated, end: %s; %zu lines sent, %zu ok, %zu error%s", t_end,
                label.end == RunEnd::done           ? "done"
                : label.end == RunEnd::budget_spent ? "timeout"
                                                    : "cpu_stopped",
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
  if (tp.present) toolpath_row(svg, tp, layout, kPad + kHeader + double(rows) * kCellH);
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
