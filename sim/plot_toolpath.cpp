#include "plot_toolpath.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "svg_panel.h"

namespace sim {

using namespace svg;

namespace {

constexpr double kPathW = 680, kPathH = 470;  // the toolpath's plot area at most, px
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

}  // namespace

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

}  // namespace sim
