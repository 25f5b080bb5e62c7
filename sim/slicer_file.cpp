// The PrusaSlicer-style file and its estimate (slicer_file.h). Written from
// what PrusaSlicer's output looks like, not from its code.
#include "slicer_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace sim {

int64_t round_half_away(int64_t v, int64_t d) { return v >= 0 ? (v + d / 2) / d : -((-v + d / 2) / d); }

std::string slicer_duration(double seconds) {
  const long s = std::lround(seconds);
  char buf[48];
  if (s >= 3600) std::snprintf(buf, sizeof buf, "%ldh %ldm %lds", s / 3600, s / 60 % 60, s % 60);
  else if (s >= 60) std::snprintf(buf, sizeof buf, "%ldm %lds", s / 60, s % 60);
  else std::snprintf(buf, sizeof buf, "%lds", s);
  return buf;
}

size_t SlicerFile::command_lines() const {
  size_t n = 0;
  for (const std::string& l : lines) n += !l.empty() && l[0] != ';';
  return n;
}

namespace {

// A number of `decimals` decimals from an integer in 10^-decimals, trailing
// zeros dropped as a slicer does ("12.5", "-2", "0.03742").
std::string number(int64_t v, int decimals) {
  int64_t scale = 1;
  for (int i = 0; i < decimals; ++i) scale *= 10;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s%lld.%0*lld", v < 0 ? "-" : "", (long long)(std::llabs(v) / scale), decimals,
                (long long)(std::llabs(v) % scale));
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s == "-0" ? "0" : s;
}

constexpr int64_t kEPerMm5 = 3742;      // E (1e-5 mm) per mm of path: 0.45 x 0.2 mm lines, 1.75 mm filament
constexpr int64_t kRetract5 = 200000;   // 2 mm
constexpr double kRetractFeed = 2400, kZFeed = 720;

class Writer {
 public:
  Writer(const MachineLimits& l, SlicerFile& f) : l_(l), f_(f), est_(l) {}
  void line(const std::string& s) { f_.lines.push_back(s); }
  // G1 to the given X Y (um), Z (um), E (1e-5 mm); -1 / kKeep: unchanged.
  static constexpr int64_t kKeep = INT64_MIN;
  void g1(int64_t x, int64_t y, int64_t z, int64_t e5, double feed, const std::string& comment = "") {
    std::string s = "G1";
    std::vector<double> d(l_.axes.size(), 0);
    const auto word = [&](char name, int64_t& now, int64_t to, int decimals, double mm_per_unit) {
      if (to == kKeep || to == now) return;
      s += std::string(" ") + name + number(to, decimals);
      const int i = l_.index(name);
      if (i >= 0) d[size_t(i)] = double(to - now) * mm_per_unit;
      now = to;
    };
    word('X', x_, x, 3, 1e-3);
    word('Y', y_, y, 3, 1e-3);
    word('Z', z_, z, 3, 1e-3);
    if (e5 != kKeep && e5 != e5_) move_e(e5);
    word('E', e5_, e5, 5, 1e-5);
    // F when it changes, and always on a retraction or an unretraction
    // (extruder alone), as PrusaSlicer writes them.
    if (feed != feed_ || s.rfind("G1 E", 0) == 0) s += " F" + number(std::llround(feed), 0);
    feed_ = feed;
    line(comment.empty() ? s : s + " ; " + comment);
    if (timing_) est_.move(d, feed);
  }
  void g92_e0() {
    e_offset_ = e_machine_ - 0;  // the program's E is 0 at the machine's count
    e5_ = 0;
    line("G92 E0");
  }
  // The program E (1e-5 mm) in steps: 1/10000 mm, then steps per metre.
  int64_t e_steps_of(int64_t e5) const {
    const int i = l_.index('E');
    const int64_t spm = i >= 0 ? std::llround(l_.axes[size_t(i)].steps_per_mm * 1000) : 1000000;
    return round_half_away(round_half_away(e5, 10) * spm, 10000000);
  }
  // A move to the program E `e5`: the firmware's target, its distance
  // scaled by the flow (half away from zero), the difference into the offset.
  void move_e(int64_t e5) {
    const int64_t target = e_steps_of(e5) + e_offset_, delta = target - e_machine_;
    const int64_t flowed = round_half_away(delta * flow_, 100);
    e_machine_ += flowed;
    e_offset_ += flowed - delta;
  }
  void set_flow(int percent) { flow_ = percent; }
  int64_t e5() const { return e5_; }
  int64_t x() const { return x_; }
  int64_t y() const { return y_; }
  int64_t z() const { return z_; }
  void timing(bool on) { timing_ = on; }
  void finish() {
    f_.estimate_s = est_.seconds();
    f_.moves = est_.moves();
    f_.x_um = x_;
    f_.y_um = y_;
    f_.z_um = z_;
    f_.e_steps = e_machine_;
  }
  TimeEstimator& estimator() { return est_; }
  // An extruding move to (x, y): E grows with the path's length.
  void extrude_to(int64_t x, int64_t y, double feed) {
    const double mm = std::hypot(double(x - x_), double(y - y_)) / 1000;
    const int64_t de = std::llround(mm * kEPerMm5);
    filament5_ += de;
    g1(x, y, kKeep, e5_ + de, feed);
  }
  int64_t filament5_ = 0;

