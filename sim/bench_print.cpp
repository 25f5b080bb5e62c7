// The benchmark's print (bench.h, PrintFigures): a slicer's file from
// sim/slicer_file.h, printed start to finish on the m32 image with its hot
// end and its switches, the host one line in flight at the board's baud
// rate (sim/serial_host.h), comments dropped as a host drops them.
// Exact: X back on its homed position (the file ends with G28 X0), Y and Z
// that position plus the file's last target in steps, E on the file's
// steps; the homed positions are the axes' decoded positions when the
// file's first G28 answered.
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

int64_t position_at(const sim::AxisTrace& a, uint64_t cycle) {
  int64_t p = 0;
  for (size_t i = 0; i < a.step_cycles.size() && a.step_cycles[i] <= cycle; ++i) p += a.step_deltas[i];
  return p;
}

std::string command_of(const std::string& line) {
  std::string s = line.substr(0, line.find(';'));
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

PrintFigures measure_print(const std::string& dir) {
  PrintFigures p;
  const std::string elf = dir + "/avrmotion-m32.elf";
  const sim::MachineLimits limits = sim::probe_limits(elf);
  p.rate_mm_s = limits.axes.front().max_rate_mm_s;
  p.accel_mm_s2 = limits.axes.front().accel_mm_s2;
  sim::SlicerOptions o;
  o.layers = kPrintLayers;
  o.end_m400 = true;
  const sim::SlicerFile file = sim::write_slicer_file(limits, o);
  p.estimate_s = file.estimate_s;

  sim::Machine m(elf);
  sim::ThermalPlant plant(m);
  sim::Endstops switches(m);
  sim::PrintWatch watch(m, &plant, &switches);
  for (const std::string& l : file.lines) {
    const std::string c = command_of(l);
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
  uint64_t first = UINT64_MAX, last = 0;
  for (const sim::AxisTrace& a : m.axes()) {
    for (const uint64_t c : a.step_cycles) {
      if (c >= heated && c < first) first = c;
      if (c <= parked && c > last) last = c;
    }
  }
  if (first >= last) return p;
  p.print_s = double(last - first) / f;
  const sim::AxisTrace *x = m.axis('X'), *y = m.axis('Y'), *z = m.axis('Z'), *e = m.axis('E');
  const auto steps = [&](char name, int64_t um) {
    return sim::round_half_away(um * int64_t(limits.axes[size_t(limits.index(name))].steps_per_mm * 1000), 1000000);
  };
  p.exact = x->position == position_at(*x, homed) && y->position == position_at(*y, homed) + steps('Y', file.y_um) &&
            z->position == position_at(*z, homed) + steps('Z', file.z_um) && e->position == file.e_steps;
  p.c_at_first_extrusion = watch.sensor_c_at_first_extrusion();
  std::snprintf(p.enabled_at_end, sizeof p.enabled_at_end, "%s", watch.enabled_now().c_str());
  for (const char a : {'X', 'Y', 'Z'}) p.switch_closes += watch.switch_closes(a);
  p.ran = true;
  return p;
}

void print_print(const PrintFigures& p) {
  std::printf("Print, m32: a slicer's file of %d layers (sim/slicer_file.h), one line in flight at 115200 baud,\n"
              "hot end from 25 C; limits probed from the image: %.2f mm/s, %.1f mm/s^2 (X)\n",
              kPrintLayers, p.rate_mm_s, p.accel_mm_s2);
  std::printf("        lines  answered  errors  starvations  print (s)  estimate (s)  ratio   run (s)  exact  C at 1st E\n");
  std::printf("  print  %5zu  %8zu  %6zu  %11d  %9.2f  %12.2f  %5.3f  %8.1f  %5s  %10.1f\n\n", p.lines, p.answered, p.errors,
              p.starvations, p.print_s, p.estimate_s, p.estimate_s > 0 ? p.print_s / p.estimate_s : 0, p.total_s,
              p.exact ? "yes" : "NO", p.c_at_first_extrusion);
}

std::string print_markdown(const PrintFigures& p) {
  char buf[2048];
  std::snprintf(
      buf, sizeof buf,
      "## A slicer's print (m32)\n\n"
      "A PrusaSlicer-style file of %d layers (`sim/slicer_file.h`: M104, G28, G1 Z5, M109, two\n"
      "perimeters of 48 chords and a zig-zag infill per layer, `G92 E0` and a 2 mm retraction at\n"
      "each layer change, fan changes, a park, M400, M104 S0, G28 X0, M84), sent one line in flight\n"
      "at 115200 baud to the m32 image with its simulated hot end (from 25 C) and switches. Its\n"
      "estimate is a slicer's (`sim/print_estimate.h`: a trapezoid per move, grbl's junction speeds,\n"
      "look-ahead over the whole file) with the limits probed from the image (%.2f mm/s,\n"
      "%.1f mm/s^2 on X; the junction deviation 0.01 mm). *print*: simulated, from the first\n"
      "step after M109's answer to the last step before the M400's, the moves the estimate\n"
      "times: heat-up and homing, which a slicer does not time, are out of both; *run*: the\n"
      "whole simulated run. *exact*: every axis on the steps the file and the homing give.\n"
      "The host's time per simulated second varies with the machine: the benchmark prints it\n"
      "on standard error.\n\n"
      "| lines | answered | errors | starvations | print (s) | estimate (s) | ratio | run (s) | exact | C at first extrusion |\n"
      "|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|\n"
      "| %zu | %zu | %zu | %d | %.2f | %.2f | %.3f | %.1f | %s | %.1f |\n\n",
      kPrintLayers, p.rate_mm_s, p.accel_mm_s2, p.lines, p.answered, p.errors, p.starvations, p.print_s, p.estimate_s,
      p.estimate_s > 0 ? p.print_s / p.estimate_s : 0, p.total_s, p.exact ? "yes" : "NO", p.c_at_first_extrusion);
  return buf;
}

}  // namespace bench
