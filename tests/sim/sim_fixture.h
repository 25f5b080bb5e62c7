// Helpers shared by the simavr tests: load a board image, run a script.
#pragma once
#include <gtest/gtest.h>

#include <unistd.h>

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

inline std::vector<uint64_t> intervals(const std::vector<uint64_t>& stamps) {
  std::vector<uint64_t> out;
  for (size_t i = 1; i < stamps.size(); ++i) out.push_back(stamps[i] - stamps[i - 1]);
  return out;
}

}  // namespace simtest
