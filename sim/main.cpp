// avrmotion-sim: runs a firmware image in libsimavr, feeds it a command file
// over its UART, or offers the UART as a pseudo-terminal to a program
// (--pty, pty_run.h), and reports what the motors did
// (docs/simulator-report.md, docs/simulator.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <sim_avr.h>

#include "dc_servo.h"
#include "endstops.h"
#include "keypad_model.h"
#include "lcd_model.h"
#include "machine.h"
#include "plot.h"
#include "print_watch.h"
#include "progress.h"
#include "pty_run.h"
#include "report.h"
#include "spindle_encoder.h"
#include "thermal_plant.h"
#include "vcd.h"

namespace {

void usage() {
  std::cerr << "usage: avrmotion-sim (--board NAME | --elf FILE) [--input FILE|-] [--report FILE]\n"
               "                     [--plot FILE.svg] [--vcd FILE.vcd [--vcd-signals LIST]]\n"
               "                     [--max-seconds S] [--progress] [--eeprom FILE] [--save-eeprom FILE]\n"
               "       avrmotion-sim (--board NAME | --elf FILE) --pty [--link PATH] [--speed N|max] [--linger S]\n"
               "                     [--report FILE] [--plot FILE.svg] [--vcd ...] [--max-seconds S] [--progress]\n"
               "                     [--thermal-initial C] [--thermal-fault NAME@S] [--thermal-fan F@S]\n"
               "                     [--spindle-lines N] [--spindle-quadrature] [--spindle-rpm RPM@S]... [--spindle-jitter US]\n"
               "                     [--lcd FILE|-] [--keys KEYS@S]...\n"
               "  --board NAME        run " AVRMOTION_FIRMWARE_DIR "/avrmotion-NAME.elf (uno, m32, m16, m16-lathe, ...)\n"
               "  --input FILE        command lines to send (default: standard input); '#' starts a comment\n"
               "  --report FILE       JSON report (default: standard output)\n"
               "  --plot FILE.svg     pictures: per axis position, velocity, acceleration, step intervals\n"
               "  --vcd FILE.vcd      trace of pins, interrupts and PWM duties for GTKWave\n"
               "  --vcd-signals LIST  what the trace holds (default board,isr,pwm): board, isr, pwm,\n"
               "                      an axis letter, a pin (PB3), a vector (isr11), a PWM channel (pwm2A)\n"
               "  --max-seconds S     simulated-time budget (default 120; --pty: none, counted from the\n"
               "                      first open); exit 3 when spent\n"
               "  --progress          progress on standard error about once a second, and at the end\n"
               "  --eeprom FILE       the EEPROM's first bytes from FILE at power-up (a board's stored\n"
               "                      settings, docs/settings.md); they live through every reset\n"
               "  --save-eeprom FILE  the whole EEPROM into FILE at the end (for a later --eeprom)\n"
               "  --pty               the UART as a pseudo-terminal (its path on standard error) instead of\n"
               "                      --input; each open resets the MCU; ends when the client has closed\n"
               "  --link PATH         also a symlink PATH to the pseudo-terminal\n"
               "  --speed N|max       simulated time N times wall-clock time while a client is there\n"
               "                      (default 1); max: as fast as it goes\n"
               "  --linger S          after a close, wait S s for a client to open it again (default 2)\n"
               "  a board with a heater (m32) runs a simulated 40 W hot end (docs/heater.md):\n"
               "  --thermal-initial C hot end and thermistor at C at reset (default 25)\n"
               "  --thermal-fault NAME@S  from S seconds on: open, shorted (sensor), disconnected,\n"
               "                      stuck_on (heater); may be given more than once\n"
               "  --thermal-fan F@S   part fan at F (0..1) from S seconds on; more than once allowed\n"
               "  a board with endstops (m32) has its switches at each axis's position 0 (docs/homing.md):\n"
               "  --endstop A=STEPS   axis A's switch at STEPS instead; more than once allowed\n"
               "  --endstop-bounce US each contact change bounces for US microseconds (default 0)\n"
               "  --endstop-nc        normally-closed switches: each pin reads the other way\n"
               "  --no-endstops       no switches: every endstop stays open\n"
               "  a board with a spindle encoder (m16-lathe, m16-servo) runs a simulated spindle (docs/lathe.md);\n"
               "  the m16-servo's leadscrew is the seed's DC servo (sim/dc_servo.h):\n"
               "  --spindle-lines N   encoder lines per turn (default 40, the seed's disc)\n"
               "  --spindle-quadrature  two channels a quarter line apart (default: one channel)\n"
               "  --spindle-rpm RPM@S rpm at S seconds, linear between points, negative turns backward;\n"
               "                      more than once (default 0@0: at rest)\n"
               "  --spindle-jitter US each encoder edge up to +-US microseconds off its time\n"
               "  the operator panel (m16-panel: HD44780 on PORTA, 4x4 keypad on PORTB, docs/lathe.md):\n"
               "  --lcd FILE|-        the 2x16 display; every screen it showed, with its time, to FILE\n"
               "                      (-: standard error)\n"
               "  --keys KEYS@S       press KEYS (of 0-9 A-D * #) from S seconds on, one every 0.25 s, each\n"
               "                      held 0.125 s and bouncing 4 ms; more than once allowed; the run lasts\n"
               "                      until 1 s after the last key at least\n"
               "exit: 0 ran to the end (--pty: the client closed, or SIGINT/SIGTERM), 2 bad usage or image, 3 budget spent, 4 CPU stopped,\n"
               "      5 simavr reported an error (a dropped event: the run is not valid)\n";
}

std::string strip(const std::string& line) {
  std::string s = line.substr(0, line.find('#'));
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}


// "VALUE@SECONDS" -> value and seconds; false if malformed.
bool split_at(const std::string& s, std::string& value, double& seconds) {
  const size_t at = s.find('@');
  if (at == std::string::npos || at == 0) return false;
  value = s.substr(0, at);
  char* end = nullptr;
  seconds = std::strtod(s.c_str() + at + 1, &end);
  return end && *end == '\0' && end != s.c_str() + at + 1 && seconds >= 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string elf, input = "-", report, plot, vcd, vcd_signals;
  std::string link, speed_text;
  double max_seconds = 120, linger = 2;
  bool progress = false, pty = false, input_given = false, linger_given = false, budget_given = false;
  sim::ThermalParams thermal;
  std::vector<std::pair<double, sim::ThermalFault>> faults;
  std::vector<std::pair<double, double>> fans;
  std::vector<std::pair<char, int64_t>> endstop_at;
  sim::EndstopParams endstop_params;
  bool no_endstops = false;
  std::string lcd_file;
  std::string eeprom_file, save_eeprom_file;
  std::vector<std::pair<std::string, double>> key_script;
  sim::SpindleParams spindle;
  spindle.profile.clear();
  bool spindle_given = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        usage();
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--board") elf = std::string(AVRMOTION_FIRMWARE_DIR) + "/avrmotion-" + value() + ".elf";
    else if (a == "--elf") elf = value();
    else if (a == "--input") input = value(), input_given = true;
    else if (a == "--report") report = value();
    else if (a == "--plot") plot = value();
    else if (a == "--vcd") vcd = value();
    else if (a == "--vcd-signals") vcd_signals = value();
    else if (a == "--max-seconds") max_seconds = std::atof(value().c_str()), budget_given = true;
    else if (a == "--progress") progress = true;
    else if (a == "--pty") pty = true;
    else if (a == "--link") link = value();
    else if (a == "--speed") speed_text = value();
    else if (a == "--linger") linger = std::atof(value().c_str()), linger_given = true;
    else if (a == "--thermal-initial") thermal.initial_c = std::atof(value().c_str());
    else if (a == "--endstop") {
      char axis;
      int64_t steps;
      if (!sim::parse_endstop_position(value(), axis, steps)) {
        usage();
        return 2;
      }
      endstop_at.push_back({axis, steps});
    } else if (a == "--endstop-bounce") {
      endstop_params.bounce_us = std::atof(value().c_str());
      if (endstop_params.bounce_us < 0) {
        usage();
        return 2;
      }
    } else if (a == "--endstop-nc") endstop_params.normally_closed = true;
    else if (a == "--no-endstops") no_endstops = true;
    else if (a == "--lcd") lcd_file = value();
    else if (a == "--eeprom") eeprom_file = value();
    else if (a == "--save-eeprom") save_eeprom_file = value();
    else if (a == "--keys") {
      std::string keys;
      double at = 0;
      if (!split_at(value(), keys, at)) {
        std::cerr << "avrmotion-sim: --keys needs KEYS@SECONDS\n";
        return 2;
      }
      key_script.push_back({keys, at});
    } else if (a == "--spindle-lines") {
      const int n = std::atoi(value().c_str());
      if (n < 1 || n > 16383) {
        usage();
        return 2;
      }
      spindle.lines = uint16_t(n), spindle_given = true;
    } else if (a == "--spindle-quadrature") spindle.quadrature = true, spindle_given = true;
    else if (a == "--spindle-jitter") spindle.jitter_us = std::atof(value().c_str()), spindle_given = true;
    else if (a == "--spindle-rpm") {
      std::string rpm;
      double at = 0;
      char* end = nullptr;
      if (!split_at(value(), rpm, at)) {
        usage();
        return 2;
      }
      const double r = std::strtod(rpm.c_str(), &end);
      if (*end || (!spindle.profile.empty() && at <= spindle.profile.back().t_s)) {
        usage();
        return 2;
      }
      spindle.profile.push_back({at, r});
      spindle_given = true;
    }
    else if (a == "--thermal-fault" || a == "--thermal-fan") {
      const std::string v = value();
      std::string what;
      double at = 0;
      sim::ThermalFault f;
      char* end = nullptr;
      if (!split_at(v, what, at)) {
        usage();
        return 2;
      }
      if (a == "--thermal-fault") {
        if (!sim::parse_thermal_fault(what, f)) {
          usage();
          return 2;
        }
        faults.push_back({at, f});
      } else {
        const double fraction = std::strtod(what.c_str(), &end);
        if (*end || fraction < 0 || fraction > 1) {
          usage();
          return 2;
        }
        fans.push_back({at, fraction});
      }
    }
    else {
      usage();
      return 2;
    }
  }
  const double speed = speed_text.empty() ? 1 : speed_text == "max" ? 0 : std::atof(speed_text.c_str());
  const bool pty_only = !link.empty() || !speed_text.empty() || linger_given;
  if (elf.empty() || max_seconds <= 0 || (!vcd_signals.empty() && vcd.empty()) || (pty && input_given) ||
      (!pty && pty_only) || speed < 0 || (speed == 0 && speed_text != "max") || linger < 0) {
    usage();
    return 2;
  }
  try {
    sim::Machine machine(elf);
    const uint64_t budget = uint64_t(max_seconds * machine.f_cpu());
    if (!eeprom_file.empty()) {
      std::ifstream in(eeprom_file, std::ios::binary);
      std::vector<uint8_t> bytes;
      if (in) bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      if (bytes.empty()) {
        std::cerr << "avrmotion-sim: cannot read the EEPROM bytes of " << eeprom_file << "\n";
        return 2;
      }
      machine.set_eeprom(bytes);
    }
    std::unique_ptr<sim::VcdRecorder> trace;
    sim::RunEnd end;
    sim::PtyStats stats;
    // The hot end lives through every reset (a --pty client's open is one).
    std::unique_ptr<sim::ThermalPlant> plant;
    if (machine.board().heater_pin != am::kNoPin) {
      plant.reset(new sim::ThermalPlant(machine, thermal));
      for (const auto& f : faults) plant->inject_at(f.first, f.second);
      for (const auto& f : fans) plant->fan_at(f.first, f.second);
    } else if (!faults.empty() || !fans.empty()) {
      throw std::runtime_error("--thermal-fault/--thermal-fan: this board has no heater");
    }
    // The switches, wherever the axes go (and through every reset).
    std::unique_ptr<sim::Endstops> switches;
    bool has_endstops = false;
    for (uint8_t i = 0; i < machine.board().axis_count; ++i) has_endstops |= machine.board().axes[i].endstop != am::kNoPin;
    if (has_endstops && !no_endstops) {
      switches.reset(new sim::Endstops(machine, endstop_params));
      for (const auto& e : endstop_at) switches->set_position(e.first, e.second);
    } else if (!endstop_at.empty() || endstop_params.bounce_us > 0 || endstop_params.normally_closed) {
      throw std::runtime_error("--endstop/--endstop-bounce/--endstop-nc: this board has no endstops (or --no-endstops)");
    }
    // A printer (a hot end and a step/dir extruder): the print's measurements.
    std::unique_ptr<sim::PrintWatch> print_watch;
    bool step_dir_e = false;
    for (uint8_t i = 0; i < machine.board().axis_count; ++i)
      step_dir_e |= machine.board().axes[i].name == 'E' && machine.board().axes[i].kind == am::AxisKind::step_dir;
    if (plant && step_dir_e) print_watch.reset(new sim::PrintWatch(machine, plant.get(), switches.get()));
    std::unique_ptr<sim::SpindleEncoder> spindle_model;
    if (machine.board().spindle_pins[0] != am::kNoPin) {
      if (spindle.profile.empty()) spindle.profile.push_back({0, 0});
      spindle_model.reset(new sim::SpindleEncoder(machine, spindle));
    } else if (spindle_given) {
      throw std::runtime_error("--spindle-*: this board has no spindle encoder");
    }
    // A DC-servo leadscrew (m16-servo): the seed's plant on its pins.
    std::unique_ptr<sim::DcServo> servo_model;
    if (machine.board().servo_pins[0] != am::kNoPin) {
      servo_model.reset(new sim::DcServo(machine));
    }
    // The panel: the display (its screens logged) and the keypad's script.
    std::unique_ptr<sim::LcdModel> lcd;
    std::unique_ptr<sim::KeypadModel> keypad;
    std::ofstream lcd_out;
    std::ostream* lcd_log = nullptr;
    std::string pending_screen;
    uint64_t pending_cycle = 0;
    const auto log_screen = [&] {
      char t[32];
      std::snprintf(t, sizeof t, "%10.4f |", double(pending_cycle) / machine.f_cpu());
      *lcd_log << t << pending_screen.substr(0, 16) << "|" << pending_screen.substr(17) << "|\n";
    };
    double keys_end_s = 0;
    if (!lcd_file.empty() || !key_script.empty()) {
      lcd.reset(new sim::LcdModel(machine));
      keypad.reset(new sim::KeypadModel(machine));
      for (const auto& k : key_script) keys_end_s = std::max(keys_end_s, keypad->type(k.first, k.second));
      if (!lcd_file.empty()) {
        if (lcd_file != "-") lcd_out.open(lcd_file);
        lcd_log = lcd_file == "-" ? &std::cerr : &lcd_out;
        // A screen is logged once it has stood for 5 ms: the characters of
        // one redraw (about 2 ms) come as a single line.
        lcd->on_change = [&] {
          const uint64_t now = machine.cycles();
          if (!pending_screen.empty() && now - pending_cycle >= machine.f_cpu() / 200) log_screen();
          pending_screen = lcd->text();
          pending_cycle = now;
        };
      }
    }
    if (keys_end_s > 0) {
      const uint64_t until = uint64_t((keys_end_s + 1) * machine.f_cpu());
      if (until < budget) end = machine.run([] { return false; }, until);
    }
    double wall_seconds = -1;  // an --input run's host time (a --pty run reports its own)
    if (pty) {
      sim::PtyPort port(link);
      std::cerr << "avrmotion-sim: pty " << port.path() << (link.empty() ? "" : " (link " + link + ")") << std::endl;
      if (!vcd.empty()) trace.reset(new sim::VcdRecorder(machine, vcd, vcd_signals));
      // A session ends when its client leaves: no budget unless one is asked for.
      const uint64_t pty_budget = budget_given ? budget : 0;
      end = sim::run_pty(machine, port, sim::PtyOptions{speed, linger, pty_budget, progress ? &std::cerr : nullptr},
                         stats);
    } else {
      std::ifstream file;
      if (input != "-") {
        file.open(input);
        if (!file) throw std::runtime_error("cannot read " + input);
      }
      std::istream& in = input == "-" ? std::cin : file;
      for (std::string line; std::getline(in, line);) {
        const std::string s = strip(line);
        if (!s.empty()) machine.serial().add_line(s);
      }
      if (!vcd.empty()) trace.reset(new sim::VcdRecorder(machine, vcd, vcd_signals));
      const auto wall_start = std::chrono::steady_clock::now();
      end = sim::run_script_with_progress(machine, budget, progress ? &std::cerr : nullptr);
      wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    }
    if (trace) trace->finish();
    if (lcd_log && !pending_screen.empty()) log_screen();
    const sim::PtyStats* pty_stats = pty ? &stats : nullptr;
    if (report.empty()) {
      sim::write_report(std::cout, machine, end, pty_stats, plant.get(), wall_seconds, print_watch.get());
    } else {
      std::ofstream out(report);
      sim::write_report(out, machine, end, pty_stats, plant.get(), wall_seconds, print_watch.get());
    }
    if (!save_eeprom_file.empty()) {
      const std::vector<uint8_t> bytes = machine.eeprom();
      std::ofstream out(save_eeprom_file, std::ios::binary);
      if (bytes.empty() || !out.write(reinterpret_cast<const char*>(bytes.data()), long(bytes.size()))) {
        std::cerr << "avrmotion-sim: cannot write the EEPROM to " << save_eeprom_file << "\n";
        return 2;
      }
    }
    const std::string title = pty ? "pty" : input == "-" ? "" : input;
    if (!plot.empty()) sim::write_run_plot(plot, machine, sim::PlotLabel{title, end, plant.get()});
    if (end == sim::RunEnd::budget_spent) {
      std::cerr << "avrmotion-sim: simulated-time budget of " << max_seconds << " s spent\n";
      return 3;
    }
    return end == sim::RunEnd::done || end == sim::RunEnd::interrupted ? 0 : 4;
  } catch (const sim::SimulatorFault& e) {
    std::cerr << "avrmotion-sim: " << e.what() << "\n";
    return 5;
  } catch (const std::exception& e) {
    std::cerr << "avrmotion-sim: " << e.what() << "\n";
    return 2;
  }
}
