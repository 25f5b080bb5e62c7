// Pieces of the run pictures' SVG (sim/plot.cpp, sim/plot_toolpath.cpp):
// text escaping, numbers, and a panel: a frame with ticks and titles and a
// mapping from data to pixels.
#pragma once
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "ticks.h"

namespace sim {
namespace svg {

constexpr double kPad = 10;  // around the whole picture
constexpr double kLeft = 66, kRight = 14, kTop = 26, kBottom = 40;  // inside a panel

std::string esc(const std::string& s);
// A pixel coordinate, one decimal.
std::string num(double v);

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
                const std::string& ytitle);
std::vector<std::string> labels(const Ticks& t);

}  // namespace svg
}  // namespace sim
