// The benchmark's prints (bench.h, PrintScenario, PrintFigures): slicer's
// files from sim/slicer_file.h, each printed start to finish on the m32
// image (the i3 row: the m32-i3 image, the printer profile, with the file's
// own machine limits and M221 S95) with its hot end and its switches, the host one line in flight at
// the board's baud rate (sim/serial_host.h), comments dropped as a host
// drops them. The host's time is measured for standard error only.
// Exact: X back on its homed position (the file ends with G28 X0), Y and Z
// that position plus the file's last target in steps, E on the file's
// steps; the homed positions are the axes' decoded positions when the
// file's first G28 answered. The i3 row's estimate uses the file's limits
// (the image not probed: the file sets every rate and acceleration); every
// `held within the board's limit` line the firmware printed is counted.
#include <chrono>
#include <cstdio>
#include <cstring>

#include "bench.h"
#include "endstops.h"
#include "machine.h"
#include "print_limits.h"
#include "print_watch.h"
#include "slicer_file.h"
#include "thermal_plant.h"

namespace bench {

namespace {

}  // namespace

// The coarse print: 1.3 mm chords, heated from cold. The fine one: 0.26 mm
// chords (a small feature's), about 115 lines a second at the perimeters'
// 30 mm/s, the hot end already at 200 C (its heat-up is in the coarse row).
// The i3 one: the coarse chords on the printer profile at 80/400/93
// steps/mm, the file's M201 .. M205 in force, 95 % flow.
const std::vector<PrintScenario>& print_scenarios() {
  static const std::vector<PrintScenario> list = {
      {"coarse", 8, 48, 25}, {"fine", 3, 240, 200}, {"i3", 4, 48, 200, "m32-i3", true, 95}};
  return list;
}

PrintFigures measure_print(const std::string& dir, const PrintScenario& s) {
  PrintFigures p;
  const std::string elf = dir + "/avrmotion-" + s.board + ".elf";
  sim::SlicerOptions o;
  o.layers = s.layers;
  o.segments = s.segments;
  o.end_m400 = true;
  o.machine_limits = s.i3_limits;
  if (s.i3_limits) o.file_limits = sim::i3_file_limits();
  o.flow_percent = s.flow_percent;
  const sim::MachineLimits board = sim::board_limits(elf);
  const sim::MachineLimits limits =
      o.machine_limits && sim::file_sets_all(board, o.file_limits) ? board : sim::probe_limits(elf);
  const sim::MachineLimits used = o.machine_limits ? sim::apply_file_limits(limits, o.file_limits) : limits;
  p.rate_mm_s = used.axes.front().max_rate_mm_s;
  p.accel_mm_s2 = used.axes.front().accel_mm_s2;
  const sim::SlicerFile file = sim::write_slicer_file(limits, o);
  p.estimate_s = file.estimate_s;

  sim::Machine m(elf);
  sim::ThermalParams hot_end;
  hot_end.initial_c = s.initial_c;
  sim::ThermalPlant plant(m, hot_end);
  sim::Endstops switches(m);
  sim::PrintWatch watch(m, &plant, &switches);
  for (const std::string& l : file.lines) {
    const std::string c = sim::command_of(l);
    if (!c.empty()) m.serial().add_line(c);
  }
  p.lines = m.serial().lines_pending();
  const auto wall = std::chrono::steady_clock::now();
  const sim::RunEnd end = m.run_script(uint64_t(m.f_cpu()) * 900);
  p.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  const double f = m.f_cpu();
  p.total_s = double(m.cycles()) / f;
  p.starvations = m.starvations();
  uint64_t homed = 0, heated = 0, parked = 0;
  // The file's lines (the host's own M400 after them is not one).
  const std::vector<sim::Response>& rs = m.serial().responses();
  for (size_t i = 0; i < rs.size() && i < p.lines; ++i) {
    const sim::Response& r = rs[i];
    if (r.answer.empty()) continue;
    ++p.answered;
    p.errors += !sim::SerialHost::is_ok(r.answer);
    if (r.line == "G28" && !homed) homed = r.answer_cycle;
    if (r.line.rfind("M109 ", 0) == 0 && !heated) heated = r.answer_cycle;
    if (r.line == "M400" && !parked) parked = r.answer_cycle;
  }
  if (end != sim::RunEnd::done || !homed || !heated || !parked) return p;
  uint64_t first, last;
  if (!sim::motion_span(m.axes(), heated, parked, first, last)) return p;
  p.print_s = double(last - first) / f;
  const sim::AxisTrace *x = m.axis('X'), *y = m.axis('Y'), *z = m.axis('Z'), *e = m.axis('E');
  const auto steps = [&](char name, int64_t um) {
    return sim::round_half_away(um * int64_t(limits.axes[size_t(limits.index(name))].steps_per_mm * 1000), 1000000);
  };
  p.exact = x->position == sim::position_at(*x, homed) && y->position == sim::position_at(*y, homed) + steps('Y', file.y_um) &&
            z->position == sim::position_at(*z, homed) + steps('Z', file.z_um) && e->position == file.e_steps;
  for (const std::string& l : m.serial().messages()) p.held += l.find(" held within the board's limit") != std::string::npos;
  p.progress = sim::last_progress(m.serial());
  std::string message;
  if (sim::last_message(m.serial(), message)) std::snprintf(p.message, sizeof p.message, "%s", message.c_str());
  p.c_at_first_extrusion = watch.sensor_c_at_first_extrusion();
  std::snprintf(p.enabled_at_end, sizeof p.enabled_at_end, "%s", watch.enabled_now().c_str());
  for (const char a : {'X', 'Y', 'Z'}) p.switch_closes += watch.switch_closes(a);
  p.ran = true;
  return p;
}

namespace {

// Below the table, one line a file: what the firmware said of it.
std::string said(const std::vector<PrintFigures>& prints, const char* before, const char* after) {
  const std::vector<PrintScenario>& list = print_scenarios();
  std::string out;
  char buf[256];
  for (size_t i = 0; i < prints.size(); ++i) {
    const PrintFigures& p = prints[i];
    std::snprintf(buf, sizeof buf, "%s%s on %s: %zu limits held, last progress %d %%, last message \"%s\"%s\n", before,
                  list[i].label, list[i].board, p.held, p.progress, p.message, after);
    out += buf;
  }
  return out;
}

const PrintFigures* i3_row(const std::vector<PrintFigures>& prints) {
  for (size_t i = 0; i < prints.size(); ++i)
    if (print_scenarios()[i].i3_limits) return &prints[i];
  return nullptr;
}

}  // namespace

void print_print(const std::vector<PrintFigures>& prints) {
  const std::vector<PrintScenario>& list = print_scenarios();
  const PrintFigures* i3 = i3_row(prints);
  std::printf("Prints, m32 (i3: m32-i3): slicer's files (sim/slicer_file.h), one line in flight at 115200 baud;\n"
              "limits probed from the m32 image: %.2f mm/s, %.1f mm/s^2 (X); i3: the file's, %.0f mm/s, %.0f mm/s^2 (X)\n",
              prints.front().rate_mm_s, prints.front().accel_mm_s2, i3 ? i3->rate_mm_s : 0, i3 ? i3->accel_mm_s2 : 0);
  std::printf("               layers  chords  from (C)  lines  answered  errors  starvations  print (s)  estimate (s)"
              "  ratio  run (s)  exact  C at 1st E\n");
  for (size_t i = 0; i < prints.size(); ++i) {
    const PrintFigures& p = prints[i];
    std::printf("  print %-6s  %6d  %6d  %8.0f  %5zu  %8zu  %6zu  %11d  %9.2f  %12.2f  %5.3f  %7.1f  %5s  %10.1f\n",
                list[i].label, list[i].layers, list[i].segments, list[i].initial_c, p.lines, p.answered, p.errors,
                p.starvations, p.print_s, p.estimate_s, p.estimate_s > 0 ? p.print_s / p.estimate_s : 0, p.total_s,
                p.exact ? "yes" : "NO", p.c_at_first_extrusion);
  }
  std::printf("%s\n", said(prints, "  ", "").c_str());
}

void print_host_time(const std::vector<PrintFigures>& prints) {
  for (size_t i = 0; i < prints.size(); ++i) {
    const PrintFigures& p = prints[i];
    if (p.total_s > 0)
      std::fprintf(stderr, "avrmotion-bench: print %s: %.3f s of host time per simulated second (%.1f s for %.1f s)\n",
                   print_scenarios()[i].label, p.wall_s / p.total_s, p.wall_s, p.total_s);
  }
}

std::string print_markdown(const std::vector<PrintFigures>& prints) {
  const std::vector<PrintScenario>& list = print_scenarios();
  char buf[2048];
  std::snprintf(
      buf, sizeof buf,
      "## Slicer's prints (m32)\n\n"
      "PrusaSlicer-style files (`sim/slicer_file.h`: M104, G28, G1 Z5, M109, per layer two\n"
      "perimeters of radius 10 mm in *chords* and a zig-zag infill, `G92 E0` and a 2 mm retraction\n"
      "at each layer change, fan changes, `M73 P R` and `M117 Layer n of N`; a park, M400, M104\n"
      "S0, G28 X0, M84), sent one line in flight at 115200 baud to the m32 image with its simulated\n"
      "hot end (starting at *from*) and switches. The estimate is a slicer's\n"
      "(`sim/print_estimate.h`: a trapezoid per move, grbl's junction speeds, look-ahead over the\n"
      "whole file) with the limits probed from the image (%.2f mm/s, %.1f mm/s^2 on X; the\n"
      "junction deviation 0.01 mm). The *i3* file runs on the printer profile (the m32-i3 image:\n"
      "80/400/93 steps/mm) and sets its own limits (M201 X1000 Y1000 Z200 E5000, M203 X200 Y200\n"
      "Z12 E120, M204 P1000 R1000 T1500, M205 J0.02, so %.0f mm/s, %.0f mm/s^2 on X) and M221\n"
      "S95; its estimate uses them. *print*: simulated, from\n"
      "the first step after M109's answer to the last step before the M400's, the moves the\n"
      "estimate times: heat-up and homing, which a slicer does not time, are out of both;\n"
      "*ratio*: print / estimate; *run*: the whole simulated run. *exact*: every axis on the\n"
      "steps the file and the homing give. The host's time per simulated second varies with\n"
      "the machine: the benchmark prints it on standard error.\n\n"
      "| file | layers | chords | from (C) | lines | answered | errors | starvations | print (s) | estimate (s) | "
      "ratio | run (s) | exact | C at first extrusion |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n",
      prints.front().rate_mm_s, prints.front().accel_mm_s2, i3_row(prints) ? i3_row(prints)->rate_mm_s : 0,
      i3_row(prints) ? i3_row(prints)->accel_mm_s2 : 0);
  std::string out = buf;
  for (size_t i = 0; i < prints.size(); ++i) {
    const PrintFigures& p = prints[i];
    std::snprintf(buf, sizeof buf, "| %s | %d | %d | %.0f | %zu | %zu | %zu | %d | %.2f | %.2f | %.3f | %.1f | %s | %.1f |\n",
                  list[i].label, list[i].layers, list[i].segments, list[i].initial_c, p.lines, p.answered, p.errors,
                  p.starvations, p.print_s, p.estimate_s, p.estimate_s > 0 ? p.print_s / p.estimate_s : 0, p.total_s,
                  p.exact ? "yes" : "NO", p.c_at_first_extrusion);
    out += buf;
  }
  return out + "\nWhat the firmware said (`held within the board's limit` lines, its last `echo:Progress:` and\n" +
         "M117 echo):\n\n" + said(prints, "- ", "") + "\n";
}

}  // namespace bench
