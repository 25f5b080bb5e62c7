#include "report.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

#include "print_watch.h"
#include "pty_run.h"

namespace sim {

namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

size_t lines_answered(const SerialHost& serial) {
  size_t n = 0;
  for (const Response& r : serial.responses()) n += !r.answer.empty();
  return n;
}

}  // namespace

const char* end_name(RunEnd end) {
  switch (end) {
    case RunEnd::done: return "done";
    case RunEnd::budget_spent: return "timeout";
    case RunEnd::interrupted: return "interrupted";
    case RunEnd::cpu_stopped: break;
  }
  return "cpu_stopped";
}

std::string progress_line(Machine& m) {
  const SerialHost& serial = m.serial();
  const size_t input = serial.lines_sent() + serial.lines_pending();
  const size_t answered = lines_answered(serial), ok = serial.lines_ok(), errors = answered - ok;
  const unsigned percent = input ? unsigned(answered * 100 / input) : 100;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "avrmotion-sim: %s s simulated, %zu of %zu lines sent, %zu answered (%zu ok, %zu error%s), "
                "%u%% of the input",
                number(double(m.cycles()) / m.f_cpu()).c_str(), serial.lines_sent(), input, answered, ok, errors,
                errors == 1 ? "" : "s", percent);
  return buf;
}