 private:
  const MachineLimits& l_;
  SlicerFile& f_;
  TimeEstimator est_;
  bool timing_ = false;
  int64_t x_ = 0, y_ = 0, z_ = 0, e5_ = 0, e_offset_ = 0, e_machine_ = 0;
  int64_t flow_ = 100;
  double feed_ = -1;
};

}  // namespace

FileLimits i3_file_limits() {
  FileLimits l;
  const double accel[4] = {1000, 1000, 200, 5000}, feed[4] = {200, 200, 12, 120}, jerk[4] = {8, 8, 0.4, 4.5};
  for (int i = 0; i < 4; ++i) l.accel[i] = accel[i], l.feed[i] = feed[i], l.jerk[i] = jerk[i];
  l.print_accel = 1000;
  l.retract_accel = 1000;
  l.travel_accel = 1500;
  l.junction_mm = 0.02;
  return l;
}

namespace {
constexpr char kFileAxes[4] = {'X', 'Y', 'Z', 'E'};
}

MachineLimits apply_file_limits(const MachineLimits& limits, const FileLimits& file) {
  MachineLimits l = limits;
  for (int k = 0; k < 4; ++k) {
    const int i = l.index(kFileAxes[k]);
    if (i < 0) continue;
    if (file.accel[k] > 0) l.axes[size_t(i)].accel_mm_s2 = file.accel[k];
    if (file.feed[k] > 0) l.axes[size_t(i)].max_rate_mm_s = file.feed[k];
  }
  if (file.print_accel > 0) l.print_accel = file.print_accel;
  if (file.retract_accel > 0) l.retract_accel = file.retract_accel;
  if (file.travel_accel > 0) l.travel_accel = file.travel_accel;
  if (file.junction_mm > 0) l.junction_mm = file.junction_mm;
  return l;
}

bool file_sets_all(const MachineLimits& limits, const FileLimits& file) {
  for (const AxisLimit& a : limits.axes) {
    int k = 0;
    while (k < 4 && kFileAxes[k] != a.name) ++k;
    if (k == 4 || !(file.accel[k] > 0) || !(file.feed[k] > 0)) return false;
  }
  return true;
}

