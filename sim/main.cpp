// avrmotion-sim: runs a firmware image in libsimavr, feeds it a command file
// over its UART and reports what the motors did (docs/simulator-report.md).
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "machine.h"
#include "plot.h"
#include "report.h"

namespace {

void usage() {
  std::cerr << "usage: avrmotion-sim (--board NAME | --elf FILE) [--input FILE|-] [--report FILE]\n"
               "                     [--plot FILE.svg] [--max-seconds S] [--progress]\n"
               "  --board NAME      run build/firmware/avrmotion-NAME.elf (uno, m32, m16, m16-8mhz)\n"
               "  --input FILE      command lines to send (default: standard input); '#' starts a comment\n"
               "  --report FILE     JSON report (default: standard output)\n"
               "  --plot FILE.svg   picture of position against time\n"
               "  --max-seconds S   simulated-time budget (default 120); exit 3 when spent\n"
               "exit: 0 ran to the end, 2 bad usage or image, 3 budget spent, 4 CPU stopped\n";
}

std::string strip(const std::string& line) {
  std::string s = line.substr(0, line.find('#'));
  const size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

}  // namespace

int main(int argc, char** argv) {
  std::string elf, input = "-", report, plot;
  double max_seconds = 120;
  bool progress = false;
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
    else if (a == "--input") input = value();
    else if (a == "--report") report = value();
    else if (a == "--plot") plot = value();
    else if (a == "--max-seconds") max_seconds = std::atof(value().c_str());
    else if (a == "--progress") progress = true;
    else {
      usage();
      return 2;
    }
  }
  if (elf.empty() || max_seconds <= 0) {
    usage();
    return 2;
  }
  try {
    sim::Machine machine(elf);
    machine.set_progress(progress);
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
    const sim::RunEnd end = machine.run_script(uint64_t(max_seconds * machine.f_cpu()));
    if (report.empty()) {
      sim::write_report(std::cout, machine, end);
    } else {
      std::ofstream out(report);
      sim::write_report(out, machine, end);
    }
    if (!plot.empty()) sim::write_position_plot(plot, machine);
    if (end == sim::RunEnd::budget_spent) {
      std::cerr << "avrmotion-sim: simulated-time budget of " << max_seconds << " s spent\n";
      return 3;
    }
    return end == sim::RunEnd::done ? 0 : 4;
  } catch (const std::exception& e) {
    std::cerr << "avrmotion-sim: " << e.what() << "\n";
    return 2;
  }
}
