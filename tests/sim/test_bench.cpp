// avrmotion-bench, run as a user runs it: in parallel it prints the same
// tables as one job at a time, its --markdown page carries every figure of
// those tables (and the image sizes, and the quoted anchors), it says what
// it is doing on standard error, docs/benchmarks.md is the page it writes
// today, and a broken run fails it. The whole benchmark takes about a
// minute on two cores (the hot end's 200 s and the print's 191 s of
// simulated time are the longest jobs).
#include <gtest/gtest.h>
#include <sim_core_config.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "sim_fixture.h"

namespace {

std::string bench_exe() {
#ifdef AVRMOTION_BENCH_EXE
  return AVRMOTION_BENCH_EXE;
#else
  // Built next to avrmotion-sim, in the same directory.
  const std::string sim = AVRMOTION_SIM_EXE;
  return sim.substr(0, sim.rfind('/') + 1) + "avrmotion-bench";
#endif
}

// The figures are those of the patched simulator: against Debian's stock
// libsimavr the timer-pulsed axis does not step exactly (docs/simulator.md),
// so the benchmark reports a broken run there, as it must.
bool patched_simavr() { return std::string(CONFIG_SIMAVR_VERSION).find("avrmotion") != std::string::npos; }

using simtest::exists;
using simtest::slurp;
using simtest::temp_path;

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

std::vector<std::string> words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

std::string without(std::string s, const std::string& chars) {
  std::string out;
  for (char c : s) {
    if (chars.find(c) == std::string::npos) out += c;
  }
  return out;
}

// A Markdown table row's cells, trimmed, without the code ticks.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::string cell;
  for (size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '|') {
      const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
      out.push_back(a == std::string::npos ? "" : without(cell.substr(a, b - a + 1), "`"));
      cell.clear();
    } else {
      cell += row[i];
    }
  }
  return out;
}

struct BenchRun {
  int status = -1;  // exit status, -1 if it did not exit
  std::string out, err;
};

BenchRun bench(const std::string& args, const std::string& tag) {
  EXPECT_TRUE(exists(bench_exe())) << bench_exe() << " is missing: build the avrmotion-bench target";
  const std::string out = temp_path(tag + ".out"), err = temp_path(tag + ".err");
  const std::string cmd = "'" + bench_exe() + "' " + args + " > '" + out + "' 2> '" + err + "'";
  const int rc = std::system(cmd.c_str());
  BenchRun r;
  r.status = WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::remove(out.c_str());
  std::remove(err.c_str());
  return r;
}

std::string firmware_dir() { return std::string("--firmware-dir '") + AVRMOTION_FIRMWARE_DIR + "'"; }

// Standard output's step-engine rows (ten columns, from "F asked" to
// "exact") and image-size rows ("uno atmega328p 16618 (50.7%) ...": seven
// words once the parentheses go).
void stdout_rows(const std::string& out, std::vector<std::vector<std::string>>& engine,
                 std::vector<std::vector<std::string>>& sizes) {
  bool in_sizes = false;
  for (const std::string& line : lines_of(out)) {
    if (line.rfind("Image sizes", 0) == 0) in_sizes = true;
    if (line.empty()) in_sizes = false;
    const std::vector<std::string> w = words(without(line, "()"));
    if (w.empty() || w[0] == "image" || w[0] == "F") continue;
    if (in_sizes && w.size() == 7) sizes.push_back(w);
    if (!in_sizes && w.size() == 10 && std::isdigit(static_cast<unsigned char>(w[0][0]))) engine.push_back(w);
  }
}

