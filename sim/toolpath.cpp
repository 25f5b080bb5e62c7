#include "toolpath.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "../core/board/descriptor.h"
#include "../core/text/gcode_interpreter.h"
#include "motion.h"

namespace sim {

namespace {

// A motion line of the run: a G0/G1 or MOVE the firmware answered "ok".
struct MotionLine {
  size_t response = 0;      // index into the responses
  bool has_target = false;  // G0/G1: the interpreter's target; MOVE: none
  bool rapid = false;       // G0
  double x = 0, y = 0;      // the target, mm from the power-up origin
};

// Position units (what the interpreter's scale counts) per full step: the
// firmware counts coil-driven axes in 1/64 full step (firmware/axes), so a
// target here is rounded exactly as the firmware rounds it.
uint32_t units_per_full_step(const AxisTrace& a) { return a.kind == int(am::AxisKind::step_dir) ? 1u : 64u; }

uint8_t modes_of(const AxisTrace& a) {
  if (a.kind == int(am::AxisKind::shield_latch)) return am::kModesShield;
  if (a.kind == int(am::AxisKind::unipolar4)) return am::kModesUnipolar;
  return 0;
}

bool is_move_line(const std::string& line) {
  size_t i = line.find_first_not_of(" \t");
  if (i == std::string::npos || line.size() < i + 4) return false;
  for (const char c : {'M', 'O', 'V', 'E'}) {
    if ((line[i++] & ~0x20) != c) return false;
  }
  return i == line.size() || line[i] == ' ' || line[i] == '\t';
}

// Runs every G-code line the firmware accepted through the same interpreter
// with the same axes, and collects the motion lines in order.
template <uint8_t N>
std::vector<MotionLine> motion_lines(const std::vector<AxisTrace>& axes, const std::vector<Response>& responses, int xi,
                                     int yi) {
  am::GcodeAxis table[N];
  for (uint8_t i = 0; i < N; ++i) {
    const uint32_t per_m = uint32_t(std::llround(axes[i].steps_per_mm * 1000));
    table[i] = am::GcodeAxis{axes[i].name, modes_of(axes[i]), per_m * units_per_full_step(axes[i])};
  }
  am::GcodeInterpreter<N> gcode(table);
  am::GcodeAction<N> action{};
  std::vector<MotionLine> out;
  for (size_t r = 0; r < responses.size(); ++r) {
    const Response& resp = responses[r];
    if (resp.answer != "ok") continue;  // refused lines change nothing, in the firmware as here
    if (is_gcode_line(resp.line)) {
      if (gcode.run(resp.line.c_str(), action) != am::GcodeError::none) continue;
      if (action.kind != am::GcodeActionKind::move) continue;
      MotionLine m;
      m.response = r;
      m.has_target = table[xi].steps_per_m > 0 && table[yi].steps_per_m > 0;
      m.rapid = action.rapid;
      if (m.has_target) {
        m.x = double(action.target[xi]) * 1000 / double(table[xi].steps_per_m);
        m.y = double(action.target[yi]) * 1000 / double(table[yi].steps_per_m);
      }
      out.push_back(m);
    } else if (is_move_line(resp.line)) {
      MotionLine m;
      m.response = r;
      out.push_back(m);
    }
  }
  return out;
}

std::vector<MotionLine> motion_lines(const std::vector<AxisTrace>& axes, const std::vector<Response>& responses, int xi,
                                     int yi) {
  switch (axes.size()) {
    case 1:
      return motion_lines<1>(axes, responses, xi, yi);
    case 2:
      return motion_lines<2>(axes, responses, xi, yi);
    case 3:
      return motion_lines<3>(axes, responses, xi, yi);
    case 4:
      return motion_lines<4>(axes, responses, xi, yi);
    case 5:
      return motion_lines<5>(axes, responses, xi, yi);
    case 6:
      return motion_lines<6>(axes, responses, xi, yi);
    case 7:
      return motion_lines<7>(axes, responses, xi, yi);
    case 8:
      return motion_lines<8>(axes, responses, xi, yi);
    default:
      return {};
  }
}

int index_of(const std::vector<AxisTrace>& axes, char name) {
  for (size_t i = 0; i < axes.size(); ++i) {
    if (axes[i].name == name) return int(i);
  }
  return -1;
}

// An axis's position (units) after every step event, to read it at any cycle.
struct Positions {
  const AxisTrace* a = nullptr;
  std::vector<int64_t> after;  // after[i]: position after step event i