namespace {

// The machine-limits block, as PrusaSlicer writes it for Marlin 2.
void limits_block(const FileLimits& l, std::vector<std::string>& out) {
  const auto axes = [](const char* code, const double (&v)[4], const char* comment) {
    std::string s = code;
    char buf[32];
    for (int k = 0; k < 4; ++k)
      if (v[k] > 0) std::snprintf(buf, sizeof buf, " %c%g", kFileAxes[k], v[k]), s += buf;
    return s == code ? std::string() : s + " ; " + comment;
  };
  const std::string lines[] = {axes("M201", l.accel, "sets maximum accelerations, mm/sec^2"),
                               axes("M203", l.feed, "sets maximum feedrates, mm/sec"), "", "",
                               axes("M205", l.jerk, "sets the jerk limits, mm/sec"), ""};
  for (size_t i = 0; i < 2; ++i)
    if (!lines[i].empty()) out.push_back(lines[i]);
  std::string m204 = "M204";
  char buf[32];
  const double p[3] = {l.print_accel, l.retract_accel, l.travel_accel};
  for (int k = 0; k < 3; ++k)
    if (p[k] > 0) std::snprintf(buf, sizeof buf, " %c%g", "PRT"[k], p[k]), m204 += buf;
  if (m204.size() > 4) out.push_back(m204 + " ; sets acceleration (P, T) and retract acceleration (R), mm/sec^2");
  if (!lines[4].empty()) out.push_back(lines[4]);
  if (l.junction_mm > 0) {
    std::snprintf(buf, sizeof buf, "M205 J%g", l.junction_mm);
    out.push_back(std::string(buf) + " ; sets the junction deviation, mm");
  }
}

}  // namespace