TEST(Bench, ParallelPageHasEveryFigureAndTheDocsPageIsCurrent) {
  if (!patched_simavr()) GTEST_SKIP() << "the benchmark's figures are the patched simulator's";
  const std::string md = temp_path("benchmarks.md");
  std::remove(md.c_str());
  const BenchRun r = bench(firmware_dir() + " --jobs 2 --markdown '" + md + "'", "parallel");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string page = slurp(md);
  std::remove(md.c_str());
  ASSERT_FALSE(page.empty()) << r.err;

  std::vector<std::vector<std::string>> engine, sizes;
  stdout_rows(r.out, engine, sizes);
  ASSERT_EQ(engine.size(), 15u) << r.out;  // the scenarios of sim/bench_scenarios.cpp
  ASSERT_EQ(sizes.size(), 13u) << r.out;  // sim/bench_scenarios.cpp's kSizeImages

  // The page's rows, in order: the same figures in the same columns (the
  // page writes "45.5 %" where the terminal writes "45.5%", and puts the
  // command in front of the step-engine rows, the clock after the MCU).
  std::vector<std::vector<std::string>> page_engine, page_sizes;
  for (const std::string& line : lines_of(page)) {
    if (line.rfind("| `MOVE ", 0) == 0) page_engine.push_back(cells(line));
    for (const auto& s : sizes) {
      if (line.rfind("| " + s[0] + " | ", 0) == 0) page_sizes.push_back(cells(line));
    }
  }
  ASSERT_EQ(page_engine.size(), engine.size()) << page;
  for (size_t i = 0; i < engine.size(); ++i) {
    ASSERT_EQ(page_engine[i].size(), 11u) << i;
    EXPECT_EQ(page_engine[i][0].rfind("MOVE ", 0), 0u);
    for (size_t c = 0; c < 10; ++c) EXPECT_EQ(without(page_engine[i][c + 1], " "), engine[i][c]) << i << " " << c;
  }
  ASSERT_EQ(page_sizes.size(), sizes.size()) << page;
  for (size_t i = 0; i < sizes.size(); ++i) {
    const std::vector<std::string>& p = page_sizes[i];
    ASSERT_EQ(p.size(), 10u) << i;
    EXPECT_EQ(p[0], sizes[i][0]);
    EXPECT_EQ(p[1], sizes[i][1]);
    EXPECT_EQ(p[3], sizes[i][2]);
    EXPECT_EQ(without(p[4], " "), sizes[i][3]);
    EXPECT_EQ(p[5], sizes[i][4]);
    EXPECT_EQ(without(p[6], " "), sizes[i][5]);
    EXPECT_EQ(p[7], sizes[i][6]);
  }

  // The anchors, as docs/step-engine.md quotes them, marked as quoted.
  for (const char* a : {"| grbl 1.1h | 32 kHz | 362 |", "| FastAccelStepper | 80 kHz | 149 |",
                        "| AccelStepper 1.64 | 4.45 kHz |"}) {
    EXPECT_NE(page.find(a), std::string::npos) << a;
  }
  EXPECT_NE(page.find("not re-measured"), std::string::npos);

  // The hot end's row: the figures the terminal prints, on the page.
  std::vector<std::string> hot_out, hot_page;
  const std::vector<std::string> out_lines = lines_of(r.out);
  for (size_t i = 0; i + 2 < out_lines.size(); ++i) {
    if (out_lines[i].rfind("Hot end, m32:", 0) != 0) continue;
    for (const std::string& w : words(without(out_lines[i + 2], ","))) {
      if (std::isdigit(static_cast<unsigned char>(w[0]))) hot_out.push_back(w);
    }
  }
  for (const std::string& line : lines_of(page)) {
    if (line.rfind("| ", 0) == 0 && line.find("..") != std::string::npos && hot_page.empty()) {
      const std::vector<std::string> c = cells(line);
      if (c.size() == 7) hot_page = c;
    }
  }
  ASSERT_EQ(hot_out.size(), 7u) << r.out;  // to 200 C, overshoot, settled, hold, mean, max, samples
  EXPECT_EQ(hot_page, hot_out) << page;

  // The prints' rows ("print coarse 8 48 25 1064 ...": fifteen words): the
  // figures the terminal prints, on the page, and runs that printed the
  // whole file without an error, exactly (a broken one fails the benchmark).
  std::vector<std::vector<std::string>> print_out, print_page;
  for (const std::string& line : lines_of(r.out)) {
    const std::vector<std::string> w = words(line);
    if (w.size() == 15 && w[0] == "print") print_out.emplace_back(w.begin() + 1, w.end());
  }
  const size_t print_heading = page.find("## Slicer's prints (m32)");
  ASSERT_NE(print_heading, std::string::npos) << page;
  for (const std::string& line : lines_of(page.substr(print_heading))) {
    if (line.rfind("## ", 0) == 0 && !print_page.empty()) break;
    const std::vector<std::string> c = cells(line);
    if (c.size() == 14 && c[1].size() && std::isdigit(static_cast<unsigned char>(c[1][0]))) print_page.push_back(c);
  }
  ASSERT_EQ(print_out.size(), 3u) << r.out;  // sim/bench_print.cpp's files: coarse, fine, i3
  EXPECT_EQ(print_page, print_out) << page;
  for (const std::vector<std::string>& p : print_out) {
    EXPECT_EQ(p[4], p[5]);    // lines, answered: every line answered
    EXPECT_EQ(p[6], "0");     // no error
    EXPECT_EQ(p[12], "yes");  // exact
  }

  // The lathe's rows ("x4 K0.5 800 0.3 32000 ...": thirteen words): the
  // figures the terminal prints, on the page.
  std::vector<std::vector<std::string>> lathe_out, lathe_page;
  for (const std::string& line : lines_of(r.out)) {
    const std::vector<std::string> w = words(line);
    if (w.size() == 13 && (w[0] == "x4" || w[0] == "x1")) lathe_out.push_back(w);
  }
  for (const std::string& line : lines_of(page)) {
    if (line.rfind("| x4 | ", 0) == 0 || line.rfind("| x1 | ", 0) == 0) lathe_page.push_back(cells(line));
  }
  ASSERT_EQ(lathe_out.size(), 22u) << r.out;  // sim/bench_lathe.cpp's rows
  EXPECT_EQ(lathe_page, lathe_out) << page;

  // Progress: every job (the hot end, the print, a scenario, a lathe row or
  // a size row) starts and ends on standard error.
  const size_t jobs = 1 + print_out.size() + engine.size() + lathe_out.size() + sizes.size();
  size_t started = 0, ended = 0;
  for (const std::string& line : lines_of(r.err)) {
    started += line.find("] start ") != std::string::npos;
    ended += line.find("] done ") != std::string::npos;
  }
  EXPECT_EQ(started, jobs) << r.err;
  EXPECT_EQ(ended, jobs) << r.err;
  EXPECT_NE(r.err.find(std::to_string(jobs) + " jobs on 2 workers"), std::string::npos) << r.err;

  // The committed page is today's: no figure in it that the benchmark does
  // not print now.
  EXPECT_EQ(slurp(std::string(AVRMOTION_SOURCE_DIR) + "/docs/benchmarks.md"), page)
      << "docs/benchmarks.md is out of date: regenerate it with avrmotion-bench --markdown docs/benchmarks.md";
}

