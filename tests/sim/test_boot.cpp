// Every board image boots in its safe state, greets the host and answers.
#include <string>

#include "sim_fixture.h"

namespace {

struct Image {
  const char* name;
  const char* board;
  const char* mcu;
  unsigned long f_cpu;
};

class Boot : public ::testing::TestWithParam<Image> {};

// The printer images speak Marlin (firmware/boards/m32.h, m1284.h); every
// other image speaks grbl.
bool marlin(const Image& img) { return std::string(img.name) == "m32" || std::string(img.name) == "m1284"; }
// Whether the image takes the direct controls (MOVE, POS, ...) beside
// G-code: the m32 printer and the m32-cnc do not.
bool has_commands(const sim::Machine& m) { return m.board().program & am::kProgramCommands; }

TEST_P(Boot, BannerNamesBoardAndClockThenAnswers) {
  const Image& img = GetParam();
  auto m = simtest::run(img.name, {"POS", "NOPE"}, 1);
  const std::string expected = std::string("avrmotion ") + AVRMOTION_VERSION_STRING + " board=" + img.board +
                               " mcu=" + img.mcu + " f_cpu=" + std::to_string(img.f_cpu);
  const auto& got = m->serial().received();
  ASSERT_GE(got.size(), 2u);
  EXPECT_EQ(m->board().f_cpu, img.f_cpu);
  ASSERT_EQ(m->serial().responses().size(), 2u);
  const auto& r = m->serial().responses();
  if (marlin(img)) {
    EXPECT_EQ(m->serial().banner(), "start");
    EXPECT_EQ(got[1], "echo:" + expected);
    // Marlin answers a command it does not have with an echo and ok.
    EXPECT_EQ(r[0].answer, "ok");
    EXPECT_EQ(r[1].answer, "ok");
    const std::vector<std::string> msgs = m->serial().messages();
    ASSERT_EQ(msgs.size(), 2u);
    if (has_commands(*m))
      EXPECT_EQ(msgs[0].rfind("pos X:0 Y:0 Z:0 E:0", 0), 0u) << msgs[0];
    else
      EXPECT_EQ(msgs[0], "echo:Unknown command: \"POS\"");
    EXPECT_EQ(msgs[1], "echo:Unknown command: \"NOPE\"");
  } else {
    EXPECT_EQ(m->serial().banner(), "Grbl 1.1h ['$' for help]");
    EXPECT_EQ(got[1], "[MSG:" + expected + "]");
    EXPECT_EQ(r[0].answer, has_commands(*m) ? "ok" : "error:20");
    EXPECT_EQ(r[1].answer, "error:20");
    EXPECT_EQ(r[1].reason, "unknown command");
  }
  // No axis moved and nothing was decoded as a step.
  for (const sim::AxisTrace& a : m->axes()) EXPECT_TRUE(a.step_cycles.empty()) << a.name;
}

TEST_P(Boot, EveryAxisMovesExactlyAsCommanded) {
  const Image& img = GetParam();
  std::vector<std::string> script;
  sim::Machine probe(simtest::image(img.name));
  // Without the direct controls: the same steps as relative G-code moves
  // (1000 steps/mm).
  const bool commands = has_commands(probe);
  if (!commands) script.push_back("G91");
  for (const sim::AxisTrace& a : probe.axes()) {
    if (!commands) {
      script.push_back(std::string("G1 ") + a.name + "0.037 F120");
      script.push_back(std::string("G1 ") + a.name + "-0.012 F120");
    } else {
      script.push_back(std::string("MOVE ") + a.name + "37 F2000 A20000");
      script.push_back(std::string("MOVE ") + a.name + "-12 F2000 A20000");
    }
  }
  auto m = simtest::run(img.name, script, 5);
  EXPECT_EQ(m->serial().lines_ok(), script.size());
  for (const sim::AxisTrace& a : m->axes()) {
    EXPECT_DOUBLE_EQ(a.steps(), 25.0) << a.name;
    EXPECT_EQ(a.step_cycles.size(), 49u) << a.name;
    EXPECT_EQ(a.decode_errors, 0u) << a.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Images, Boot,
                         ::testing::Values(Image{"uno", "uno", "atmega328p", 16000000},
                                           Image{"m32", "m32", "atmega32", 16000000},
                                           Image{"m32-cnc", "m32-cnc", "atmega32", 16000000},
                                           Image{"m32-direct", "m32-direct", "atmega32", 16000000},
                                           Image{"m1284", "m1284", "atmega1284p", 16000000},
                                           Image{"m16", "m16", "atmega16", 16000000},
                                           Image{"m16-8mhz", "m16", "atmega16", 8000000}),
                         [](const ::testing::TestParamInfo<Image>& info) {
                           std::string n = info.param.name;
                           for (char& c : n) c = c == '-' ? '_' : c;
                           return n;
                         });

TEST(Boot, PowerOnLeavesCoilsOffAndStepLinesLow) {
  sim::Machine uno(simtest::image("uno"));
  uno.run([&] { return uno.serial().banner_seen(); }, 16000000);
  ASSERT_NE(uno.latch(), nullptr);
  EXPECT_EQ(uno.latch()->outputs(), 0);  // shield: all bridge inputs low

  sim::Machine m32(simtest::image("m32"));
  const auto& step = m32.watch_pin('C', 0);
  m32.run([&] { return m32.serial().banner_seen(); }, 16000000);
  for (const sim::PinEdge& e : step) EXPECT_FALSE(e.level);
}

}  // namespace