void write_report(std::ostream& out, Machine& m, RunEnd end, const PtyStats* pty, const ThermalPlant* plant,
                  double wall_seconds, const PrintWatch* print) {
  const am::BoardDescriptor& b = m.board();
  SerialHost& serial = m.serial();
  out << "{\n";
  out << "  \"board\": " << quoted(b.board) << ",\n";
  out << "  \"mcu\": " << quoted(b.mcu) << ",\n";
  out << "  \"f_cpu\": " << b.f_cpu << ",\n";
  out << "  \"end\": " << quoted(end_name(end)) << ",\n";
  out << "  \"cycles\": " << m.cycles() << ",\n";
  out << "  \"seconds\": " << number(double(m.cycles()) / b.f_cpu) << ",\n";
  out << "  \"banner\": " << quoted(serial.banner()) << ",\n";
  out << "  \"lines_sent\": " << serial.lines_sent() << ",\n";
  out << "  \"lines_ok\": " << serial.lines_ok() << ",\n";
  out << "  \"lines_answered\": " << lines_answered(serial) << ",\n";
  out << "  \"lines_input\": " << serial.lines_sent() + serial.lines_pending() << ",\n";
  out << "  \"errors\": [";
  const auto errors = serial.errors();
  for (size_t i = 0; i < errors.size(); ++i) out << (i ? ", " : "") << quoted(errors[i]);
  out << "],\n";
  out << "  \"messages\": [";
  const auto messages = serial.messages();
  for (size_t i = 0; i < messages.size(); ++i) out << (i ? ", " : "") << quoted(messages[i]);
  out << "],\n";
  out << "  \"axes\": {";
  bool first = true;
  for (const AxisTrace& a : m.axes()) {
    out << (first ? "\n" : ",\n") << "    \"" << a.name << "\": {\"steps\": " << number(a.steps())
        << ", \"mm\": " << number(a.steps_per_mm > 0 ? a.steps() / a.steps_per_mm : 0)
        << ", \"decode_errors\": " << a.decode_errors << "}";
    first = false;
  }
  out << "\n  },\n";
  out << "  \"step_stats\": {";
  first = true;
  for (const AxisTrace& a : m.axes()) {
    const uint64_t min = a.min_interval();
    out << (first ? "\n" : ",\n") << "    \"" << a.name << "\": {\"step_events\": " << a.step_cycles.size()
        << ", \"max_rate_hz\": " << number(min ? double(b.f_cpu) / min : 0)
        << ", \"min_interval_cycles\": " << min << "}";
    first = false;
  }
  out << "\n  },\n";
  out << "  \"isr\": {";
  first = true;
  for (const auto& kv : m.isr_stats()) {
    out << (first ? "\n" : ",\n") << "    \"" << kv.first << "\": {\"count\": " << kv.second.count
        << ", \"total_cycles\": " << kv.second.total_cycles << ", \"max_cycles\": " << kv.second.max_cycles << "}";
    first = false;
  }
  out << "\n  },\n";
  if (plant) {
    out << "  \"thermal\": {\"peak_c\": " << number(plant->peak_sensor_c())
        << ", \"final_c\": " << number(plant->sensor_c()) << ", \"final_block_c\": " << number(plant->block_c())
        << ", \"fault\": " << quoted(thermal_fault_name(plant->fault())) << "},\n";
  }
  // The motion: from the first step edge of any axis to the last (a print's
  // time, heat-up and homing included once they step), and the extruder's
  // net travel (the filament a print used; retractions come back).
  uint64_t first_step = UINT64_MAX, last_step = 0;
  double filament_mm = 0;
  for (const AxisTrace& a : m.axes()) {
    if (!a.step_cycles.empty()) {
      first_step = std::min(first_step, a.step_cycles.front());
      last_step = std::max(last_step, a.step_cycles.back());
    }
    if (a.name == 'E' && a.steps_per_mm > 0) filament_mm = a.steps() / a.steps_per_mm;
  }
  const bool moved = first_step != UINT64_MAX;
  out << "  \"motion\": {\"first_step_s\": " << number(moved ? double(first_step) / b.f_cpu : 0)
      << ", \"last_step_s\": " << number(moved ? double(last_step) / b.f_cpu : 0)
      << ", \"motion_s\": " << number(moved ? double(last_step - first_step) / b.f_cpu : 0)
      << ", \"filament_mm\": " << number(filament_mm) << "},\n";
  if (print) {
    // Measured from the pins and the plant (print_watch.h); -1: not seen.
    const double f = b.f_cpu;
    out << "  \"print\": {\"first_extrusion_s\": " << number(print->extruded() ? print->first_extrusion_cycle() / f : -1)
        << ", \"hotend_c_at_first_extrusion\": " << number(print->sensor_c_at_first_extrusion())
        << ", \"block_c_at_first_extrusion\": " << number(print->block_c_at_first_extrusion())
        << ", \"heater_pin_at_end\": " << print->heater_pin_now()
        << ", \"heater_duty_last_100ms\": " << number(print->heater_duty_last())
        << ", \"target_c_at_end\": " << number(print->target_c_last())
        << ", \"drivers_enabled_at_end\": " << quoted(print->enabled_now());
    for (const AxisTrace& a : m.axes()) {
      if (print->switches() && print->switches()->has(a.name))
        out << ", \"switch_closes_" << a.name << "\": " << print->switch_closes(a.name);
    }
    // What the firmware said (print_watch.h): absent when it said nothing.
    const int progress = last_progress(serial);
    if (progress >= 0) out << ", \"progress\": " << progress;
    std::string message;
    if (last_message(serial, message)) out << ", \"message\": " << quoted(message);
    out << "},\n";
  }
  if (wall_seconds >= 0) {
    const double simulated = double(m.cycles()) / b.f_cpu;
    out << "  \"wall_seconds\": " << number(wall_seconds) << ",\n";
    out << "  \"simulated_per_wall\": " << number(wall_seconds > 0 ? simulated / wall_seconds : 0) << ",\n";
  }
  out << "  \"stack_bytes\": " << m.stack_bytes() << ",\n";
  out << "  \"starvations\": " << m.starvations() << (pty ? ",\n" : "\n");
  if (pty) {
    out << "  \"pty\": {\"sessions\": " << pty->sessions << ", \"bytes_to_avr\": " << pty->bytes_to_avr
        << ", \"bytes_from_avr\": " << pty->bytes_from_avr << ", \"bytes_discarded\": " << pty->bytes_discarded
        << ", \"bytes_dropped_at_reset\": " << pty->bytes_dropped_at_reset
        << ", \"min_byte_interval_cycles\": " << pty->min_byte_interval
        << ", \"wall_seconds\": " << number(pty->wall_seconds)
        << ", \"simulated_seconds\": " << number(pty->simulated_seconds)
        << ", \"max_lag_seconds\": " << number(pty->max_lag_s) << "}\n";
  }
  out << "}\n";
}

}  // namespace sim