SlicerFile write_slicer_file(const MachineLimits& probed, const SlicerOptions& o) {
  SlicerFile f;
  const MachineLimits limits = o.machine_limits ? apply_file_limits(probed, o.file_limits) : probed;
  Writer w(limits, f);
  std::vector<std::pair<size_t, size_t>> progress;  // (line, mark): M73s filled once the estimate is known
  const auto m73 = [&] {
    if (!o.progress) return;
    progress.emplace_back(f.lines.size(), w.estimator().mark());
    w.line("M73");
  };
  const auto m117 = [&](const std::string& text) {
    if (!o.progress) return;
    w.line("M117 " + text);
    f.last_message = text;
  };
  constexpr int64_t K = Writer::kKeep;
  const double kPi = 3.14159265358979323846;
  w.line("; generated by avrmotion sim/slicer_file.cpp in the manner of PrusaSlicer");
  // The limits the estimate used, an axis a line (a line of over 96
  // characters is one the firmware refuses, comment or not).
  const std::string described = limits.describe();
  for (size_t at = 0, next; at < described.size(); at = next + (next < described.size() ? 2 : 0)) {
    next = std::min(described.find(", ", at), described.size());
    w.line("; machine limits: " + described.substr(at, next - at));
  }
  w.line("; layer_height = " + number(o.layer_um, 3));
  w.line("; perimeters = " + std::to_string(o.perimeters));
  m73();  // at the start, as PrusaSlicer: P0 and the whole estimate
  if (o.machine_limits) limits_block(o.file_limits, f.lines);
  w.line("M107");
  w.line("M104 S" + std::to_string(o.hotend_c) + " ; set temperature");
  w.line("G28 ; home all axes");
  w.g1(K, K, 5000, K, 5000, "lift nozzle");  // G1 Z5 F5000, after G28 (the program's 0), not timed
  w.line("M109 S" + std::to_string(o.hotend_c) + " ; set temperature and wait for it to be reached");
  w.line("G21 ; set units to millimeters");
  w.line("G90 ; use absolute coordinates");
  w.line("M82 ; use absolute distances for extrusion");
  w.g92_e0();
  if (o.flow_percent > 0) {
    w.line("M220 S100");
    w.line("M221 S" + std::to_string(o.flow_percent));
    w.set_flow(o.flow_percent);
  }
  w.timing(true);
  const int64_t inset = 450;  // one extrusion width between perimeters
  for (int layer = 0; layer < o.layers; ++layer) {
    const int64_t z = o.layer_um * (layer + 1);
    w.line(";LAYER_CHANGE");
    w.line(";Z:" + number(z, 3));
    m73();
    m117("Layer " + std::to_string(layer + 1) + " of " + std::to_string(o.layers));
    w.g92_e0();
    w.g1(K, K, K, -kRetract5, kRetractFeed, "retract");
    w.g1(K, K, z, K, kZFeed, "move to next layer (" + std::to_string(layer) + ")");
    if (layer >= 1) w.line("M106 S" + std::to_string(layer == 1 ? 127 : 255));
    const double phase = layer * 0.61;  // the seam wanders
    for (int p = 0; p < o.perimeters; ++p) {
      const double r = double(o.radius_um - (o.perimeters - 1 - p) * inset);
      const auto at = [&](int k) {
        const double a = phase + 2 * kPi * k / o.segments;
        return std::make_pair(o.cx_um + std::llround(r * std::cos(a)), o.cy_um + std::llround(r * std::sin(a)));
      };
      auto pt = at(0);
      w.g1(pt.first, pt.second, K, K, o.travel_feed, p == 0 ? "move to first perimeter point" : "");
      if (p == 0) {
        w.g1(K, K, K, 0, kRetractFeed, "unretract");
        w.line(";TYPE:" + std::string(o.perimeters > 1 ? "Perimeter" : "External perimeter"));
      }
      if (p == o.perimeters - 1 && o.perimeters > 1) w.line(";TYPE:External perimeter");
      for (int k = 1; k <= o.segments; ++k) {
        pt = at(k);
        w.extrude_to(pt.first, pt.second, o.perimeter_feed);
      }
    }
    // Infill: a zig-zag in the square inside the inner perimeter.
    const int64_t inner = o.radius_um - (o.perimeters - 1) * inset - inset;
    const int64_t half = int64_t(double(inner) / std::sqrt(2.0)) / o.infill_spacing_um * o.infill_spacing_um;
    const bool along_x = layer % 2 == 0;
    const auto pos = [&](int64_t u, int64_t v) {  // u along the lines, v across
      return along_x ? std::make_pair(o.cx_um + u, o.cy_um + v) : std::make_pair(o.cx_um + v, o.cy_um + u);
    };
    w.g1(K, K, K, w.e5() - kRetract5, kRetractFeed, "retract");
    auto start = pos(-half, -half);
    w.g1(start.first, start.second, K, K, o.travel_feed, "move to first infill point");
    w.g1(K, K, K, w.e5() + kRetract5, kRetractFeed, "unretract");
    w.line(";TYPE:Internal infill");
    int dir = 1;
    for (int64_t v = -half; v <= half; v += o.infill_spacing_um, dir = -dir) {
      if (v > -half) {
        const auto step = pos(dir * -half, v);  // across to the next line, at the end the last one reached
        w.extrude_to(step.first, step.second, o.infill_feed);
      }
      const auto end = pos(dir * half, v);
      w.extrude_to(end.first, end.second, o.infill_feed);
    }
  }
  // The end: retract, lift, park; then what a slicer's end G-code does.
  w.g1(K, K, K, w.e5() - kRetract5, kRetractFeed, "retract");
  w.g1(K, K, w.z() + 1000, K, kZFeed, "lift");
  w.g1(10000, o.cy_um + 40000, K, K, o.travel_feed, "park");
  m73();
  m117("Print done");
  w.finish();
  for (const auto& [at, mark] : progress) {
    const double t = w.estimator().at(mark), left = std::max(0.0, f.estimate_s - t);
    const int p = f.estimate_s > 0 ? std::min(100, int(std::floor(100 * t / f.estimate_s + 1e-9))) : 100;
    f.lines[at] = "M73 P" + std::to_string(p) + " R" + std::to_string(long(std::ceil(left / 60 - 1e-9)));
    f.last_progress = p;
  }
  if (o.end_m400) w.line("M400 ; wait for the moves to finish");
  w.line("M104 S0 ; turn off temperature");
  w.line("M107");
  w.line("G28 X0 ; home X axis");
  w.line("M84 ; disable motors");
  f.filament_mm = double(w.filament5_) / 100000;
  char filament[64];
  std::snprintf(filament, sizeof filament, "%.2f", f.filament_mm);
  w.line("; filament used [mm] = " + std::string(filament));
  w.line("; estimated printing time (normal mode) = " + slicer_duration(f.estimate_s));
  return f;
}

std::string command_of(const std::string& line) {
  std::string s = line.substr(0, line.find(';'));
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace sim
