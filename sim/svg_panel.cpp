#include "svg_panel.h"

#include <cmath>
#include <cstdio>

namespace sim {
namespace svg {

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

}  // namespace svg
}  // namespace sim
