// Why a file of short chords runs slower than a slicer's estimate (the
// benchmark's fine row, docs/simulator.md): the planner ring's fill while
// such a print runs, read from the firmware's RAM. One layer of the fine
// file (240 chords of 0.26 mm round a 10 mm radius, 30 mm/s perimeters),
// one line in flight at 115200 baud, the m32 image hot from the start. At
// every X step edge between the answers to the first and the last
// perimeter chord (the infill's long lines keep the ring full: not the
// case in question), the ring's blocks not yet taken
// (firmware/engine/path.cpp's plan()::instance: core/motion/path_planner.h's
// count_ less taken_, its second and third bytes). Printed: the share of
// samples at each fill, the mean, the time between two answers (the line
// rate) against a perimeter chord's time at its feed, and the print's time
// against the estimate. Checked: the fill never above the ring's 5 blocks
// (board::kPathBlocks), every sample counted once, and the host's line
// period not shorter than the bytes' time on the wire.
#include <gtest/gtest.h>
#include <sim_avr.h>

#include <cstdio>
#include <string>
#include <vector>

#include "board_info.h"
#include "endstops.h"
#include "machine.h"
#include "print_limits.h"
#include "slicer_file.h"
#include "sim_fixture.h"
#include "thermal_plant.h"

namespace {

constexpr int kRingBlocks = 5;  // firmware/boards/common/m32_printer.h

std::string command_of(const std::string& line) {
  std::string s = line.substr(0, line.find(';'));
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

}  // namespace

TEST(PrintRing, TheFineFilesRingRunsShortOfBlocks) {
  const std::string image = simtest::image("m32");
  const sim::ElfSymbol ring = sim::find_symbol(image, "_ZZN4path12_GLOBAL__N_14planEvE8instance");
  ASSERT_TRUE(ring.found);
  const uint16_t at = uint16_t(ring.value & 0xFFFF);
  const sim::MachineLimits limits = sim::probe_limits(image);
  sim::SlicerOptions o;
  o.layers = 1;
  o.segments = 240;
  o.end_m400 = true;
  const sim::SlicerFile file = sim::write_slicer_file(limits, o);

  sim::Machine m(image);
  sim::ThermalParams hot;
  hot.initial_c = 200;
  sim::ThermalPlant plant(m, hot);
  sim::Endstops switches(m);
  struct Sample {
    uint64_t cycle;
    int waiting;
  };
  std::vector<Sample> samples;
  const am::BoardDescriptor& b = m.board();
  uint8_t x_step = am::kNoPin;
  for (uint8_t i = 0; i < b.axis_count; ++i)
    if (b.axes[i].name == 'X') x_step = b.axes[i].pins[0];
  ASSERT_NE(x_step, am::kNoPin);
  m.listen_pin(am::pin_port(x_step), am::pin_bit(x_step), [&](bool level, uint64_t cycle) {
    if (level) samples.push_back({cycle, int(m.avr()->data[at + 1]) - int(m.avr()->data[at + 2])});
  });
  // The perimeters: the command lines from the one after ;TYPE:Perimeter
  // to the last before ;TYPE:Internal infill less its retract and travel
  // (2 lines) and its unretraction.
  size_t bytes = 0, first_perimeter = 0, infill = 0;
  for (const std::string& l : file.lines) {
    if (l == ";TYPE:Perimeter") first_perimeter = m.serial().lines_pending();
    if (l == ";TYPE:Internal infill") infill = m.serial().lines_pending();
    const std::string c = command_of(l);
    if (c.empty()) continue;
    m.serial().add_line(c);
    bytes += c.size() + 1;
  }
  ASSERT_GT(infill, first_perimeter + 400);
  const size_t lines = m.serial().lines_pending();
  ASSERT_EQ(m.run_script(uint64_t(m.f_cpu()) * 300), sim::RunEnd::done);

  uint64_t heated = 0, parked = 0;
  std::vector<uint64_t> answers;
  const std::vector<sim::Response>& rs = m.serial().responses();
  for (size_t i = 0; i < lines && i < rs.size(); ++i) {
    ASSERT_TRUE(sim::SerialHost::is_ok(rs[i].answer)) << rs[i].line;
    if (rs[i].line.rfind("M109 ", 0) == 0 && !heated) heated = rs[i].answer_cycle;
    if (rs[i].line == "M400" && !parked) parked = rs[i].answer_cycle;
    if (i >= first_perimeter && i + 3 < infill) answers.push_back(rs[i].answer_cycle);
  }
  ASSERT_TRUE(heated && parked);
  ASSERT_GT(answers.size(), 200u);

  int count[kRingBlocks + 2] = {};
  size_t n = 0;
  double sum = 0;
  for (const Sample& s : samples) {
    if (s.cycle < answers.front() || s.cycle > answers.back()) continue;
    ASSERT_GE(s.waiting, 0);
    ASSERT_LE(s.waiting, kRingBlocks);
    ++count[s.waiting];
    ++n;
    sum += s.waiting;
  }
  ASSERT_GT(n, 1000u);
  uint64_t first, last;
  ASSERT_TRUE(sim::motion_span(m.axes(), heated, parked, first, last));
  size_t counted = 0;
  for (int k = 0; k <= kRingBlocks; ++k) counted += size_t(count[k]);
  EXPECT_EQ(counted, n);

  const double f = m.f_cpu();
  const double period_ms = double(answers.back() - answers.front()) / double(answers.size() - 1) / f * 1000;
  const double chord_mm = 2 * 3.14159265358979 * 10 / o.segments, chord_ms = chord_mm / (o.perimeter_feed / 60) * 1000;
  // A line's bytes take 10 bits each at 115200 baud: the host cannot be faster.
  EXPECT_GT(period_ms, double(bytes) / double(lines) * 10 / 115200 * 1000);
  std::printf("ring fill (blocks not yet taken, %zu samples at X steps):", n);
  for (int k = 0; k <= kRingBlocks; ++k) std::printf(" %d: %.1f %%", k, 100.0 * count[k] / double(n));
  std::printf("; mean %.2f\n", sum / double(n));
  std::printf("print %.3f s against the estimate's %.3f s: ratio %.3f\n", double(last - first) / f, file.estimate_s,
              double(last - first) / f / file.estimate_s);
  std::printf("perimeters: %zu lines answered over %.3f s\n", answers.size(), double(answers.back() - answers.front()) / f);
  std::printf("line period %.2f ms (the perimeters' answers) against %.2f ms a %.3f mm chord at %.0f mm/s\n", period_ms,
              chord_ms, chord_mm, o.perimeter_feed / 60);
}
