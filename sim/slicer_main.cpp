// avrmotion-slicer: writes a PrusaSlicer-style print for a G-code image
// (sim/slicer_file.h) with its estimated printing time from the machine
// limits measured from that image (sim/print_limits.h).
//
//   avrmotion-slicer (--board NAME | --elf FILE) [--layers N] [--perimeters N] [--segments N]
//                    [--end-m400] [--machine-limits i3] [--flow PERCENT] [--no-progress] [--output FILE]
//
// --machine-limits i3 writes an i3-style machine's M201/M203/M204/M205 block
// (slicer_file.h, i3_file_limits()) and estimates with it: the image is then
// not probed (the block sets every rate and acceleration), only its
// descriptor read for steps/mm. --flow writes M220 S100 and M221 S<PERCENT>.
// The file goes to standard output (or FILE); the limits, the estimate and
// the line count to standard error. Exit 0, 2 on bad usage or a bad image.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>

#include "print_limits.h"
#include "slicer_file.h"

int main(int argc, char** argv) {
  std::string elf, output;
  sim::SlicerOptions o;
  const auto usage = [] {
    std::cerr << "usage: avrmotion-slicer (--board NAME | --elf FILE) [--layers N] [--perimeters N] [--segments N]\n"
                 "                        [--end-m400] [--machine-limits i3] [--flow PERCENT] [--no-progress]\n"
                 "                        [--output FILE]\n";
    return 2;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has = i + 1 < argc;
    const auto count = [&](int& v) {
      v = std::atoi(argv[++i]);
      return v >= 1 && v <= 10000;
    };
    if (a == "--board" && has) elf = std::string(AVRMOTION_FIRMWARE_DIR) + "/avrmotion-" + argv[++i] + ".elf";
    else if (a == "--elf" && has) elf = argv[++i];
    else if (a == "--output" && has) output = argv[++i];
    else if (a == "--end-m400") o.end_m400 = true;
    else if (a == "--no-progress") o.progress = false;
    else if (a == "--machine-limits" && has && std::string(argv[i + 1]) == "i3") {
      ++i;
      o.machine_limits = true;
      o.file_limits = sim::i3_file_limits();
    } else if (a == "--flow" && has && count(o.flow_percent) && o.flow_percent >= 10 && o.flow_percent <= 500) {
    }
    else if (!((a == "--layers" && has && count(o.layers)) || (a == "--perimeters" && has && count(o.perimeters)) ||
               (a == "--segments" && has && count(o.segments) && o.segments >= 3)))
      return usage();
  }
  if (elf.empty()) return usage();
  try {
    const sim::MachineLimits board = sim::board_limits(elf);
    const sim::MachineLimits limits =
        o.machine_limits && sim::file_sets_all(board, o.file_limits) ? board : sim::probe_limits(elf);
    const sim::SlicerFile f = sim::write_slicer_file(limits, o);
    std::ofstream file;
    if (!output.empty()) {
      file.open(output);
      if (!file) throw std::runtime_error("cannot write " + output);
    }
    std::ostream& out = output.empty() ? std::cout : file;
    for (const std::string& l : f.lines) out << l << "\n";
    std::fprintf(stderr, "avrmotion-slicer: %s\navrmotion-slicer: %zu lines (%zu sent), %zu moves timed, estimate %.3f s (%s)\n",
                 (o.machine_limits ? sim::apply_file_limits(limits, o.file_limits) : limits).describe().c_str(), f.lines.size(), f.command_lines(), f.moves, f.estimate_s,
                 sim::slicer_duration(f.estimate_s).c_str());
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "avrmotion-slicer: " << e.what() << "\n";
    return 2;
  }
}
