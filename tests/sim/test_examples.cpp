// The example jobs in examples/ run as their comments say: the README points
// users at them, so they must stay true.
#include <fstream>
#include <string>
#include <vector>

#include "endstops.h"
#include "sim_fixture.h"

namespace {

std::vector<std::string> job(const std::string& file) {
  std::ifstream in(std::string(AVRMOTION_SOURCE_DIR) + "/examples/" + file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find('#'));
    const size_t end = line.find_last_not_of(" \t\r");
    if (end != std::string::npos) lines.push_back(line.substr(0, end + 1));
  }
  return lines;
}

}  // namespace

TEST(Examples, UnoDemo) {
  const auto lines = job("demo.txt");
  ASSERT_EQ(lines.size(), 9u);
  auto m = simtest::run("uno", lines, 30);
  EXPECT_EQ(m->serial().errors(), std::vector<std::string>{"error: no such axis on this board"});
  const std::vector<std::string> messages = {"warning: F clamped to 160000", "pos X:450 Y:-250 U:2048 Z:0"};
  EXPECT_EQ(m->serial().messages(), messages);
  EXPECT_DOUBLE_EQ(m->axis('X')->steps(), 450);  // 500 full steps, then 800 sixteenths back
  EXPECT_DOUBLE_EQ(m->axis('Y')->steps(), -250);
  EXPECT_DOUBLE_EQ(m->axis('U')->steps(), 2048);
  EXPECT_DOUBLE_EQ(m->axis('Z')->steps(), 0);
  EXPECT_EQ(m->axis('Z')->step_cycles.size(), 80000u);
}

TEST(Examples, M32Demo) {
  // The world avrmotion-sim gives the m32: its switches at 0.
  sim::Machine m(simtest::image("m32"));
  sim::Endstops switches(m);
  for (const std::string& l : job("m32-demo.txt")) m.serial().add_line(l);
  ASSERT_EQ(m.run_script(uint64_t(30 * m.f_cpu())), sim::RunEnd::done);
  EXPECT_EQ(m.serial().errors(), std::vector<std::string>{"error: move beyond the soft limits"});
  const std::vector<std::string> messages = {"warning: F clamped to 40000", "pos X:0 Y:15000 Z:500 E:3000"};
  EXPECT_EQ(m.serial().messages(), messages);
  EXPECT_DOUBLE_EQ(m.axis('X')->steps(), 1000);  // homed 1 mm off the switch
  EXPECT_DOUBLE_EQ(m.axis('Y')->steps(), 16000);
  EXPECT_DOUBLE_EQ(m.axis('Z')->steps(), 1500);
}

TEST(Examples, M16Demo) {
  auto m = simtest::run("m16", job("m16-demo.txt"), 30);
  EXPECT_TRUE(m->serial().errors().empty());
  EXPECT_EQ(m->serial().messages(), std::vector<std::string>{"pos Z:0 U:2048"});
  EXPECT_EQ(m->axis('Z')->step_cycles.size(), 6300u);  // 50 mm out and back
}

TEST(Examples, UnoPlotter) {
  auto m = simtest::run("uno", job("uno-plotter.gcode"), 60);
  EXPECT_TRUE(m->serial().errors().empty());
  ASSERT_EQ(m->serial().messages().size(), 1u);
  EXPECT_EQ(m->serial().messages()[0], "X:0.0000 Y:0.0000 U:0.0000 Z:2.0000 Count X:0 Y:0 U:0 Z:800");
  // The square's four sides and the diamond's four: 50 full steps each
  // axis per side, the diagonals 125 on both axes at once.
  EXPECT_EQ(m->axis('X')->step_cycles.size(), 250u + 500u + 125u + 4 * 125u + 375u);
  EXPECT_DOUBLE_EQ(m->axis('X')->steps(), 0);
  EXPECT_DOUBLE_EQ(m->axis('Y')->steps(), 0);
  EXPECT_DOUBLE_EQ(m->axis('Z')->steps(), 800);
}