TEST(Bench, SerialAndParallelRunsPrintTheSameTables) {
  if (!patched_simavr()) GTEST_SKIP() << "the benchmark's figures are the patched simulator's";
  const BenchRun serial = bench(firmware_dir() + " --jobs 1", "serial");
  const BenchRun parallel = bench(firmware_dir() + " --jobs 3", "jobs3");
  ASSERT_EQ(serial.status, 0) << serial.err;
  ASSERT_EQ(parallel.status, 0) << parallel.err;
  EXPECT_FALSE(serial.out.empty());
  EXPECT_EQ(serial.out, parallel.out);
}

TEST(Bench, ABrokenRunFailsAndWritesNoPage) {
  // No images: no run can finish. Every job is tried, the status says so,
  // and no page replaces a good one.
  const std::string md = temp_path("broken.md"), none = temp_path("no-firmware");
  std::remove(md.c_str());
  const BenchRun r = bench("--firmware-dir '" + none + "' --jobs 2 --markdown '" + md + "'", "broken");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_FALSE(exists(md));
  EXPECT_NE(r.err.find("BROKEN"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did not finish"), std::string::npos) << r.err;
  // The tables are still printed, every run marked not exact.
  size_t not_exact = 0;
  for (const std::string& line : lines_of(r.out)) not_exact += line.size() > 3 && line.substr(line.size() - 3) == " NO";
  EXPECT_EQ(not_exact, 15u) << r.out;  // the engine tables' rows: 5 + 3 + 5 + 2
  std::remove(md.c_str());
}

TEST(Bench, RejectsBadUsage) {
  EXPECT_EQ(bench("--jobs 0", "jobs0").status, 2);
  EXPECT_EQ(bench("--jobs", "jobs-missing").status, 2);
  EXPECT_EQ(bench("--frobnicate", "bad-option").status, 2);
  const BenchRun help = bench("--help", "help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("--markdown FILE"), std::string::npos);
}

}  // namespace
