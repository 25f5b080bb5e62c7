// Traces and progress: the VCD file avrmotion-sim --vcd writes (well formed,
// one variable per chosen signal, cycle-exact times, as many step edges as
// the report counts, interrupt windows as the profiler counts them) and the
// --progress lines (the last one says what the report says).
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "plot.h"
#include "progress.h"
#include "report.h"
#include "sim_fixture.h"
#include "vcd.h"
#include "vcd_read.h"
#include "xml_check.h"

namespace {

using simtest::exists;
using simtest::slurp;
using simtest::temp_path;

// A number or string value of the report's top level.
std::string json_value(const std::string& json, const std::string& key) {
  const std::regex re("\"" + key + "\": (\"[^\"]*\"|[-0-9.e+]+)");
  std::smatch m;
  if (!std::regex_search(json, m, re)) return "";
  return m[1];
}

size_t json_errors(const std::string& json) {
  const size_t a = json.find("\"errors\": [");
  if (a == std::string::npos) return size_t(-1);
  const size_t b = json.find(']', a);
  const std::string list = json.substr(a + 11, b - a - 11);
  if (list.empty()) return 0;
  size_t n = 0;
  for (size_t i = 0; (i = list.find("\"error", i)) != std::string::npos; ++i) ++n;
  return n;
}

// Runs `lines` on `image` with a trace of `spec`, returns the machine.
std::unique_ptr<sim::Machine> traced(const std::string& image, const std::vector<std::string>& lines,
                                     const std::string& path, const std::string& spec = "board,isr,pwm") {
  std::unique_ptr<sim::Machine> m(new sim::Machine(simtest::image(image)));
  for (const auto& l : lines) m->serial().add_line(l);
  sim::VcdRecorder vcd(*m, path, spec);
  EXPECT_EQ(m->run_script(uint64_t(20) * m->f_cpu()), sim::RunEnd::done);
  vcd.finish();
  return m;
}

uint64_t ps_per_cycle(const sim::Machine& m) { return 1000000000000ull / m.f_cpu(); }

TEST(Vcd, StepEdgesAndInterruptWindowsMatchTheReport) {
  const std::string path = temp_path("m32.vcd");
  auto m = traced("m32", {"G91", "G1 X2 F1200", "G1 Y-0.5 F300"}, path);
  const vcdread::Trace t = vcdread::read(path);
  ASSERT_EQ(t.error, "");
  EXPECT_EQ(t.redundant, 0u) << "only changes are written";
  EXPECT_EQ(t.timescale, "1ps");
  EXPECT_NE(t.comment.find("62500 ps"), std::string::npos) << t.comment;
  // Every pin the board descriptor names is there, grouped by axis.
  for (const char* name : {"m32.X.step_PC0", "m32.X.dir_PC1", "m32.X.enable_PB0", "m32.Y.step_PC2", "m32.Z.step_PC4",
                           "m32.E.step_PC6", "m32.isr.v7_TIMER1_COMPA"}) {
    EXPECT_TRUE(t.by_name(name)) << name;
  }
  // The groups keep only vectors that ran and duties that were set: one
  // signal per vector in the report, none flat.
  size_t vectors = 0;
  for (const vcdread::Var& v : t.vars) {
    if (v.name.find(".isr.") == std::string::npos && v.name.find(".pwm.") == std::string::npos) continue;
    vectors += v.name.find(".isr.") != std::string::npos;
    EXPECT_GT(t.changes.at(v.id).size(), 1u) << v.name << " never changes";
  }
  EXPECT_EQ(vectors, m->isr_stats().size());
  std::ostringstream report;
  sim::write_report(report, *m, sim::RunEnd::done);
  const std::string json = report.str();
  // As many rising step edges as step events, at exactly the decoded cycles.
  for (const char axis : {'X', 'Y', 'Z'}) {
    const vcdread::Var* step = t.by_name(std::string(1, axis) + ".step_PC" +
                                         char('0' + 2 * (axis == 'X'   ? 0
                                                         : axis == 'Y' ? 1
                                                                       : 2)));
    ASSERT_TRUE(step) << axis;
    const std::vector<uint64_t> edges = t.rising(step->id);
    const sim::AxisTrace* a = m->axis(axis);
    ASSERT_EQ(edges.size(), a->step_cycles.size()) << axis;
    for (size_t i = 0; i < edges.size(); ++i) {
      ASSERT_EQ(edges[i] % ps_per_cycle(*m), 0u);
      ASSERT_EQ(edges[i] / ps_per_cycle(*m), a->step_cycles[i]) << axis << " step " << i;
    }
    const std::regex re(std::string("\"") + axis + "\": \\{\"step_events\": ([0-9]+)");
    std::smatch sm;
    ASSERT_TRUE(std::regex_search(json, sm, re)) << axis;
    EXPECT_EQ(std::to_string(edges.size()), sm[1].str()) << axis;
  }
  EXPECT_EQ(m->axis('X')->step_cycles.size(), 2000u);
  // The step interrupt's windows: as many as the profiler counted, as long.
  const vcdread::Var* isr = t.by_name("isr.v7_TIMER1_COMPA");
  ASSERT_TRUE(isr);
  const auto& ch = t.changes.at(isr->id);
  uint64_t windows = 0, cycles = 0;
  for (size_t i = 1; i < ch.size(); ++i) {
    if (ch[i].value == "0" && ch[i - 1].value == "1") {
      ++windows;
      cycles += (ch[i].time - ch[i - 1].time) / ps_per_cycle(*m);
    }
  }
  EXPECT_EQ(windows, m->isr_stats().at(7).count);
  EXPECT_EQ(cycles, m->isr_stats().at(7).total_cycles);
  // The trace ends where the run ended.
  EXPECT_EQ(t.stamps.back(), m->cycles() * ps_per_cycle(*m));
  std::remove(path.c_str());
}

TEST(Vcd, HardwareTimedStepPinIsTracedEdgeForEdge) {
  // Uno axis Z: STEP is OC1A, driven by the timer (simavr flags those pin
  // changes as outputs); every pulse must show.
  const std::string path = temp_path("uno-z.vcd");
  auto m = traced("uno", {"MOVE Z1000 F50000 A300000", "MOVE Z-300 F50000 A300000"}, path);
  const vcdread::Trace t = vcdread::read(path);
  ASSERT_EQ(t.error, "");
  const vcdread::Var* step = t.by_name("uno.Z.step_PB1");
  ASSERT_TRUE(step);
  const std::vector<uint64_t> edges = t.rising(step->id);
  ASSERT_EQ(edges.size(), 1300u);
  ASSERT_EQ(m->axis('Z')->step_cycles.size(), 1300u);
  for (size_t i = 0; i < edges.size(); ++i) ASSERT_EQ(edges[i] / ps_per_cycle(*m), m->axis('Z')->step_cycles[i]);
  // The direction line changed once, before the first step back.
  const vcdread::Var* dir = t.by_name("uno.Z.dir_PB2");
  ASSERT_TRUE(dir);
  const auto& d = t.changes.at(dir->id);
  ASSERT_GE(d.size(), 2u);
  EXPECT_LT(d.back().time, edges[1000]);
  EXPECT_GT(d.back().time, edges[999]);
  // The shield's latch lines and enable PWM duties are in the default set.
  EXPECT_TRUE(t.by_name("uno.shield.latch_PB4"));
  EXPECT_TRUE(t.by_name("uno.shield.oe_PD7"));
  std::remove(path.c_str());
}

TEST(Vcd, OnlyTheChosenSignals) {
  const std::string path = temp_path("m32-chosen.vcd");
  traced("m32", {"G1 X0.1 F1200"}, path, "X, isr7, PD3");
  const vcdread::Trace t = vcdread::read(path);
  ASSERT_EQ(t.error, "");
  std::vector<std::string> names;
  for (const auto& v : t.vars) names.push_back(v.name);
  EXPECT_EQ(names, (std::vector<std::string>{"m32.X.step_PC0", "m32.X.dir_PC1", "m32.X.enable_PB0",
                                             "m32.isr.v7_TIMER1_COMPA", "m32.pins.PD3"}));
  std::remove(path.c_str());
  // A name that is none of these is refused, before the run, leaving no file.
  sim::Machine m(simtest::image("m32"));
  const std::string bad = temp_path("m32-bad.vcd");
  EXPECT_THROW(sim::VcdRecorder(m, bad, "X,Q"), std::runtime_error);
  EXPECT_THROW(sim::VcdRecorder(m, bad, "PE9"), std::runtime_error);
  EXPECT_FALSE(exists(bad));
}

// --- progress --------------------------------------------------------------

struct Figures {
  std::string seconds;
  size_t sent = 0, input = 0, answered = 0, ok = 0, errors = 0, percent = 0;
};

bool parse_progress(const std::string& line, Figures& f) {
  static const std::regex re(
      "avrmotion-sim: ([0-9.e+-]+) s simulated, ([0-9]+) of ([0-9]+) lines sent, ([0-9]+) answered "
      "\\(([0-9]+) ok, ([0-9]+) errors?\\), ([0-9]+)% of the input");
  std::smatch m;
  if (!std::regex_match(line, m, re)) return false;
  f.seconds = m[1];
  f.sent = std::stoul(m[2]);
  f.input = std::stoul(m[3]);
  f.answered = std::stoul(m[4]);
  f.ok = std::stoul(m[5]);
  f.errors = std::stoul(m[6]);
  f.percent = std::stoul(m[7]);
  return true;
}

std::vector<std::string> lines_of(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

void expect_matches_report(const std::string& line, const std::string& json) {
  Figures f;
  ASSERT_TRUE(parse_progress(line, f)) << line;
  EXPECT_EQ(f.seconds, json_value(json, "seconds")) << line;
  EXPECT_EQ(std::to_string(f.sent), json_value(json, "lines_sent")) << line;
  EXPECT_EQ(std::to_string(f.ok), json_value(json, "lines_ok")) << line;
  EXPECT_EQ(std::to_string(f.answered), json_value(json, "lines_answered")) << line;
  EXPECT_EQ(std::to_string(f.input), json_value(json, "lines_input")) << line;
  EXPECT_EQ(f.errors, json_errors(json)) << line;
  EXPECT_EQ(f.ok + f.errors, f.answered);
  EXPECT_EQ(f.percent, f.input ? f.answered * 100 / f.input : 100);
}

TEST(Progress, TheLastLineSaysWhatTheReportSays) {
  sim::Machine m(simtest::image("uno"));
  for (const char* l : {"MOVE X100 F400 A800", "MOVE E10", "MOVE Y300 F500 A1000", "POS"}) m.serial().add_line(l);
  std::ostringstream progress;
  const sim::RunEnd end = sim::run_script_with_progress(m, uint64_t(30) * m.f_cpu(), &progress, 0);
  ASSERT_EQ(end, sim::RunEnd::done);
  std::ostringstream report;
  sim::write_report(report, m, end);
  const std::vector<std::string> lines = lines_of(progress.str());
  ASSERT_GE(lines.size(), 3u);  // a line per 0.1 s slice, and the last one
  expect_matches_report(lines.back(), report.str());
  Figures last;
  ASSERT_TRUE(parse_progress(lines.back(), last));
  EXPECT_EQ(last.percent, 100u);
  EXPECT_EQ(last.errors, 1u);
  // On the way: never more than the end, never going back.
  size_t percent = 0;
  for (const std::string& l : lines) {
    Figures f;
    ASSERT_TRUE(parse_progress(l, f)) << l;
    EXPECT_GE(f.percent, percent);
    percent = f.percent;
    EXPECT_LE(f.answered, f.sent);
  }
}

TEST(Progress, ATimedOutRunEndsWithItsOwnFigures) {
  sim::Machine m(simtest::image("uno"));
  for (const char* l : {"MOVE Y2048 F500 A1000", "MOVE Y-2048 F500 A1000", "POS"}) m.serial().add_line(l);
  std::ostringstream progress;
  const sim::RunEnd end = sim::run_script_with_progress(m, m.f_cpu() / 2, &progress, 60);
  ASSERT_EQ(end, sim::RunEnd::budget_spent);
  std::ostringstream report;
  sim::write_report(report, m, end);
  const std::vector<std::string> lines = lines_of(progress.str());
  ASSERT_EQ(lines.size(), 1u);  // only the final line: the wall-clock interval never passed
  expect_matches_report(lines.back(), report.str());
  Figures f;
  ASSERT_TRUE(parse_progress(lines.back(), f));
  EXPECT_LT(f.percent, 100u);
  EXPECT_EQ(f.input, 3u);
}

TEST(Progress, RunningInSlicesChangesNothing) {
  const std::vector<std::string> job = {"MOVE X60 F400 A800", "MOVE Z3000 F40000 A300000", "POS"};
  auto whole = simtest::run("uno", job);
  sim::Machine sliced(simtest::image("uno"));
  for (const auto& l : job) sliced.serial().add_line(l);
  std::ostringstream sink;
  ASSERT_EQ(sim::run_script_with_progress(sliced, uint64_t(10) * sliced.f_cpu(), &sink, 0), sim::RunEnd::done);
  EXPECT_EQ(sliced.cycles(), whole->cycles());
  EXPECT_EQ(sliced.axis('Z')->step_cycles, whole->axis('Z')->step_cycles);
  EXPECT_EQ(sliced.axis('X')->step_cycles, whole->axis('X')->step_cycles);
  // And a budget spent in the middle of a slice ends at the same cycle.
  auto a = std::unique_ptr<sim::Machine>(new sim::Machine(simtest::image("uno")));
  sim::Machine b(simtest::image("uno"));
  for (const auto& l : job) {
    a->serial().add_line(l);
    b.serial().add_line(l);
  }
  const uint64_t budget = 2345679;
  EXPECT_EQ(a->run_script(budget), sim::RunEnd::budget_spent);
  EXPECT_EQ(sim::run_script_with_progress(b, budget, nullptr), sim::RunEnd::budget_spent);
  EXPECT_EQ(a->cycles(), b.cycles());
}

// --- the command, as a user runs it ------------------------------------------

TEST(Cli, PicturesTraceReportAndProgressLandWhereAsked) {
  const std::string dir = temp_path("cli-");
  const std::string job = dir + "job.txt", svg = dir + "job-m16.svg", vcd = dir + "job-m16.vcd";
  const std::string json = dir + "job-m16.json", err = dir + "job-m16.err";
  { std::ofstream(job) << "# a short job\nMOVE Z300 F1000 A4000\nMOVE U100 F500 A1000\nMOVE Q1\nPOS\n"; }
  const std::string cmd = std::string("'") + AVRMOTION_SIM_EXE + "' --elf '" + simtest::image("m16") + "' --input '" +
                          job + "' --report '" + json + "' --plot '" + svg + "' --vcd '" + vcd +
                          "' --vcd-signals board,isr --progress 2> '" + err + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd << "\n" << slurp(err);
  const std::string report = slurp(json), progress = slurp(err);
  const std::vector<std::string> lines = lines_of(progress);
  ASSERT_FALSE(lines.empty());
  expect_matches_report(lines.back(), report);
  EXPECT_EQ(json_value(report, "lines_input"), "4");
  // The picture parses, the trace reads, with Z's steps in it.
  xmlcheck::Parser parser(slurp(svg));
  ASSERT_TRUE(parser.parse()) << parser.error();
  const vcdread::Trace t = vcdread::read(vcd);
  ASSERT_EQ(t.error, "");
  const vcdread::Var* step = t.by_name("m16.Z.step_PC0");
  ASSERT_TRUE(step);
  EXPECT_EQ(t.rising(step->id).size(), 300u);
  EXPECT_FALSE(t.by_name("OC1A_duty"));  // pwm was not asked for
  // Bad signal names are a usage error (2), and no trace is left behind.
  const std::string bad = dir + "bad.vcd";
  const std::string cmd2 = std::string("'") + AVRMOTION_SIM_EXE + "' --elf '" + simtest::image("m16") + "' --input '" +
                           job + "' --report /dev/null --vcd '" + bad + "' --vcd-signals nonsense 2>/dev/null";
  const int rc = std::system(cmd2.c_str());
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 2) << rc;
  EXPECT_FALSE(exists(bad));
  for (const std::string& f : {job, svg, vcd, json, err}) std::remove(f.c_str());
}

}  // namespace