  explicit Positions(const AxisTrace* trace) : a(trace) {
    if (!a) return;
    int64_t p = 0;
    after.reserve(a->step_deltas.size());
    for (const int8_t d : a->step_deltas) after.push_back(p += d);
  }
  // The position once every step event at or before `cycle` has happened.
  int64_t at(uint64_t cycle) const {
    const size_t k =
        size_t(std::upper_bound(a->step_cycles.begin(), a->step_cycles.end(), cycle) - a->step_cycles.begin());
    return k ? after[k - 1] : 0;
  }
};

// One point of the path: a step of X, of Y, or of both in one coordinated
// event.
struct XyEvent {
  uint64_t cycle;
  int dx, dy;  // position units
};

// The firmware steps the axes of one coordinated event in one interrupt, a
// few cycles apart (the m32's Y 5 cycles after X, E 13; the Uno's shield
// latches X and Y at once); distinct events are hundreds of cycles apart.
constexpr uint64_t kSameXyEventCycles = 64;
// E steps that belong to the same coordinated event as the stretch's last XY
// step come a few instructions after it, in the same interrupt.
constexpr uint64_t kSameEventCycles = 256;

int sign(int v) { return (v > 0) - (v < 0); }

}  // namespace

const char* move_kind_name(MoveKind k) {
  switch (k) {
    case MoveKind::travel:
      return "travel";
    case MoveKind::feed:
      return "feed";
    case MoveKind::extrusion:
      return "extrusion";
  }
  return "?";
}

bool is_gcode_line(const std::string& line) {
  size_t i = 0;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (i == line.size()) return false;
  if (line[i] == ';' || line[i] == '(') return true;
  const char c = char(line[i++] & ~0x20);
  if (c != 'G' && c != 'M' && c != 'N') return false;
  while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
  if (i == line.size()) return false;
  const char d = line[i];
  return (d >= '0' && d <= '9') || d == '-' || d == '+' || d == '.';
}

Toolpath trace_toolpath(const std::vector<AxisTrace>& axes, const std::vector<Response>& responses) {
  Toolpath tp;
  const int xi = index_of(axes, 'X'), yi = index_of(axes, 'Y');
  if (xi < 0 || yi < 0 || axes[size_t(xi)].step_cycles.empty() || axes[size_t(yi)].step_cycles.empty()) return tp;
  tp.present = true;
  const AxisTrace& ax = axes[size_t(xi)];
  const AxisTrace& ay = axes[size_t(yi)];
  const int ei = index_of(axes, 'E'), zi = index_of(axes, 'Z');
  const AxisTrace* ae = ei >= 0 ? &axes[size_t(ei)] : nullptr;
  const AxisTrace* az = zi >= 0 ? &axes[size_t(zi)] : nullptr;

  // The rule: an E axis makes it a printer; else a Z that moved, a plotter.
  int64_t z_low = 0;
  if (ae) {
    tp.rule = ToolpathRule::extrusion;
  } else if (az && !az->step_cycles.empty()) {
    int64_t z = 0, z_high = 0;
    for (const int8_t d : az->step_deltas) {
      z += d;
      z_low = std::min(z_low, z);
      z_high = std::max(z_high, z);
    }
    if (z_high > z_low) {
      tp.rule = ToolpathRule::pen;
      tp.pen_down_mm = double(z_low) * mm_per_unit(*az);
    }
  }

  // X and Y step events in time order, an X and a Y step of one event merged.
  std::vector<XyEvent> ev;
  {
    ev.reserve(ax.step_cycles.size() + ay.step_cycles.size());
    size_t i = 0, j = 0;
    while (i < ax.step_cycles.size() || j < ay.step_cycles.size()) {
      const bool take_x =
          j == ay.step_cycles.size() || (i < ax.step_cycles.size() && ax.step_cycles[i] <= ay.step_cycles[j]);
      if (take_x) {
        ev.push_back({ax.step_cycles[i], ax.step_deltas[i], 0});
        ++i;
      } else {
        ev.push_back({ay.step_cycles[j], 0, ay.step_deltas[j]});
        ++j;
      }
      // The other axis's step of the same event joins this point.
      XyEvent& e = ev.back();
      if (take_x && j < ay.step_cycles.size() && ay.step_cycles[j] - e.cycle <= kSameXyEventCycles) {
        e.dy = ay.step_deltas[j++];
      } else if (!take_x && i < ax.step_cycles.size() && ax.step_cycles[i] - e.cycle <= kSameXyEventCycles) {
        e.dx = ax.step_deltas[i++];
      }
    }
  }

  const double mx = mm_per_unit(ax), my = mm_per_unit(ay);
  tp.points.resize(ev.size() + 1);
  int64_t ux = 0, uy = 0;
  for (size_t j = 0; j < ev.size(); ++j) {
    ux += ev[j].dx;
    uy += ev[j].dy;
    ToolpathPoint& p = tp.points[j + 1];
    p.x = double(ux) * mx;
    p.y = double(uy) * my;
    p.cycle = ev[j].cycle;
  }

  // Attribution: points[1..] to the motion lines, in order.
  const std::vector<MotionLine> lines = motion_lines(axes, responses, xi, yi);
  tp.motion_lines = lines.size();
  std::vector<char> rapid(responses.size(), 0);
  for (const MotionLine& m : lines) rapid[m.response] = m.rapid;
  const size_t n = tp.points.size();
  size_t next = 1;  // the first point not yet attributed
  // Distances are compared in mm^2; a real change is at least about a 30th
  // of a step squared (targets are kept to 1/64 step), far above this.
  const double eps = 1e-6 * std::min(mx, my) * std::min(mx, my);
  for (size_t k = 0; k < lines.size(); ++k) {
    const MotionLine& line = lines[k];
    const uint64_t sent = responses[line.response].sent_cycle;
    // What happened before this line was sent was an earlier line's motion.
    while (next < n && tp.points[next].cycle < sent) {
      tp.points[next].line = k ? int(lines[k - 1].response) : -1;
      ++next;
    }
    if (!line.has_target) continue;
    const ToolpathPoint& start = tp.points[next - 1];
    const double dx = line.x - start.x, dy = line.y - start.y;
    const int sx = std::fabs(dx) < 0.25 * mx ? 0 : dx > 0 ? 1 : -1;
    const int sy = std::fabs(dy) < 0.25 * my ? 0 : dy > 0 ? 1 : -1;
    double d = dx * dx + dy * dy;
    while (next < n) {
      const ToolpathPoint& p = tp.points[next];
      const double ex = line.x - p.x, ey = line.y - p.y, e = ex * ex + ey * ey;
      // On a tie: a step the line itself would make (each axis that steps
      // goes the line's way on it).
      const XyEvent& step = ev[next - 1];
      const bool own_direction = (step.dx == 0 || sign(step.dx) == sx) && (step.dy == 0 || sign(step.dy) == sy);
      if (!(e < d - eps || (e <= d + eps && own_direction))) break;
      tp.points[next].line = int(line.response);
      d = e;
      ++next;
    }
  }
  for (; next < n; ++next) tp.points[next].line = lines.empty() ? -1 : int(lines.back().response);

  const Positions e_pos(ae), z_pos(az);
  // Kinds, per stretch of one line (points attributed to a line are
  // consecutive).
  for (size_t i = 1; i < n;) {
    size_t j = i;
    while (j + 1 < n && tp.points[j + 1].line == tp.points[i].line) ++j;
    const int line = tp.points[i].line;
    // E's net motion from just before the stretch's first XY step to its last.
    const uint64_t from = tp.points[i].cycle ? tp.points[i].cycle - 1 : 0;
    const bool extruding = ae && e_pos.at(tp.points[j].cycle + kSameEventCycles) - e_pos.at(from) > 0;
    for (size_t q = i; q <= j; ++q) {
      ToolpathPoint& p = tp.points[q];
      if (extruding) {
        p.kind = MoveKind::extrusion;
      } else if (tp.rule == ToolpathRule::pen) {
        p.kind = z_pos.at(p.cycle) == z_low ? MoveKind::feed : MoveKind::travel;
      } else {
        p.kind = line >= 0 && rapid[size_t(line)] ? MoveKind::travel : MoveKind::feed;
      }
    }
    i = j + 1;
  }
  // Lengths: each line's move is straight, so a run of one line and one kind
  // is as long as the distance between its ends (its steps are a staircase).
  for (size_t i = 1; i < n;) {
    size_t j = i;
    while (j + 1 < n && tp.points[j + 1].line == tp.points[i].line && tp.points[j + 1].kind == tp.points[i].kind) ++j;
    const double dx = tp.points[j].x - tp.points[i - 1].x, dy = tp.points[j].y - tp.points[i - 1].y;
    tp.length_mm[int(tp.points[i].kind)] += std::sqrt(dx * dx + dy * dy);
    i = j + 1;
  }
  return tp;
}

}  // namespace sim
