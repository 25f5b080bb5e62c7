// Running tests/sim/printcore_stream.py (printrun's printcore, Debian's
// printrun-common) against a port, and reading the JSON summary it prints
// (its keys: printcore_stream.py's header). For test_printcore*.cpp.
#pragma once
#include <cstdio>
#include <regex>
#include <string>

namespace printcore_run {

// One number of the summary, -1 if it has none.
inline long summary_number(const std::string& json, const std::string& key) {
  std::smatch m;
  return std::regex_search(json, m, std::regex("\"" + key + "\": (-?[0-9]+)")) ? std::stol(m[1]) : -1;
}

// A command's standard output, with "<exit status not 0>" after it when
// it failed.
inline std::string run_output(const std::string& command) {
  std::string out;
  if (FILE* f = popen(command.c_str(), "r")) {
    char buf[4096];
    for (size_t n; (n = fread(buf, 1, sizeof buf, f)) > 0;) out.append(buf, n);
    if (pclose(f) != 0) out += "\n<exit status not 0>";
  }
  return out;
}

// printcore_stream.py PORT FILE `options`: its summary.
inline std::string stream(const std::string& port, const std::string& file, const std::string& options) {
  return run_output(std::string(AVRMOTION_PRINTCORE_PYTHON) + " '" + AVRMOTION_SOURCE_DIR +
                    "/tests/sim/printcore_stream.py' " + port + " '" + file + "' " + options + " 2>/dev/null");
}

}  // namespace printcore_run
