#include "plot_lathe.h"

#include <algorithm>
#include <fstream>

#include "svg_panel.h"
#include "ticks.h"

namespace sim {

using namespace svg;

namespace {

constexpr double kCellW = 560, kCellH = 340;
const char* const kHelix = "#000000", *const kCarriage = "#d55e00", *const kError = "#0072b2";

template <typename F>
void series(const Panel& p, const std::vector<LathePlotPoint>& pts, const char* kind, const char* colour,
            const char* dash, F value) {
  p.svg << "<polyline class='series' data-axis='Z' data-kind='" << kind << "' fill='none' stroke='" << colour
        << "' stroke-width='1.4'" << (dash ? std::string(" stroke-dasharray='") + dash + "'" : std::string())
        << " points='";
  // At most about two points per pixel column: the series is thinned, every
  // kept point an actual sample (the error's extremes per column kept).
  const size_t n = pts.size();
  const size_t columns = 2 * size_t(p.right() - p.left());
  const size_t stride = n > columns ? n / columns : 1;
  bool first = true;
  for (size_t i = 0; i < n; i += stride) {
    size_t lo = i, hi = i;
    for (size_t j = i; j < std::min(n, i + stride); ++j) {
      if (value(pts[j]) < value(pts[lo])) lo = j;
      if (value(pts[j]) > value(pts[hi])) hi = j;
    }
    for (size_t k : {std::min(lo, hi), std::max(lo, hi)}) {
      p.svg << (first ? "" : " ") << num(p.px(pts[k].t_s)) << "," << num(p.py(value(pts[k])));
      first = false;
      if (lo == hi) break;
    }
  }
  p.svg << "'/>\n";
}

}  // namespace

void write_lathe_plot(std::ostream& svg, const std::string& title, const std::vector<LathePlotPoint>& pts) {
  const double width = 2 * kCellW + 2 * kPad, height = kCellH + 2 * kPad + 24;
  svg << "<?xml version='1.0' encoding='UTF-8'?>\n"
      << "<svg xmlns='http://www.w3.org/2000/svg' width='" << num(width) << "' height='" << num(height)
      << "' viewBox='0 0 " << num(width) << " " << num(height) << "' font-family='sans-serif' font-size='11'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n"
      << "<text x='" << num(kPad) << "' y='" << num(kPad + 12) << "' font-size='13'>" << esc(title) << "</text>\n";
  if (pts.empty()) {
    svg << "</svg>\n";
    return;
  }
  const double t0 = pts.front().t_s, t1 = std::max(pts.back().t_s, t0 + 1e-3);
  const Ticks time = nice_ticks(t0, t1, 6, false);
  double plo = pts.front().helix_mm, phi = plo, elo = 0, ehi = 0;
  for (const LathePlotPoint& p : pts) {
    plo = std::min({plo, p.helix_mm, p.carriage_mm});
    phi = std::max({phi, p.helix_mm, p.carriage_mm});
    elo = std::min(elo, p.error_um);
    ehi = std::max(ehi, p.error_um);
  }
  const double y0 = kPad + 24;
  {
    const Ticks y = nice_ticks(plo, phi + 1e-6);
    Panel p{svg, kPad, y0, kCellW, kCellH, time.lo, time.hi, y.lo, y.hi};
    open_panel(p, "Z", "position", "helix: lambda x spindle angle (black, dashed); carriage (orange)", kCarriage,
               time.values, labels(time), y.values, labels(y), "time (s)", "carriage (mm)");
    series(p, pts, "helix", kHelix, "6,3", [](const LathePlotPoint& q) { return q.helix_mm; });
    series(p, pts, "carriage", kCarriage, nullptr, [](const LathePlotPoint& q) { return q.carriage_mm; });
    svg << "</g>\n";
  }
  {
    const double pad = 0.05 * std::max(1.0, ehi - elo);
    const Ticks y = nice_ticks(elo - pad, ehi + pad);
    Panel p{svg, kPad + kCellW, y0, kCellW, kCellH, time.lo, time.hi, y.lo, y.hi};
    open_panel(p, "Z", "error", "following error: helix - carriage, in the pass's direction", kError, time.values,
               labels(time), y.values, labels(y), "time (s)", "error (\xc2\xb5m)");
    series(p, pts, "error", kError, nullptr, [](const LathePlotPoint& q) { return q.error_um; });
    svg << "</g>\n";
  }
  svg << "</svg>\n";
}

bool write_lathe_plot(const std::string& path, const std::string& title, const std::vector<LathePlotPoint>& pts) {
  std::ofstream out(path);
  if (!out) return false;
  write_lathe_plot(out, title, pts);
  return bool(out);
}

}  // namespace sim
