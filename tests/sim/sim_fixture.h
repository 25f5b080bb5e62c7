// Helpers shared by the simavr tests: load a board image, run a script.
#pragma once
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "machine.h"

namespace simtest {

inline std::string image(const std::string& name) {
  return std::string(AVRMOTION_FIRMWARE_DIR) + "/avrmotion-" + name + ".elf";
}

// Runs `lines` on a fresh machine of image `name`; fails the test if the run
// does not finish within `seconds` of simulated time.
inline std::unique_ptr<sim::Machine> run(const std::string& name, const std::vector<std::string>& lines,
                                         double seconds = 10) {
  std::unique_ptr<sim::Machine> m(new sim::Machine(image(name)));
  for (const std::string& l : lines) m->serial().add_line(l);
  const sim::RunEnd end = m->run_script(uint64_t(seconds * m->f_cpu()));
  EXPECT_EQ(end, sim::RunEnd::done) << name << ": script did not finish";
  return m;
}

// A file name in the test temp directory, unique per process: several build
// trees may run their tests at once.
inline std::string temp_path(const std::string& name) {
  return ::testing::TempDir() + "avrmotion-" + std::to_string(getpid()) + "-" + name;
}

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline bool exists(const std::string& path) { return std::ifstream(path).good(); }

// An image's flash (.text + .data) and RAM (.data + .bss) as the
// toolchain's avr-size prints them for its MCU; 0 and 0 if it could not be
// run.
struct ImageSize {
  unsigned long flash = 0, ram = 0;
};
inline ImageSize avr_size(const std::string& name, const std::string& mcu) {
  ImageSize size;
  const std::string cmd = "avr-size -C --mcu=" + mcu + " " + image(name);
  FILE* out = popen(cmd.c_str(), "r");
  if (!out) return size;
  char line[256];
  while (fgets(line, sizeof line, out)) {
    std::sscanf(line, "Program: %lu", &size.flash);
    std::sscanf(line, "Data: %lu", &size.ram);
  }
  pclose(out);
  return size;
}
inline ImageSize avr_size_m16(const std::string& name) { return avr_size(name, "atmega16"); }

// A PWM output's edges: the cycles of its rises, and its high times.
struct PwmTrace {
  std::vector<uint64_t> rises;
  uint64_t high_total = 0;  // cycles high, over `highs` completed pulses
  size_t highs = 0;
};
inline PwmTrace pwm_trace(const std::vector<sim::PinEdge>& edges) {
  PwmTrace t;
  uint64_t last_rise = 0;
  for (const sim::PinEdge& e : edges) {
    if (e.level) {
      t.rises.push_back(e.cycle);
      last_rise = e.cycle;
    } else if (last_rise) {
      t.high_total += e.cycle - last_rise;
      ++t.highs;
    }
  }
  return t;
}

inline std::vector<uint64_t> intervals(const std::vector<uint64_t>& stamps) {
  std::vector<uint64_t> out;
  for (size_t i = 1; i < stamps.size(); ++i) out.push_back(stamps[i] - stamps[i - 1]);
  return out;
}

}  // namespace simtest
